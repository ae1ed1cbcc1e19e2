// Whole-fluid measurements written to metrics.csv by the runner and used by tests and validation.
#pragma once

#include <array>
#include <string>

#include "particle_state.h"
#include "params.h"

namespace sph {

struct Metrics {
  double kinetic_energy = 0.0;      // sum 1/2 m v^2 [J]
  double potential_energy = 0.0;    // sum m (-g.x - phi_ref) [J], phi_ref the reference passed to measure()
  double density_error_mean = 0.0;  // mean |rho - rho0| / rho0 over fluid particles
  double density_error_max = 0.0;
  double v_max = 0.0;
  double front_x = 0.0;   // largest x of the fluid, ignoring the few most extreme particles (see .cpp)
  double top_y = 0.0;     // largest y of the fluid, same rule
  double height_at_x0 = 0.0;  // largest y of the fluid within h of the plane x = 0 (dam break column), same rule
  double momentum[3] = {0.0, 0.0, 0.0};
  long particles = 0;
  long outside_domain = 0;  // particles (inlet ones included) outside the domain of c.grid, or not finite
};

// Fluid particles only (a jet's inlet particles, age < 0, are moved kinematically and left out).
// potential_reference: the specific potential energy -g.x [J/kg] counted as zero, normally the lowest level
// the fluid can reach (Simulation::potential_reference()).
Metrics measure(const SimConstants& c, const ParticleState& ps, double potential_reference = 0.0);

// Depth of fluid [m] above `base` along -gravity, as a wave gauge reads it: the fluid's rest volume per
// unit horizontal area, averaged over a disc of radius R = 1.5 h about the vertical through base,
//   d = sum_j (m_j / rho0_j) W2(r_j),  W2(r) = 4 / (pi R^8) (R^2 - r^2)^3 for r < R (integral 1 over the plane),
// over fluid particles j at or above base (r_j their horizontal distance from the vertical). On a particle
// lattice the sum of W2 is within 0.3% of 1 wherever the gauge stands at R = 1.5 h (1.4% at R = h).
// Integrating the volume rather than finding a surface makes it independent of how the floor truncates a
// kernel, counts spray above a breaking wave as water, as a gauge's wetted length does, and reads 0 where
// dry. Needs gravity != 0 (the vertical); without it returns 0.
double probe_depth(const SimConstants& c, const ParticleState& ps, const std::array<double, 3>& base);

// Specific potential energy of gravity at x: phi = -g.x [J/kg] (g.h above the origin for g along -y).
// 1/2 m v^2 [J] of particle i (double precision: sums over millions of particles).
inline double particle_kinetic_energy(const SimConstants& c, const ParticleState& ps, std::size_t i) {
  const Vec3 v = ps.vel[i];
  return 0.5 * c.fluids[ps.fluid[i]].mass * (double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
}

inline double specific_potential(const SimConstants& c, Vec3 x) {
  return -(double(c.gravity.x) * x.x + double(c.gravity.y) * x.y + double(c.gravity.z) * x.z);
}

// The lowest specific potential energy the fluid can reach [J/kg], from the boundaries that bound it
// against gravity: a box container (its lowest corner), a plane, absorbing or not, whose normal points
// against gravity (within 0.1 degree), a sphere container (its lowest point). Fluid must satisfy all of
// them, so the highest of these floors is the one that holds. bounded = false when no shape bounds the
// fluid (it may fall for ever); without gravity the level is 0 and bounded.
struct PotentialFloor {
  double level = 0.0;
  bool bounded = true;
};
PotentialFloor lowest_reachable_potential(const SimConstants& c);

// Robust extreme: the k-th largest value with k = max(3, N / 1000), so a few stray particles do not
// count as the front of the fluid.
double robust_max(std::vector<float> values);

}  // namespace sph
