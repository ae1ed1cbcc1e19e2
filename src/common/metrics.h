// Whole-fluid measurements written to metrics.csv by the runner and used by tests and validation.
#pragma once

#include <string>

#include "particle_state.h"
#include "params.h"

namespace sph {

struct Metrics {
  double kinetic_energy = 0.0;      // sum 1/2 m v^2 [J]
  double density_error_mean = 0.0;  // mean |rho - rho0| / rho0 over fluid particles
  double density_error_max = 0.0;
  double v_max = 0.0;
  double front_x = 0.0;   // largest x of the fluid, ignoring the few most extreme particles (see .cpp)
  double top_y = 0.0;     // largest y of the fluid, same rule
  double height_at_x0 = 0.0;  // largest y of the fluid within h of the plane x = 0 (dam break column), same rule
  double momentum[3] = {0.0, 0.0, 0.0};
  long particles = 0;
};

Metrics measure(const SimConstants& c, const ParticleState& ps);

// Robust extreme: the k-th largest value with k = max(3, N / 1000), so a few stray particles do not
// count as the front of the fluid.
double robust_max(std::vector<float> values);

}  // namespace sph
