// The viscous time-step limit, derived from the discrete operator instead of the continuum rule of thumb
// dt <= 0.125 h^2 / nu (which let a cube at mu = 1000 Pa s shake apart in free fall: issue 10, item 6).
//
// With only viscosity acting, the Mueller and Morris terms of forces.h are linear in the velocities,
//   dv_a/dt = -sum_b w_ab (v_a - v_b),
//   Mueller (thesis eq. 2.24):  w_ab = mu_a m_b lap W(r) / (rho_a rho_b),       lap W = 45/(pi h^6) (h - r)
//   Morris 1997:                w_ab = (mu_a + mu_b) m_b |dW/dr| r / ((r^2 + eps^2) rho_a rho_b),  Spiky dW/dr,
// a weighted graph Laplacian. On an infinite cubic lattice of spacing d at its lattice density every Fourier
// mode v_b = exp(i k.x_b) is an eigenvector, with eigenvalue
//   lambda(k) = sum_b w_b (1 - cos k.x_b);
// its largest value over the Brillouin zone, lambda_max [1/s], is the fastest viscous rate of the scene.
// Host code, run once at set-up (and when the demo edits a viscosity).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "forces.h"
#include "kernels.h"
#include "params.h"

namespace sph {

// Explicit stability bound on lambda dt for pure viscous decay, the same for every integrator of
// integrate.h (the amplification of the mode must stay within [-1, 1]):
//   explicit and semi-implicit Euler, leapfrog (one kick with the forces of v_t): v' = (1 - lambda dt) v;
//   modified velocity Verlet (forces see v_half): v_half' = (1 - lambda dt) v_half;
//   velocity Verlet (kicks a_n dt/2 and a_{n+1} dt/2, forces of v_t): v_{n+1} = (1 - lambda dt/2) v_n
//     - (lambda dt/2) v_{n-1}, whose roots have product lambda dt/2: stable while lambda dt < 2.
constexpr double kViscousStabilityBound = 2.0;

// The pair weight w_b of the viscosity model for a neighbour at distance r, without the factor
// mu m / (rho_a rho_b) (Mueller) or mu m / (rho_a rho_b) with mu_a = mu_b = mu (Morris): the same
// expressions as pressure_viscosity_pair in forces.h.
// cubic: SimConstants::cubic_spline (the cubic spline's dW/dr in place of Spiky's).
inline double viscous_pair_kernel(ViscosityModel model, const KernelCoeffs& k, bool cubic, double r) {
  if (model == ViscosityModel::Mueller) return viscosity_laplacian(k, float(r));
  const double r2 = r * r;
  return 2.0 * -double(gradient_dwdr(k, cubic, float(r))) / r * r2 / (r2 + double(kPairEps2) * k.h2);
}

// A site's neighbours on the cubic lattice of unit spacing within h_over_d: the offset and a pair weight.
struct LatticeNeighbour {
  int x[3];
  double w;
};

// The neighbours with weight(r), r = |offset| in (0, h_over_d).
template <class Weight>
std::vector<LatticeNeighbour> lattice_neighbours(double h_over_d, Weight weight) {
  const int n = int(std::ceil(h_over_d));
  std::vector<LatticeNeighbour> nb;
  for (int l = -n; l <= n; ++l)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const double r = std::sqrt(double(i * i + j * j + l * l));
        if (r > 0.0 && r < h_over_d) nb.push_back(LatticeNeighbour{{i, j, l}, weight(r)});
      }
  return nb;
}

// max over wave vectors k of symbol(k). The lattice is symmetric under permutations and sign changes of the
// axes, so k is sampled on 0 <= k3 <= k2 <= k1 <= pi with 16 intervals per axis (the maxima of the
// operators here lie at the sampled corners (pi, pi, 0) and (pi, pi, pi)).
template <class Symbol>
double max_over_brillouin_zone(Symbol symbol) {
  const int samples = 16;
  const double pi = 3.14159265358979323846;
  double best = 0.0;
  for (int a = 0; a <= samples; ++a)
    for (int b = 0; b <= a; ++b)
      for (int c = 0; c <= b; ++c) {
        const double k[3] = {pi * a / samples, pi * b / samples, pi * c / samples};
        best = std::max(best, symbol(k));
      }
  return best;
}

