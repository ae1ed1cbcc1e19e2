// Equations of state: pressure from density (thesis 2.2.2) and near pressure (thesis 3.1).
#pragma once

#include <cmath>

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

// A pressure over rho^2 from 1 / rho, as the symmetric pressure term (thesis eq. 2.18) takes it. Computed once
// per particle by the pressure phase (pressure.h), and per ghost by the forces, with its own pressure.
SPH_HD inline float over_rho2(float pressure, float inv_rho) { return pressure * inv_rho * inv_rho; }

SPH_HD inline float equation_of_state(const SimConstants& c, const FluidConstants& f, float rho) {
  float p = c.eos == EquationOfState::Tait ? tait_pressure(rho, f.rest_density, f.tait_b)
                                           : ideal_pressure(rho, f.rest_density, f.speed_of_sound);
  if (c.clamp_negative_pressure && p < 0.0f) p = 0.0f;
  return p;
}

// Internal (elastic) energy per kilogram stored at density rho [J/kg]: u = int_rho0^rho P(r) / r^2 dr, the
// work the pressure does when the fluid returns to rest density, so that kinetic + potential + internal
// energy is what an energy-conserving SPH scheme conserves [Monaghan 2005, "Smoothed particle
// hydrodynamics", sec. 2.6]. u >= 0 and zero at rho0; below rho0 zero when negative pressure is clamped.
// With r = rho / rho0: Tait u = (B / rho0) (r^6 / 6 + 1 / r - 7 / 6); ideal u = c0^2 (ln r + 1 / r - 1).
// Host code in double (the energy budget); the near pressure's share is near_internal_energy().
inline double specific_internal_energy(const SimConstants& c, const FluidConstants& f, double rho) {
  if (!(rho > 0.0)) return 0.0;
  const double r = rho / f.rest_density;
  if (c.clamp_negative_pressure && r < 1.0) return 0.0;
  if (c.eos == EquationOfState::Tait) {
    const double r2 = r * r;
    return double(f.tait_b) / f.rest_density * (r2 * r2 * r2 / 6.0 + 1.0 / r - 7.0 / 6.0);
  }
  const double c0 = f.speed_of_sound;
  return c0 * c0 * (std::log(r) + 1.0 / r - 1.0);
}

// Internal energy per kilogram of the near pressure, u = k_near rho_near^2 / (2 rho^2): the force
// -m_b (Pn_a / rho_a^2 + Pn_b / rho_b^2) grad W_near is minus the gradient of sum_a m_a u_a with
// du / d rho_near = P_near / rho^2, rho held fixed (thesis 3.1 with the symmetric form of eq. 2.18).
inline double near_internal_energy(const FluidConstants& f, double rho_near, double rho) {
  if (!(rho > 0.0)) return 0.0;
  return 0.5 * double(f.near_stiffness) * rho_near * rho_near / (rho * rho);
}

}  // namespace sph
