// The fluids' viscosity as an explicit non-pressure force of the incompressible solvers: WCSPH's forces loop
// (forces.h) without its pressure terms, its per-particle inputs, and the velocity update v += dt a. DFSPH
// (dfsph.h) takes all of its non-pressure forces through them; PBF (pbf.h) the laminar viscosity of the
// scene's sph.viscosity and, with pbf.artificial_viscosity, Monaghan's artificial viscosity (ViscousForces).
// Both sub-cycle them where their rate exceeds the explicit bound of a step (viscous_limit.h,
// viscous_substeps).
#pragma once

#include <cstdint>

#include "../common/params.h"
#include "../common/particle_view.h"
#include "../common/sph_hd.h"

namespace sph {

// The forces loop's per-particle inputs without a pressure (forces.h reads vel_inv_rho, and the pressure
// terms are compiled out by NonPressureForces and ViscousForces).
struct ForceInputsFn {
  ParticleView p;
  SPH_HD void operator()(int32_t i) const {
    p.vel_force[i] = p.vel[i];
    p.vel_inv_rho[i] = with_w(p.vel[i], 1.0f / p.density[i]);
    p.pressure_rho2[i] = 0.0f;
    p.near_pressure_rho2[i] = 0.0f;
  }
};

// v += dt a, the acceleration in acc ([BK15] algorithm 1, line 5, for DFSPH's non-pressure forces); inlet
// particles (age < 0) keep their velocity.
struct PredictVelocityFn {
  ParticleView p;
  float dt;
  SPH_HD void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) p.vel[i] += dt * p.acc[i];
  }
};

// Whether any viscosity acts on the fluids of c: the laminar one (sph.viscosity = mueller or morris, a fluid
// with mu > 0) or the artificial one (SimConstants::artificial_enabled; under PBF only with
// pbf.artificial_viscosity, guided_creation.cpp).
inline bool viscosity_acts(const SimConstants& c) {
  bool laminar = false;
  if (has_laminar_term(c.viscosity))
    for (int32_t f = 0; f < c.num_fluids; ++f) laminar = laminar || c.fluids[f].viscosity > 0.0f;
  return laminar || c.artificial_enabled != 0;
}

}  // namespace sph
