// The weakly compressible SPH step (thesis chapters 2 and 3): its phases and their order, written once for
// every back end (issue 12, item 1). A back end supplies only an execution interface, Exec (see
// src/solvers/execution.h): how to run a loop over the particles, build the grid and drop expired
// particles; it holds no step order and no physics.
//
// The phase functors call the shared per-particle code of src/common/ and carry no SimConstants: C is the
// back end's trivially copyable reference to them (*c gives const SimConstants&), on cuda the GPU's
// __constant__ copy (src/cuda/device_constants.h).
#pragma once

#include <cstdint>

#include "../common/backend.h"
#include "../common/boundaries.h"
#include "../common/density.h"
#include "../common/forces.h"
#include "../common/integrate.h"
#include "../common/particle_view.h"
#include "../common/pressure.h"
#include "../common/sph_hd.h"
#include "../common/springs.h"
#include "rigid_bodies.h"
#include "surface_forces.h"

namespace sph {
namespace wcsph {

// ---- phase functors: f(i) for particle i -----------------------------------------------------------------

// The integrator's first half: move to where the forces are evaluated (integrate.h).
template <class C>
struct PredictFn {
  C c;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { predict_particle(*c, p, i, dt); }
};

// Density and near density (density.h). One functor per density method: on the GPU a kernel that held
// both (density_of's run-time switch) needed the registers of the larger and spilled under the bound.
// kBlocksPerSm: the occupancy target of issue 11 (density 64 registers: 4 blocks of 256 threads per SM),
// read by the cuda launch (src/cuda/device_launch.h), ignored elsewhere.
template <class C, bool kSummation>
struct DensityFn {
  static constexpr int kBlocksPerSm = 4;
  C c;
  GridView g;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { density_with<kSummation>(*c, g, p, i, dt); }
};

// Equation of state and the per-particle terms the forces read (pressure.h).
template <class C>
struct PressureFn {
  C c;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { pressure_of(*c, p, i); }
};

// Pressure, viscosity, surface tension and external forces under the force model Model (forces.h);
// forces 80 registers, 3 blocks per SM (issue 11).
template <class C, class Model>
struct ForcesFn {
  static constexpr int kBlocksPerSm = 3;
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { forces_with<Model>(*c, g, p, i); }
};

// The integrator's second half (integrate.h).
template <class C>
struct CorrectFn {
  C c;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { correct_particle(*c, p, i, dt); }
};

// Penalty boundaries, obstacles and absorbing planes (boundaries.h).
template <class C>
struct BoundariesFn {
  C c;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { boundaries_of(*c, p, i, dt); }
};

// Viscoelastic springs (springs.h): each particle's place under its id after the grid's reorder, then each
// particle's spring forces added to its acceleration (with its springs' plasticity and breaking).
struct IndexParticleFn {
  SpringView s;
  ParticleView p;
  SPH_HD void operator()(int32_t i) const { index_particle(s, p, i); }
};
template <class C>
struct SpringForcesFn {
  C c;
  SpringView s;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) p.acc[i] += spring_acceleration(*c, s, p, i, dt);
  }
};

// The springs' forces after a forces loop (either solver's): each particle's place under its id after the
// grid's reorder, then its spring forces, the rest lengths yielding over plastic_dt [s].
template <class Exec>
void spring_forces(Exec& x, float plastic_dt) {
  if (x.springs().capacity == 0) return;
  using C = typename Exec::Constants;
  x.for_each(IndexParticleFn{x.springs(), x.particles()});
  x.for_each(SpringForcesFn<C>{x.constants(), x.springs(), x.particles(), plastic_dt});
}

// Before the first forces: the forces see the integrator's velocity.
struct CopyVelocityFn {
  ParticleView p;
  SPH_HD void operator()(int32_t i) const { p.vel_force[i] = p.vel[i]; }
};

// ---- the step ---------------------------------------------------------------------------------------------

// Runs phase p of a WCSPH step (one of kStepPhases, backend.h, which is their order) on the back end's Exec.
template <class Exec>
void run_phase(Exec& x, Phase p, float dt) {
  using C = typename Exec::Constants;
  const SimConstants& c = x.host_constants();
  switch (p) {
    case Phase::Predict: x.for_each(PredictFn<C>{x.constants(), x.particles(), dt}); return;
    case Phase::BuildGrid: x.build_grid(); return;  // sort by cell, reorder every array, tables and lists
    case Phase::Density:
      if (c.density == DensityMethod::Summation)
        x.for_each(DensityFn<C, true>{x.constants(), x.grid(), x.particles(), dt});
      else
        x.for_each(DensityFn<C, false>{x.constants(), x.grid(), x.particles(), dt});
      return;
    case Phase::Pressure: x.for_each(PressureFn<C>{x.constants(), x.particles()}); return;
    case Phase::Forces:
      with_force_model(c, [&](auto model) {
        x.for_each(ForcesFn<C, decltype(model)>{x.constants(), x.grid(), x.particles()});
        if (x.grid().num_bodies > 0) x.for_each(BodyForcesFn<C, decltype(model)>{x.constants(), x.grid(), x.particles()});
      });
      continuum_surface_force(x);  // surface_forces.h
      interface_cohesion_forces(x);
      spring_forces(x, dt);
      update_bodies(x, dt);  // rigid bodies: the reaction to these forces moves them (rigid_bodies.h)
      return;
    case Phase::Correct: x.for_each(CorrectFn<C>{x.constants(), x.particles(), dt}); return;
    case Phase::Boundaries:
      if (c.num_shapes > 0) x.for_each(BoundariesFn<C>{x.constants(), x.particles(), dt});
      if (x.grid().boundary.n > 0 || x.grid().num_bodies > 0)
        x.for_each(BoundaryParticleCollisionFn{x.grid(), x.particles(), c.kernel.h2});
      return;
    case Phase::Recycle: x.recycle(); return;  // particles past their lifetime or absorbed leave
    default: return;  // not a phase of a WCSPH step: the back ends refuse it before
  }
}

// The accelerations of an uploaded state, without moving it: what a step's first forces need.
template <class Exec>
void initialise(Exec& x) {
  x.for_each(CopyVelocityFn{x.particles()});
  run_phase(x, Phase::BuildGrid, 0.0f);
  run_phase(x, Phase::Density, 0.0f);
  run_phase(x, Phase::Pressure, 0.0f);
  run_phase(x, Phase::Forces, 0.0f);
}

}  // namespace wcsph
}  // namespace sph