// 1 - cos k.x_b for a neighbour's offset.
inline double lattice_phase_factor(const double k[3], const LatticeNeighbour& q) {
  return 1.0 - std::cos(k[0] * q.x[0] + k[1] * q.x[1] + k[2] * q.x[2]);
}

// max over k of sum_b K(r_b) (1 - cos k.x_b) over the cubic lattice of unit spacing, K the pair kernel of
// support h_over_d [units of 1/d^5].
inline double lattice_viscous_symbol(ViscosityModel model, bool cubic, double h_over_d) {
  const KernelCoeffs k = make_kernel_coeffs(h_over_d);
  const std::vector<LatticeNeighbour> nb =
      lattice_neighbours(h_over_d, [&](double r) { return viscous_pair_kernel(model, k, cubic, r); });
  return max_over_brillouin_zone([&](const double kv[3]) {
    double sum = 0.0;
    for (const LatticeNeighbour& q : nb) sum += q.w * lattice_phase_factor(kv, q);
    return sum;
  });
}

// lambda_max [1/s] of the scene's viscosity (0 for none or artificial viscosity, which the sound limit
// covers): particles of fluid a on the lattice of spacing d [m] at their lattice density
// rho_a = m_a lattice_density / d^3 (lattice_density: the density kernel's lattice sum, calibration.h), support
// h [m]. With w_b = mu m K(r_b / d) / (d^5 rho^2) this is lambda_a = mu_a d S / (m_a lattice_density^2),
// S the unit-lattice symbol; Morris pairs of different fluids use (mu_a + mu_max) / 2.
inline double viscous_rate(const SimConstants& c, double spacing, double h, double lattice_density) {
  if (c.viscosity != ViscosityModel::Mueller && c.viscosity != ViscosityModel::Morris) return 0.0;
  const double symbol = lattice_viscous_symbol(c.viscosity, c.cubic_spline != 0, h / spacing);
  double mu_max = 0.0;
  for (int32_t f = 0; f < c.num_fluids; ++f) mu_max = std::max(mu_max, double(c.fluids[f].viscosity));
  double rate = 0.0;
  for (int32_t f = 0; f < c.num_fluids; ++f) {
    const FluidConstants& fc = c.fluids[f];
    const double mu = c.viscosity == ViscosityModel::Mueller ? fc.viscosity : 0.5 * (fc.viscosity + mu_max);
    rate = std::max(rate, mu * spacing * symbol / (double(fc.mass) * lattice_density * lattice_density));
  }
  return rate;
}

// The largest eigenvalue of a symmetric 3 x 3 matrix (trigonometric solution of its characteristic cubic).
inline double largest_symmetric_eigenvalue(const double m[3][3]) {
  const double p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
  const double q = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
  const double p2 = (m[0][0] - q) * (m[0][0] - q) + (m[1][1] - q) * (m[1][1] - q) + (m[2][2] - q) * (m[2][2] - q) + 2.0 * p1;
  const double p = std::sqrt(p2 / 6.0);
  if (!(p > 0.0)) return q;
  double b[3][3];
  for (int u = 0; u < 3; ++u)
    for (int v = 0; v < 3; ++v) b[u][v] = (m[u][v] - (u == v ? q : 0.0)) / p;
  const double det = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                     b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
  const double phi = std::acos(std::max(-1.0, std::min(1.0, det / 2.0))) / 3.0;
  return q + 2.0 * p * std::cos(phi);
}

