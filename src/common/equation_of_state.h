// Equations of state: pressure from density (thesis 2.2.2) and near pressure (thesis 3.1).
#pragma once

#include "params.h"
#include "sph_hd.h"

namespace sph {

// Tait [Monaghan 1994], thesis eq. 2.15: P = rho0 c0^2 / 7 ((rho / rho0)^7 - 1), with B = rho0 c0^2 / 7.
SPH_HD inline float tait_pressure(float rho, float rho0, float b) {
  const float r = rho / rho0;
  const float r2 = r * r;
  const float r7 = r2 * r2 * r2 * r;
  return b * (r7 - 1.0f);
}

// Ideal (Desbrun & Cani 1996), thesis eq. 2.14: P = c0^2 (rho - rho0).
SPH_HD inline float ideal_pressure(float rho, float rho0, float c0) { return c0 * c0 * (rho - rho0); }

// Near pressure for double density relaxation, thesis 3.1 (Clavet 2005): P_near = k_near rho_near >= 0,
// always repulsive, so particles cannot pull their neighbours into clusters.
SPH_HD inline float near_pressure(float rho_near, float k_near) { return k_near * rho_near; }

SPH_HD inline float equation_of_state(const SimConstants& c, const FluidConstants& f, float rho) {
  float p = c.eos == EquationOfState::Tait ? tait_pressure(rho, f.rest_density, f.tait_b)
                                           : ideal_pressure(rho, f.rest_density, f.speed_of_sound);
  if (c.clamp_negative_pressure && p < 0.0f) p = 0.0f;
  return p;
}

}  // namespace sph
