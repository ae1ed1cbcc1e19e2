// Phase "pressure": equation of state and near pressure of one particle.
#pragma once

#include "equation_of_state.h"
#include "particle_view.h"

namespace sph {

SPH_HD inline void pressure_of(const SimConstants& c, const ParticleView& p, int32_t a) {
  const FluidConstants& f = c.fluids[p.fluid[a]];
  p.pressure[a] = equation_of_state(c, f, p.density[a]);
  p.near_pressure[a] = c.near_enabled ? near_pressure(p.near_density[a], f.near_stiffness) : 0.0f;
}

}  // namespace sph