// Monaghan's artificial viscosity (forces.h, artificial_viscosity_pair), taken on every pair as if all
// approached (the term acts only on approaching pairs, so this bounds it from above): with it alone
//   dv_a/dt = -sum_b K_ab xhat_ab xhat_ab^T (v_a - v_b),
//   K_ab = alpha_ab cbar_ab h (m_b / rho_ab) r |dW/dr| / (r^2 + eps^2)   (Spiky dW/dr, or the cubic spline's),
// a graph Laplacian whose weights are 3 x 3 projections. On the unit cubic lattice its symbol at wave vector
// k is the matrix sum_b K_u(r_b) xhat_b xhat_b^T (1 - cos k.x_b), K_u = H r |dW_u/dr| / (r^2 + eps^2 H^2),
// H = h / d. This returns its largest eigenvalue over the Brillouin zone, sampled as lattice_viscous_symbol
// samples it [units of 1/d^4]. Measured against runs: DFSPH's resting column (hydrostatic_tank.json,
// alpha = 0.2, c0 = 15 m/s) blew up at steps of 2.6 ms, 2.1 times 2 / lambda_max, and ran at alpha = 0.1
// (docs/results.md).
inline double lattice_artificial_symbol(bool cubic, double h_over_d) {
  const KernelCoeffs k = make_kernel_coeffs(h_over_d);
  // K_u / r^2: the projection's x x^T carries r^2.
  const std::vector<LatticeNeighbour> nb = lattice_neighbours(h_over_d, [&](double r) {
    return h_over_d * r * -double(gradient_dwdr(k, cubic, float(r))) / (r * r + double(kPairEps2) * k.h2) / (r * r);
  });
  return max_over_brillouin_zone([&](const double kv[3]) {
    double m[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    for (const LatticeNeighbour& q : nb) {
      const double f = q.w * lattice_phase_factor(kv, q);
      for (int u = 0; u < 3; ++u)
        for (int v = 0; v < 3; ++v) m[u][v] += f * q.x[u] * q.x[v];
    }
    return largest_symmetric_eigenvalue(m);
  });
}

// lambda_max [1/s] of the artificial viscosity (0 where no fluid has one) for particles at their lattice
// density rho_a = m_a lattice_density / d^3 (as viscous_rate): lambda = S alpha_ab cbar_ab (2 m_b / (m_a +
// m_b)) / (lattice_density d), the largest over pairs of fluids, S = lattice_artificial_symbol(cubic, h / d).
// WCSPH's sound-speed step keeps below it (2 / lambda_max is 4.8 times 0.4 h / c0 at alpha = 0.2, h = 1.97
// d, the hydrostatic tank); DFSPH, whose steps have no sound limit, sub-cycles the viscosity instead (viscous_substeps).
inline double artificial_viscous_rate(const SimConstants& c, double spacing, double h, double lattice_density) {
  if (!c.artificial_enabled) return 0.0;
  const double symbol = lattice_artificial_symbol(c.cubic_spline != 0, h / spacing);
  double rate = 0.0;
  for (int32_t a = 0; a < c.num_fluids; ++a)
    for (int32_t b = 0; b < c.num_fluids; ++b) {
      const FluidConstants &fa = c.fluids[a], &fb = c.fluids[b];
      const double alpha = 0.5 * (double(fa.artificial_alpha) + double(fb.artificial_alpha));
      const double cbar = 0.5 * (double(fa.speed_of_sound) + double(fb.speed_of_sound));
      const double mass_ratio = 2.0 * double(fb.mass) / (double(fa.mass) + double(fb.mass));
      rate = std::max(rate, symbol * alpha * cbar * mass_ratio / (lattice_density * spacing));
    }
  return rate;
}

// Sub-steps that keep an explicit viscous update within its stability bound: the least n >= 1 with
// rate dt / n <= kViscousStabilityBound (rate [1/s], dt [s]).
inline int32_t viscous_substeps(double rate, double dt) {
  const double n = std::ceil(rate * dt / kViscousStabilityBound);
  return n > 1.0 ? int32_t(std::min(n, 1e6)) : 1;
}

}  // namespace sph
