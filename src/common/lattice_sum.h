// Sums over a cubic lattice of spacing d [m] around a lattice point, over the points closer than h [m]: the
// bulk values set-up calibrates against (guided_creation.cpp: the kernel sum that sets the mass; springs.cpp:
// the bonds' moments that set the springs' stiffness; cohesion_energy.cpp: a bulk particle's cohesive energy).
#pragma once

namespace sph {

// Calls g(i, j, k, r^2) for the lattice offsets (i, j, k) d with r^2 = (i^2 + j^2 + k^2) d^2 < h^2, the point
// itself (r^2 = 0) included, in a fixed order; returns the sum of what g returns.
template <class G>
double sum_over_lattice(double d, double h, G g) {
  long n = 0;
  while (double(n) * d < h) ++n;
  double sum = 0.0;
  for (long k = -n; k <= n; ++k)
    for (long j = -n; j <= n; ++j)
      for (long i = -n; i <= n; ++i) {
        const double r2 = double(i * i + j * j + k * k) * d * d;
        if (r2 < h * h) sum += g(i, j, k, r2);
      }
  return sum;
}

// sum of f(r^2) over those offsets.
template <class F>
double lattice_sum(double d, double h, F f) {
  return sum_over_lattice(d, h, [&](long, long, long, double r2) { return f(r2); });
}

// sum of f(x, y, z) over the same offsets (x, y, z) = (i, j, k) d, in the same order.
template <class F>
double lattice_sum_xyz(double d, double h, F f) {
  return sum_over_lattice(d, h, [&](long i, long j, long k, double) { return f(double(i) * d, double(j) * d, double(k) * d); });
}

// The binding of two half-lattices: the sum of f(r^2) over the pairs (a, b) with a in one column of the upper
// half (layers at (k + 1/2) d, k >= 0) and b anywhere in the lower half (layers at -(l + 1/2) d), r^2 < h^2.
// Times the pair potential's scale and over d^2 it is the work per area to pull the halves apart
// (cohesion_energy.cpp: the calibration of the adhesion against the cohesion). first_layer_only: a only in
// the layer next to the lower half (k = 0), the binding of one particle there.
template <class F>
double half_lattice_binding(double d, double h, F f, bool first_layer_only = false) {
  long n = 0;
  while (double(n) * d < h) ++n;
  double sum = 0.0;
  for (long k = 0; k <= (first_layer_only ? 0 : n); ++k)
    for (long l = 0; l <= n; ++l)
      for (long j = -n; j <= n; ++j)
        for (long i = -n; i <= n; ++i) {
          const double dy = double(k + l + 1) * d;
          const double r2 = double(i * i + j * j) * d * d + dy * dy;
          if (r2 < h * h) sum += f(r2);
        }
  return sum;
}

}  // namespace sph
