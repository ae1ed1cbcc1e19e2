// Phase "pressure": equation of state and near pressure of one particle, and the per-particle quotients the
// forces' pair terms use (1 / rho, P / rho^2, P_near / rho^2), so that the pair loop does not divide by a
// density (issue 11, item 4); 1 / rho goes with the velocity the forces see, one record per particle.
#pragma once

#include "equation_of_state.h"
#include "particle_view.h"

namespace sph {

SPH_HD inline void pressure_of(const SimConstants& c, const ParticleView& p, int32_t a) {
  const FluidConstants& f = c.fluids[p.fluid[a]];
  const float pressure = equation_of_state(c, f, p.density[a]);
  const float near = c.near_enabled ? near_pressure(p.near_density[a], f.near_stiffness) : 0.0f;
  const float inv_rho = 1.0f / p.density[a];
  p.pressure[a] = pressure;
  p.near_pressure[a] = near;
  p.vel_inv_rho[a] = with_w(p.vel_force[a], inv_rho);
  p.pressure_rho2[a] = over_rho2(pressure, inv_rho);
  p.near_pressure_rho2[a] = over_rho2(near, inv_rho);
}

}  // namespace sph
