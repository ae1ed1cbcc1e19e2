// Guided creation (thesis 4.1.4 and 4.1.5): from the user's volumes, physical properties and resolution,
// derive the spacing, the smoothing length h from the mean neighbour count, the particle masses, the grid,
// and the initial particles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "boundary_particles.h"
#include "rigid_body.h"
#include "springs.h"
#include "emitters.h"
#include "particle_state.h"
#include "scene.h"

namespace sph {

struct Setup {
  SimConstants constants{};
  ParticleState particles;         // instant emitters plus the jets' prefilled inlets
  BoundaryParticles boundary;      // the walls' boundary particles (sph.walls = "particles"), else empty
  std::vector<MeshSolid> meshes;   // the scene's meshes, loaded, scaled and placed
  std::vector<RigidBody> bodies;   // the scene's rigid bodies at their start
  SpringNetwork springs;           // the elastic fluids' springs at the start (springs.h), else empty
  std::vector<JetEmitter> jets;
  double spacing = 0.0;            // d
  double h = 0.0;                  // support radius
  double lattice_density = 0.0;    // sum_b W over a cubic lattice of spacing d, times d^3 (lattice_density_factor)
  double max_speed_of_sound = 0.0;
  double viscous_rate = 0.0;       // lambda_max of the viscous operator [1/s] (viscous_limit.h)
  double spring_rate = 0.0;        // a bound on the springs' fastest angular frequency [1/s] (springs.h); 0: none
  double blowup_speed = 0.0;       // speeds above this stop the run
  double expected_particles = 0.0; // instant particles plus the jets' steady state
  int32_t next_id = 0;
  // What set-up found and did, one line each (fills, shared lattice points, particles removed from
  // solids): the runner prints them as "setup: ...".
  std::vector<std::string> report;
  bool adjusted = false;           // the checks changed what the scene asked for (refit, shared or removed points)
};

// Support radius from the mean neighbour count, thesis eq. 4.1: h = cbrt(3 V n_avg / (4 pi N)), with
// V / N = d^3 for particles on a cubic lattice of spacing d.
double smoothing_length(double spacing, double neighbours);

// sum over the cubic lattice of spacing d of W(|x|, h), times d^3 (1 for a perfect quadrature), W Poly6 or
// the cubic spline: the density kernel of the run (params.h, density_cubic_spline). At h = 1.97 d: 1.0069 and 0.9991.
double lattice_density_factor(double spacing, double h, bool cubic_spline);

// Whether the scene's WCSPH sums use the cubic spline (sph.kernel = cubic_spline; SimConstants::cubic_spline).
inline bool wcsph_cubic_spline(const Scene& scene) {
  return scene.solver == Solver::Wcsph && scene.kernel == KernelPair::CubicSpline;
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

// The speed bound when the energy check cannot give one (a user force doing work) [m/s]:
// limits.blowup_speed, or ten times the fastest of the speeds of sound and the jets (weakly compressible
// SPH assumes flow speeds well below c0).
double fallback_blowup_speed(const Scene& scene, double max_speed_of_sound, const std::vector<JetEmitter>& jets);

// Throws SceneError when the scene cannot be set up: an emitter holds no lattice point, a jet's inlet
// crosses a boundary, fluid lies in a solid with "on_overlap": "error", a derived quantity leaves single
// precision's range, the particles (counted before anything is allocated) exceed limits.max_particles or
// this machine's memory, the grid would be too large; a std::bad_alloc becomes "out of memory" with the
// estimate.
Setup create_setup(const Scene& scene, double run_time);

}  // namespace sph
