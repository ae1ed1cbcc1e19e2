// Divergence-free SPH [BK15] (Bender & Koschier 2015; seed 000 reproduces it): its phases and their order,
// written once for every back end over the execution interface (src/solvers/execution.h). The per-particle
// formulas are src/common/dfsph.h's; the non-pressure forces are WCSPH's forces without their pressure term
// (forces.h, NonPressureForces), so viscosity, surface tension, gravity and the user force are shared.
//
// A step ([BK15] algorithm 1; the order is kDfsphPhases in backend.h). The paper's loop is entered at its
// neighbourhood update, so that a step needs nothing computed by the one before (an upload, a restart or a
// jet's new particles start a step like any other):
//   build_grid, density: the grid, rho (seed eq. 7) and alpha (eq. 9) at the current positions
//   divergence_solve: correct v until D rho / Dt = 0 on average (algorithm 2)
//   forces:           a = non-pressure acceleration
//   predict:          v* = v + dt a
//   density_solve:    correct v* until the predicted density rho* = rho + dt D rho / Dt is at rest density
//                     on average (algorithm 3)
//   correct:          x += dt v*
//   boundaries:       the scene's shapes (penalty walls, obstacles)
//   recycle
// dt is the driver's (Simulation::advance: the CFL step, seed eq. 3, from the speeds this step leaves).
//
// Both solves are a projected, under-relaxed Jacobi iteration for "no compression, no negative pressure"
// (ErrorFn): each particle's total stiffness moves by half the paper's kappa (either sign) and never below 0,
// so a particle with more pressure than it needs (after a warm start from a faster step, at a free surface)
// loses it, and none ever pulls. They warm-start from the last step's pressures ([BK15] section 4.3), kept
// per particle in the fields pressure (rho kappa, [Pa]) and near_pressure (rho kappa_v dt, [Pa s]), which
// survive the grid's reorder and do not depend on dt; a warm start carries all of them or a share
// (warm_start_fraction). The iteration is accelerated by Chebyshev's
// semi-iterative method ([Wan15], dfsph.chebyshev; solve() below): on the 16k dam break and a resting column
// it needs half the iterations or fewer (docs/results.md). Convergence: the mean residual, one deterministic
// reduction (reduction.h) per check, every check_every iterations after the minimum, the same on every back
// end; a solve that reaches max_iterations above its tolerance is flagged (SolverStats::*_capped) for the
// run's metrics and summary.
#pragma once

#include <cstdint>

#include "../common/backend.h"
#include "../common/dfsph.h"
#include "../common/forces.h"
#include "../common/particle_view.h"
#include "../common/sph_hd.h"
#include "../common/viscous_limit.h"
#include "chebyshev.h"
#include "reduction.h"
#include "wcsph.h"
#include "surface_forces.h"
#include "viscous_forces.h"

namespace sph {
namespace dfsph {

// x += dt v (algorithm 1, line 8), after XSPH's correction where enabled (as WCSPH's correct: integrate.h);
// pos_start records where the step started, for the shapes' segment test (boundaries.h).
template <class C>
struct AdvectFn {
  C c;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    p.pos_start[i] = p.pos[i];
    if (p.age[i] >= 0.0f && (*c).xsph_enabled) p.vel[i] += p.xsph_dv[i];
    p.pos[i] += dt * p.vel[i];
    p.age[i] += dt;
  }
};

// rho_i (seed eq. 7), then alpha_i (eq. 9), which reads rho_i only of the particle's own, and whether its
// neighbourhood is full enough for the divergence solve (dfsph_support).
template <class C>
struct DensityAlphaFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    p.density[i] = dfsph_density(*c, g, p, i);
    p.alpha[i] = dfsph_alpha(*c, g, p, i);
    p.support[i] = dfsph_support(*c, g, p, i);
  }
};

