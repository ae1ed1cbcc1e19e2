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
inline double viscous_pair_kernel(ViscosityModel model, const KernelCoeffs& k, double r) {
  if (model == ViscosityModel::Mueller) return viscosity_laplacian(k, float(r));
  const double r2 = r * r;
  return 2.0 * -double(spiky_dwdr(k, float(r))) / r * r2 / (r2 + double(kPairEps2) * k.h2);
}

// max over k of sum_b K(r_b) (1 - cos k.x_b) over the cubic lattice of unit spacing, K the pair kernel of
// support h_over_d [units of 1/d^5]. The lattice is symmetric under permutations and sign changes of the
// axes, so k is sampled on 0 <= k3 <= k2 <= k1 <= pi with 16 intervals per axis (the maxima of the
// Mueller and Morris kernels lie at the sampled corners (pi, pi, 0) and (pi, pi, pi)).
inline double lattice_viscous_symbol(ViscosityModel model, double h_over_d) {
  const KernelCoeffs k = make_kernel_coeffs(h_over_d);
  const int n = int(std::ceil(h_over_d));
  struct Neighbour {
    int i, j, l;
    double w;
  };
  std::vector<Neighbour> nb;
  for (int l = -n; l <= n; ++l)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const double r = std::sqrt(double(i * i + j * j + l * l));
        if (r > 0.0 && r < h_over_d) nb.push_back(Neighbour{i, j, l, viscous_pair_kernel(model, k, r)});
      }
  const int samples = 16;
  const double pi = 3.14159265358979323846;
  double best = 0.0;
  for (int a = 0; a <= samples; ++a)
    for (int b = 0; b <= a; ++b)
      for (int c = 0; c <= b; ++c) {
        const double k1 = pi * a / samples, k2 = pi * b / samples, k3 = pi * c / samples;
        double sum = 0.0;
        for (const Neighbour& q : nb) sum += q.w * (1.0 - std::cos(k1 * q.i + k2 * q.j + k3 * q.l));
        best = std::max(best, sum);
      }
  return best;
}

// lambda_max [1/s] of the scene's viscosity (0 for none or artificial viscosity, which the sound limit
// covers): particles of fluid a on the lattice of spacing d [m] at their lattice density
// rho_a = m_a lattice_density / d^3 (lattice_density: the Poly6 lattice sum of guided_creation.h), support
// h [m]. With w_b = mu m K(r_b / d) / (d^5 rho^2) this is lambda_a = mu_a d S / (m_a lattice_density^2),
// S the unit-lattice symbol; Morris pairs of different fluids use (mu_a + mu_max) / 2.
inline double viscous_rate(const SimConstants& c, double spacing, double h, double lattice_density) {
  if (c.viscosity != ViscosityModel::Mueller && c.viscosity != ViscosityModel::Morris) return 0.0;
  const double symbol = lattice_viscous_symbol(c.viscosity, h / spacing);
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

}  // namespace sph
