// Sums over a cubic lattice of spacing d [m] around a lattice point, over the points closer than h [m]: the
// bulk values set-up calibrates against (guided_creation.cpp: the kernel sum that sets the mass; springs.cpp:
// the bonds' sum r^2 that sets a spring's stiffness; cohesion_energy.cpp: a bulk particle's cohesive energy).
#pragma once

namespace sph {

// sum of f(r^2) over the lattice offsets (i, j, k) d with r^2 = (i^2 + j^2 + k^2) d^2 < h^2, the point itself
// (r^2 = 0) included, in a fixed order.
template <class F>
double lattice_sum(double d, double h, F f) {
  long n = 0;
  while (double(n) * d < h) ++n;
  double sum = 0.0;
  for (long k = -n; k <= n; ++k)
    for (long j = -n; j <= n; ++j)
      for (long i = -n; i <= n; ++i) {
        const double r2 = double(i * i + j * j + k * k) * d * d;
        if (r2 < h * h) sum += f(r2);
      }
  return sum;
}

}  // namespace sph