// The warm start ([BK15] section 4.3): the share `fraction` (DfsphConstants::warm_start_fraction, which says
// why not all) of the pressure the last step's solve ended with, kept scaled so, and kappa = P / rho (density
// solver, scale = 1) or kappa_v = P_v / (rho dt) (divergence solver, scale = 1 / dt). With warm_start off,
// kappa = 0. Inlet particles get none.
// The divergence solve (divergence true) gives a particle without support (p.support == 0) no pressure, and so
// none to start from either: kept from a step in which it had support, the divergence pressure was applied
// again at every later step (its corrections are 0, so nothing released it), and a cube's face layer under
// the continuum surface force, once apart from the bulk, kept accelerating outward (measured).
struct WarmStartFn {
  ParticleView p;
  float* kept;  // p.pressure or p.near_pressure
  float scale;
  int32_t warm;
  float fraction;
  bool divergence;
  SPH_HD void operator()(int32_t i) const {
    if (!warm || p.age[i] < 0.0f || (divergence && p.support[i] == 0)) kept[i] = 0.0f;
    kept[i] *= fraction;
    p.kappa[i] = kept[i] * scale / p.density[i];
  }
};

// The residual of one particle and its next correction. Density solver (kDensity): the predicted excess
// rho* - rho0 (seed eq. 10) gives the paper's kappa = (rho* - rho0) alpha / dt^2 (eq. 14); divergence solver:
// D rho / Dt gives kappa_v = (D rho / Dt) alpha / dt (eq. 19), zero where the particle lacks support
// (p.support == 0: a splash or a surface particle, whose rate is not a divergence of the fluid, as
// SPlisHSPlasH does). The particle's total stiffness, kept[i] scale / rho_i (warm start included), moves by
// kDfsphRelaxation times that and is clamped at 0; kappa[i] is the change made. The residual is |excess|
// where pressure is left and the compression max(excess, 0) where there is none, over rho0 (times dt for
// the divergence), whose mean the solve drives below its tolerance.
// Why half a step: with the full step (the paper's Jacobi) corrections of either sign diverged in a resting
// column within 30 steps; corrections of one sign (compression only, SPlisHSPlasH) converge but cannot take
// back pressure once given, so a warm-started column was pushed apart, and without the warm start it could
// not take steps above 2.5 ms (measured, tests/test_solvers.cpp's column).
template <class C, bool kDensity>
struct ErrorFn {
  C c;
  GridView g;
  ParticleView p;
  float dt;
  const float* kept;
  float scale;
  float omega;  // Chebyshev weight ([Wan15]); 1: plain Jacobi
  float* prev;  // the total stiffness one iteration back, written with this one's (scratch: p.lambda)
  SPH_KERNEL_FN void operator()(int32_t i) const {
    const float rest = (*c).fluids[p.fluid[i]].rest_density;
    if (p.age[i] < 0.0f) {
      p.kappa[i] = 0.0f;
      p.solver_error[i] = 0.0f;
      return;
    }
    const float rate = dfsph_density_rate(*c, g, p, p.vel, i);
    float excess = kDensity ? dfsph_predicted_density(p.density[i], rate, dt) - rest : rate;
    if (!kDensity && p.support[i] == 0) excess = 0.0f;
    const float increment = kDfsphRelaxation * (kDensity ? dfsph_density_stiffness(rest + excess, rest, p.alpha[i], dt)
                                               : dfsph_divergence_stiffness(excess, p.alpha[i], dt));
    const float total = kept[i] * scale / p.density[i];
    // [Wan15]: the Jacobi iterate total + increment, extrapolated from the one before (prev) by omega.
    float next = chebyshev_extrapolate(total + increment, prev[i], omega);
    prev[i] = total;
    next = next > 0.0f ? next : 0.0f;
    p.kappa[i] = next - total;
    const float residual = next > 0.0f ? fabsf(excess) : (excess > 0.0f ? excess : 0.0f);
    p.solver_error[i] = residual * (kDensity ? 1.0f : dt) / rest;
  }
};

// v += dt a(kappa) (seed eqs. 15-17) and the pressure kept for the next warm start: kept += rho kappa * keep
// (keep = 1: P; keep = dt: P_v dt). Inlet particles are moved by their inlet, not by the solve.
template <class C>
struct ApplyFn {
  C c;
  GridView g;
  ParticleView p;
  float dt;
  float* kept;
  float keep;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] < 0.0f) return;
    p.vel[i] += dt * dfsph_pressure_acceleration(*c, g, p, p.kappa, i);
    kept[i] += keep * p.density[i] * p.kappa[i];
  }
};

// a += the hydrostatic part of the walls' and bodies' pressure (dfsph.h, dfsph_boundary_hydrostatic), in the
// forces phase: it does not depend on the solves' stiffnesses.
template <class C>
struct BoundaryHydrostaticFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) p.acc[i] += dfsph_boundary_hydrostatic(*c, g, p, i);
  }
};

