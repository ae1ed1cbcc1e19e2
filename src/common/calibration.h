// Calibration of the particle model from physical inputs (thesis 4.1.5): the smoothing length from the
// neighbour count, the kernel's lattice sum that sets the particle mass, which kernel a run's density sums,
// and the cohesion constants that give a surface tension in N/m. Used by guided creation (guided_creation.h)
// and by the tests that check the calibrations.
#pragma once

#include "scene.h"

namespace sph {

// Support radius from the mean neighbour count, thesis eq. 4.1: h = cbrt(3 V n_avg / (4 pi N)), with
// V / N = d^3 for particles on a cubic lattice of spacing d.
double smoothing_length(double spacing, double neighbours);

// sum over the cubic lattice of spacing d of W(|x|, h), times d^3 (1 for a perfect quadrature), W Poly6 or
// the cubic spline: the density kernel of the run (params.h, density_cubic_spline). At h = 1.97 d: 1.0069 and 0.9991.
double lattice_density_factor(double spacing, double h, bool cubic_spline);

// Whether a fluid of the scene has a surface tension (fluids.N.surface_tension > 0), under either model.
inline bool any_surface_tension(const Scene& scene) {
  for (const FluidSpec& f : scene.fluids)
    if (f.surface_tension > 0.0) return true;
  return false;
}

// Whether a fluid of the scene has a surface tension and the scene gives it by the continuum surface force
// (sph.surface_tension = "csf"; surface_tension_csf.h).
inline bool csf_surface_tension(const Scene& scene) {
  return scene.surface_tension_model == SurfaceTensionModel::Csf && any_surface_tension(scene);
}

// Whether the scene is a free drop under the continuum surface force: a fluid with sigma under it, and no
// container, wall, obstacle, mesh or body and no interface tension. There the surface is closed and bounds
// nothing, so its force sums to zero (the drop's momentum is kept: surface_forces.h) and its area cannot go
// below a ball's (the energy budget: cohesion_energy.h).
inline bool csf_free_drop(const Scene& scene) {
  return csf_surface_tension(scene) && scene.boundaries.empty() && scene.meshes.empty() && scene.bodies.empty() &&
         scene.interface_tensions.empty();
}

// Whether the scene's WCSPH sums use the cubic spline (SimConstants::cubic_spline): when sph.kernel says
// "cubic_spline", and without the key when the continuum surface force acts. With the Poly6 density and
// Spiky's gradient (WCSPH's default pair) that force's drop held its pressure 15 to 32% above Laplace's
// 2 sigma / R, with one kernel within 10% (docs/results.md, "One kernel for WCSPH"; a set-up note says which).
inline bool wcsph_cubic_spline(const Scene& scene) {
  if (scene.solver != Solver::Wcsph) return false;
  if (scene.kernel_set) return scene.kernel == KernelPair::CubicSpline;
  return csf_surface_tension(scene);
}

// Whether the scene's DFSPH sums use Poly6 with Spiky (sph.kernel = "poly6_spiky" given; without the key DFSPH
// keeps [BK15]'s cubic spline; SimConstants::dfsph_poly6_spiky, dfsph.h).
inline bool dfsph_poly6_spiky(const Scene& scene) {
  return scene.solver == Solver::Dfsph && scene.kernel_set && scene.kernel == KernelPair::Poly6Spiky;
}

// Surface tension sigma [N/m] as cohesion between particles of one fluid (forces.h), with the cohesion kernel
// of Akinci, Akinci & Teschner 2013 (eq. 2, kernels.h: C(r) = 32 / (pi h^3) c(r / h)) as a pair force
// F_ab = -gamma m_a m_b C(r) x_ab / r, calibrated from sigma by the mean-field (Kirkwood-Buff) surface
// energy of a pair potential u with u'(r) = gamma m^2 C(r) in a fluid of number density n = rho0 / m:
// cutting the fluid costs sigma = -(pi / 2) n^2 int r^3 u dr = (pi / 8) n^2 int_0^h r^4 u'(r) dr
// = (pi / 8) rho0^2 gamma (32 / pi) h^2 J4, J4 = int_0^1 q^4 c(q) dq = 21 / 28160 (exact), so
// gamma = sigma / (4 rho0^2 h^2 J4) (Tartakovsky & Panchenko 2016 calibrate their pairwise force so).
// Returns the fluid's cohesion constant gamma 32 / (pi h^3) = 8 sigma / (pi rho0^2 h^5 J4) [m / (kg s^2)]:
// a_a = -constant sum_b m_b c(r / h) x_ab / r. Unlike Akinci's gamma, sigma carries its units: the force
// per particle does not change with the resolution or the mass, and a drop's Laplace pressure and
// oscillation period follow from sigma (tests/test_surface_tension.cpp).
double cohesion_from_surface_tension(double sigma, double rest_density, double h);

// The cohesion between particles of two different fluids a and b that gives their interface the tension
// sigma_ab [N/m], in the mean-field picture of cohesion_from_surface_tension: parting the two fluids costs
// the work W_ab = (pi / 4) rho0_a rho0_b K_ab h^5 J4 per area (the cohesion's 2 sigma with one fluid), and
// Dupre's relation sigma_ab = sigma_a + sigma_b - W_ab gives K_ab = 4 (sigma_a + sigma_b - sigma_ab) /
// (pi rho0_a rho0_b h^5 J4) [m / (kg s^2)]: a_a = -K_ab sum_b m_b c(r / h) x_ab / r, the pair force
// -K_ab m_a m_b c x_ab / r equal and opposite. sigma_ab = sigma_a + sigma_b: 0 (the fluids ignore each other);
// below it they attract, above it they repel.
double cross_cohesion(double sigma_a, double sigma_b, double sigma_ab, double rho_a, double rho_b, double h);

// The cohesion's internal pressure [Pa], the virial of the pair force in the bulk,
// (2 pi / 3) n^2 int r^3 u'(r) dr = (16 / 3) (J3 / J4) sigma / h = 8.23 sigma / h, J3 = 33 / 28672: the
// equation of state must hold it, so it compresses the fluid by about this / (rho0 c0^2).
double cohesion_pressure(double sigma, double h);

}  // namespace sph