// Component `component` (0-2: force x, y, z [N]; 3-5: torque [N m]) of what fluid particle i did to body `body`
// this step: the reaction to its non-pressure forces from the body's particles (friction; forces.h,
// body_reaction), to the hydrostatic part of their pressure (dfsph.h) and to what both pressure solves applied
// through them (dfsph.h, dfsph_body_reaction, with
// the stiffnesses kept: kappa = P / rho for the density solve, kappa_v = P_v dt / (rho dt) for the divergence
// solve).
template <class C>
struct BodyReactionFn {
  C c;
  GridView g;
  ParticleView p;
  int32_t body;
  int32_t component;
  float dt;
  SPH_KERNEL_FN double operator()(int32_t i) const {
    Vec3 force, torque, f, t;
    body_reaction<NonPressureForces>(*c, g, p, i, body, force, torque);
    dfsph_body_hydrostatic_reaction(*c, g, p, i, body, f, t);
    force += f, torque += t;
    dfsph_body_reaction(*c, g, p, p.pressure[i] / p.density[i], i, body, f, t);
    force += f, torque += t;
    if ((*c).dfsph.divergence_solver) {
      dfsph_body_reaction(*c, g, p, p.near_pressure[i] / (dt * p.density[i]), i, body, f, t);
      force += f, torque += t;
    }
    return wrench_component(force, torque, component);
  }
};

// One of the two solves ([BK15] algorithms 2 and 3): warm start, then corrections until the mean residual is
// within tolerance (checked every check_every iterations once min_iterations are done) or max_iterations.
// Returns the iterations; error: the mean error the solve ended at; capped: it stopped at the cap above tolerance.
template <class Exec, bool kDensity>
int32_t solve(Exec& x, float dt, double& error, bool& capped) {
  using C = typename Exec::Constants;
  const SimConstants& c = x.host_constants();
  const DfsphConstants& s = c.dfsph;
  const ParticleView p = x.particles();
  float* kept = kDensity ? p.pressure : p.near_pressure;
  const float keep = kDensity ? 1.0f : dt;
  const float tolerance = kDensity ? s.density_tolerance : s.divergence_tolerance;
  const int32_t min_iterations = kDensity ? s.min_iterations : 1;
  const int32_t n = p.n;
  x.for_each(WarmStartFn{p, kept, kDensity ? 1.0f : 1.0f / dt, s.warm_start, s.warm_start_fraction, !kDensity});
  if (s.warm_start) x.for_each(ApplyFn<C>{x.constants(), x.grid(), p, dt, kept, 0.0f});  // kept as it is
  // [Wan15]'s weights (chebyshev.h). With the projection at 0 the iteration is not linear, so a check whose
  // mean residual grew restarts the weights at 1 (this iteration's corrections recomputed as plain Jacobi):
  // without the restart a resting column at 2.6 ms steps blew up within 0.14 s, with it ran 1 s (measured,
  // rho = 0.9).
  const float rho = s.chebyshev;
  float omega = 1.0f;
  const auto corrections = [&]() {
    x.for_each(ErrorFn<C, kDensity>{x.constants(), x.grid(), p, dt, kept, kDensity ? 1.0f : 1.0f / dt, omega, p.lambda});
  };
  corrections();
  error = mean_of(x, p.solver_error, n);
  int32_t it = 0;
  while (it < s.max_iterations && (it < min_iterations || error > double(tolerance))) {
    x.for_each(ApplyFn<C>{x.constants(), x.grid(), p, dt, kept, keep});
    if (rho > 0.0f) omega = chebyshev_next_weight(rho, omega);
    corrections();
    ++it;
    if (it >= min_iterations && (it % s.check_every == 0 || it == s.max_iterations)) {
      const double before = error;
      error = mean_of(x, p.solver_error, n);
      if (omega != 1.0f && error > before) {
        omega = 1.0f;
        corrections();
      }
    }
  }
  capped = it == s.max_iterations && error > double(tolerance);
  return it;
}

// The non-pressure forces of the current positions and velocities into acc. plastic_dt [s]: the time over
// which the springs' rest lengths yield (springs.h), the step's dt once per step and 0 in the viscous
// sub-steps, which recompute the forces at the same positions.
template <class Exec>
void non_pressure_forces(Exec& x, float plastic_dt) {
  using C = typename Exec::Constants;
  x.for_each(ForceInputsFn{x.particles()});
  x.for_each(wcsph::ForcesFn<C, NonPressureForces>{x.constants(), x.grid(), x.particles()});
  if (x.grid().num_bodies > 0) x.for_each(BodyForcesFn<C, NonPressureForces>{x.constants(), x.grid(), x.particles()});
  if (x.grid().boundary.n > 0 || x.grid().num_bodies > 0)
    x.for_each(BoundaryHydrostaticFn<C>{x.constants(), x.grid(), x.particles()});
  continuum_surface_force(x);  // surface_forces.h
  interface_cohesion_forces(x);
  wcsph::spring_forces(x, plastic_dt);  // viscoelastic springs (springs.h), as in WCSPH's forces
}

// Runs phase ph of a DFSPH step (one of kDfsphPhases) on the back end's Exec; the solves record what they
// did in stats.
template <class Exec>
void run_phase(Exec& x, Phase ph, float dt, SolverStats& stats) {
  using C = typename Exec::Constants;
  const SimConstants& c = x.host_constants();
  switch (ph) {
    case Phase::Forces: non_pressure_forces(x, dt); return;
    case Phase::Predict: {
      // The non-pressure forces are explicit. The artificial viscosity's rate (scaled by c0, which no
      // DFSPH step is limited by) can exceed 2 / dt at large steps: the resting column at 2.6 ms, alpha 0.2,
      // blew up within 0.17 s. Sub-cycled then: n updates v += (dt / n) a(v), the forces recomputed
      // between them at the same positions, n from both viscosities' rates (SimConstants::substep_rate;
      // viscous_limit.h, viscous_substeps); n = 1 below their bound, the same bits as without.
      // A rigid body's reaction is still taken once, after the density solve (BodyReactionFn).
      const int32_t n = viscous_substeps(double(c.substep_rate), double(dt));
      for (int32_t k = 1; k < n; ++k) {
        x.for_each(PredictVelocityFn{x.particles(), dt / float(n)});
        non_pressure_forces(x, 0.0f);
      }
      x.for_each(PredictVelocityFn{x.particles(), dt / float(n)});
      stats.viscous_substeps = n;
      return;
    }
    case Phase::DensitySolve:
      stats.density_iterations = solve<Exec, true>(x, dt, stats.density_error, stats.density_capped);
      // Rigid bodies: moved by what the fluid did to them this step, before the fluid moves (Correct).
      update_bodies_with(x, dt, [&](int32_t body, int32_t component) {
        return BodyReactionFn<C>{x.constants(), x.grid(), x.particles(), body, component, dt};
      });
      return;
    case Phase::Correct: x.for_each(AdvectFn<C>{x.constants(), x.particles(), dt}); return;
    case Phase::Boundaries:
      if (c.num_shapes > 0) x.for_each(wcsph::BoundariesFn<C>{x.constants(), x.particles(), dt});
      if (x.grid().boundary.n > 0 || x.grid().num_bodies > 0)
        x.for_each(BoundaryParticleCollisionFn{x.grid(), x.particles(), c.kernel.h2});
      return;
    case Phase::BuildGrid: x.build_grid(); return;
    case Phase::Density: x.for_each(DensityAlphaFn<C>{x.constants(), x.grid(), x.particles()}); return;
    case Phase::DivergenceSolve:
      stats.divergence_iterations = 0;
      stats.divergence_error = 0.0;
      stats.divergence_capped = false;
      if (c.dfsph.divergence_solver)
        stats.divergence_iterations = solve<Exec, false>(x, dt, stats.divergence_error, stats.divergence_capped);
      return;
    case Phase::Recycle: x.recycle(); return;
    default: return;  // not a phase of a DFSPH step: the back ends refuse it before
  }
}

// Densities and alpha factors of an uploaded state, for its first metrics (a step computes its own).
template <class Exec>
void initialise(Exec& x) {
  SolverStats unused;
  run_phase(x, Phase::BuildGrid, 0.0f, unused);
  run_phase(x, Phase::Density, 0.0f, unused);
}

}  // namespace dfsph
}  // namespace sph
