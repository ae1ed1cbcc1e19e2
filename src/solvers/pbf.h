// Position Based Fluids [MM13] (Macklin & Mueller 2013; seed 002 describes the position-based pressure
// solver): its phases and their order, written once for every back end over the execution interface
// (src/solvers/execution.h). The per-particle formulas are src/common/pbf.h's.
//
// A step ([MM13] algorithm 1; the order is kPbfPhases in backend.h):
//   predict:          v += dt a_ext (gravity, the user force, the viscoelastic springs at x); x* = x + dt v,
//                     then the scene's shapes, and half a spacing off mirror walls
//   build_grid:       the grid on x*, kept through the iterations (the paper finds neighbours once a step)
//   constraint_solve: iterations of density rho(x*), lambda (eqs. 8-11), Delta p (eq. 14, with s_corr),
//                     x* += w Delta p (Chebyshev-extrapolated) and the shapes and walls again; a last
//                     density for the error and what follows
//   correct:          v = (x* - x) / dt
//   forces:           vorticity confinement (eqs. 15, 16), the continuum surface force, XSPH (eq. 17) and the
//                     fluids' viscosity (apply_viscosity) on v
//   recycle
// The old position x is pos_start (the shapes test the segment x -> x*). The neighbours are the pairs the grid
// phase selected at x*, evaluated at the current positions (for_each_pbf_pair, src/common/pbf.h).
// Each iteration is Jacobi: every lambda from the same positions, then every Delta p from the same lambdas,
// applied with the weight pbf.jacobi_weight and accelerated by Chebyshev's weights (pbf.chebyshev, [Wan15]):
// together they keep the iteration from amplifying the short density waves that made the plain one rattle at
// rest, and carry the floor's push farther up a column in the same iterations (docs/results.md, issue 12).
// With pbf.coarse_grid the first density is followed by a coarse-grid projection of the compression
// (pbf_coarse.h), which carries the correction across the fluid at once, and the density again.
// With pbf.density_tolerance > 0 the iterations stop early once the mean compression max(C, 0) is within it
// (one reduction a check, deterministic: reduction.h); a step that uses every iteration above it is flagged.
#pragma once

#include <cstdint>

#include "../common/backend.h"
#include "../common/boundaries.h"
#include "../common/forces.h"
#include "../common/pbf.h"
#include "../common/sph_hd.h"
#include "../common/springs.h"
#include "../common/viscous_limit.h"
#include "chebyshev.h"
#include "pbf_coarse.h"
#include "reduction.h"
#include "surface_forces.h"
#include "viscous_forces.h"
#include "wcsph.h"

namespace sph {
namespace pbf {

// The viscoelastic springs' acceleration (springs.h) at the step's start x, into acc for PredictFn; their
// rest lengths yield over dt. A loop of its own: PredictFn moves the positions the springs measure. Clavet et
// al. displace particles by the springs before their relaxation as well; here they are an external force, so
// the step keeps the springs' explicit limit (time_step.h, spring_step_bound), as DFSPH's does.
template <class C>
struct SpringAccelerationFn {
  C c;
  SpringView s;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    const Vec3* x = p.pos;
    p.acc[i] = p.age[i] < 0.0f ? Vec3{0.0f, 0.0f, 0.0f}
                               : spring_acceleration_at(*c, s, p, i, dt, [&](int32_t j) { return x[j]; });
  }
};

// v += dt a_ext, x* = x + dt v ([MM13] algorithm 1, lines 2-3), then the shapes (boundaries.h) on the
// segment x -> x* (then KeepOffWallsFn); a_ext is gravity, the user force and, with springs,
// SpringAccelerationFn's acc. The acceleration is kept in acc for the driver's
// diagnostics. Inlet particles (age < 0) move kinematically.
template <class C>
struct PredictFn {
  C c;
  ParticleView p;
  float dt;
  bool springs;  // acc holds the springs' acceleration (SpringAccelerationFn)
  SPH_KERNEL_FN void operator()(int32_t i) const {
    const SimConstants& k = *c;
    p.pos_start[i] = p.pos[i];
    if (p.age[i] < 0.0f) {
      p.acc[i] = Vec3{0.0f, 0.0f, 0.0f};
      p.pos[i] += dt * p.vel[i];
      return;
    }
    Vec3 a = k.gravity;
    if (springs) a += p.acc[i];
    if (k.user_force.strength != 0.0f) a += user_force_acceleration(k, p.pos[i]);
    p.acc[i] = a;
    p.vel[i] += dt * a;
    p.pos[i] += dt * p.vel[i];
    boundaries_of(k, p, i, dt);
  }
};

// Stores particle i's density and its compression max(C, 0) for the convergence test (inlet particles: 0).
SPH_HD inline void store_density(const SimConstants& c, const ParticleView& p, int32_t i, float rho) {
  const float constraint = pbf_constraint(rho, c.fluids[p.fluid[i]].rest_density);
  p.density[i] = rho;
  p.solver_error[i] = p.age[i] < 0.0f || constraint < 0.0f ? 0.0f : constraint;
}

// Density at x* and the compression (store_density).
template <class C>
struct DensityFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    store_density(*c, p, i, pbf_density(*c, g, p, i));
  }
};

// Density at x*, the compression for the convergence test, and lambda, from one pass (pbf_density_lambda).
template <class C>
struct DensityLambdaFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    float rho;
    const float lambda = pbf_density_lambda(*c, g, p, (*c).pbf, i, rho);
    store_density(*c, p, i, rho);
    p.lambda[i] = p.age[i] < 0.0f ? 0.0f : lambda;
  }
};

template <class C>
struct CorrectionFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    p.delta_pos[i] = p.age[i] < 0.0f ? Vec3{0.0f, 0.0f, 0.0f} : pbf_position_correction(*c, g, p, p.lambda, (*c).pbf, i);
  }
};

// x* += w Delta p ([MM13] algorithm 1, line 17; w = pbf.jacobi_weight), extrapolated by the Chebyshev weight
// omega from the iterate one iteration back ([Wan15]), which it stores in pos_previous for the next; then
// collision with the shapes ("perform collision detection and response", line 15): the segment from x, so a
// correction cannot carry a particle through a wall (then KeepOffWallsFn).
template <class C>
struct ApplyCorrectionFn {
  C c;
  ParticleView p;
  float dt;
  float weight;  // pbf.jacobi_weight
  float omega;   // Chebyshev weight ([Wan15], chebyshev.h); 1: none (the first iteration)
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] < 0.0f) return;
    const Vec3 x = p.pos[i];
    p.pos[i] = chebyshev_extrapolate(x + weight * p.delta_pos[i], p.pos_previous[i], omega);
    p.pos_previous[i] = x;
    boundaries_of(*c, p, i, dt);
  }
};

// Half a spacing off mirror walls (keep_off_mirror_walls says why), after PredictFn and ApplyCorrectionFn: a
// loop of its own, as BoundaryParticleCollisionFn is (boundaries.h): inside theirs the walls' small arrays
// took a 48-byte stack frame on the GPU (ptxas, sm_90).
template <class C>
struct KeepOffWallsFn {
  C c;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) keep_off_mirror_walls(*c, p.pos[i], (*c).mirror_wall_distance);
  }
};

// v = (x* - x) / dt (line 21); the particle's age advances.
struct VelocityFn {
  ParticleView p;
  float dt;
  SPH_HD void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) p.vel[i] = (1.0f / dt) * (p.pos[i] - p.pos_start[i]);
    p.age[i] += dt;
  }
};

template <class C>
struct VorticityFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { p.omega[i] = pbf_vorticity(*c, g, p, p.vel, i); }
};

// XSPH's velocity correction into xsph_dv and vorticity confinement's acceleration into delta_pos (to which
// the continuum surface force adds its own), from the velocities v (and vorticities) of every particle;
// ApplyVelocityFn adds them once all are known.
template <class C>
struct VelocityCorrectionFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    const PbfConstants& s = (*c).pbf;
    const Vec3 zero{0.0f, 0.0f, 0.0f};
    p.xsph_dv[i] = s.xsph_c > 0.0f ? pbf_xsph(*c, g, p, p.vel, s, i) : zero;
    p.delta_pos[i] = s.vorticity_epsilon > 0.0f ? pbf_vorticity_confinement(*c, g, p, p.omega, s, i) : zero;
  }
};

// The grid's copy of the positions, pos_mass (written at x* by the grid phase), moved to where the
// constraint iterations left the particles: the continuum surface force's loops read it (surface_forces.h).
// The neighbour lists stay those of x* (pairs within kPbfListReach h), as for the iterations.
struct SyncGridPositionsFn {
  ParticleView p;
  SPH_HD void operator()(int32_t i) const { p.pos_mass[i] = with_w(p.pos[i], p.pos_mass[i].w); }
};

// The acceleration the prediction left in acc (gravity, the user force, the springs), set aside in
// pos_previous (free once the constraint solve is done) while the viscosity's loop writes acc, and added back
// after it, so that acc again holds the step's non-pressure acceleration for the driver's diagnostics (the
// viscosity's that of its last sub-step).
struct SetAsideAccelerationFn {
  ParticleView p;
  SPH_HD void operator()(int32_t i) const { p.pos_previous[i] = p.acc[i]; }
};
struct AddBackAccelerationFn {
  ParticleView p;
  SPH_HD void operator()(int32_t i) const { p.acc[i] += p.pos_previous[i]; }
};

// The fluids' viscosity (viscous_forces.h: the laminar one of sph.viscosity and, with pbf.artificial_viscosity,
// Monaghan's artificial one) on the velocities the step ends with, at the positions and densities the solve
// ended at: v += dt a_visc, as DFSPH applies its non-pressure forces, explicit and sub-cycled in n updates of
// dt / n where their rate exceeds 2 / dt (viscous_limit.h; the forces recomputed between them at the same
// positions). [MM13] has XSPH alone; without more, PBF ignored a scene's viscosity (a honey-like fluid ran
// as water), and the start-up motion of fluid at rest at 1 ms steps did not die out (two_layers at ratio 10:
// 0.63 m/s after 0.25 s with XSPH alone, 0.03 m/s with the scene's artificial viscosity; docs/results.md,
// "PBF takes the scene's viscosity"). Returns n (1 where no viscosity acts).
template <class Exec>
int32_t apply_viscosity(Exec& x, float dt) {
  using C = typename Exec::Constants;
  const SimConstants& c = x.host_constants();
  if (!viscosity_acts(c)) return 1;
  const ParticleView p = x.particles();
  x.for_each(SyncGridPositionsFn{p});
  x.for_each(SetAsideAccelerationFn{p});
  const int32_t n = viscous_substeps(double(c.substep_rate), double(dt));
  for (int32_t k = 0; k < n; ++k) {
    x.for_each(ForceInputsFn{p});
    x.for_each(wcsph::ForcesFn<C, ViscousForces>{x.constants(), x.grid(), p});
    x.for_each(PredictVelocityFn{p, dt / float(n)});
  }
  x.for_each(AddBackAccelerationFn{p});
  return n;
}

struct ApplyVelocityFn {
  ParticleView p;
  float dt;
  SPH_HD void operator()(int32_t i) const {
    if (p.age[i] < 0.0f) return;
    p.vel[i] += p.xsph_dv[i] + dt * p.delta_pos[i];
    p.acc[i] += p.delta_pos[i];
  }
};

// After a move of the positions in the solve: half a spacing off mirror walls, out of the boundary particles.
template <class Exec>
void after_move(Exec& x) {
  using C = typename Exec::Constants;
  if (x.host_constants().mirror_walls) x.for_each(KeepOffWallsFn<C>{x.constants(), x.particles()});
  const GridView g = x.grid();
  if (g.boundary.n > 0) x.for_each(BoundaryParticleCollisionFn{g, x.particles(), x.host_constants().kernel.h2});
}

// The constraint iterations: density, error and lambda in one pass, then (unless done) Delta p and its
// application; the last pass computes the density only.
// Records in stats the iterations made, the mean compression at the end (density_error), whether a tolerance
// was set and not met (density_capped), and the coarse grid's solve.
template <class Exec>
void solve(Exec& x, float dt, SolverStats& stats) {
  using C = typename Exec::Constants;
  const PbfConstants& s = x.host_constants().pbf;
  const ParticleView p = x.particles();
  const GridView g = x.grid();
  const int32_t n = p.n;
  int32_t it = 0;
  float omega = 1.0f;
  for (;;) {
    // The last pass needs no lambda: then the density alone (the same bits).
    const bool last = it == s.iterations;
    if (last) x.for_each(DensityFn<C>{x.constants(), g, p});
    else x.for_each(DensityLambdaFn<C>{x.constants(), g, p});
    if (it == 0 && !last && s.coarse_grid) {  // pbf_coarse.h, then the density and lambda it leaves
      stats.coarse_iterations = coarse_correction(x, stats.coarse_capped);
      x.for_each(ApplyCorrectionFn<C>{x.constants(), p, dt, 1.0f, 1.0f});
      after_move(x);
      x.for_each(DensityLambdaFn<C>{x.constants(), g, p});
    }
    if (last || s.density_tolerance > 0.0f) {
      stats.density_error = mean_of(x, p.solver_error, n);
      if (last || stats.density_error <= double(s.density_tolerance)) break;
    }
    x.for_each(CorrectionFn<C>{x.constants(), g, p});
    omega = it == 0 ? 1.0f : chebyshev_next_weight(s.chebyshev, omega);
    x.for_each(ApplyCorrectionFn<C>{x.constants(), p, dt, s.jacobi_weight, omega});
    after_move(x);
    ++it;
  }
  stats.density_capped = s.density_tolerance > 0.0f && stats.density_error > double(s.density_tolerance);
  stats.density_iterations = it;
}

// Runs phase ph of a PBF step (one of kPbfPhases) on the back end's Exec; the solve records what it did in
// stats.
template <class Exec>
void run_phase(Exec& x, Phase ph, float dt, SolverStats& stats) {
  using C = typename Exec::Constants;
  const PbfConstants& s = x.host_constants().pbf;
  switch (ph) {
    case Phase::Predict: {
      const bool springs = x.springs().capacity > 0;
      if (springs) {  // each particle's place under its id (the last grid build's order), then the springs
        x.for_each(wcsph::IndexParticleFn{x.springs(), x.particles()});
        x.for_each(SpringAccelerationFn<C>{x.constants(), x.springs(), x.particles(), dt});
      }
      x.for_each(PredictFn<C>{x.constants(), x.particles(), dt, springs});
      after_move(x);
      return;
    }
    case Phase::BuildGrid: x.build_grid(); return;
    case Phase::ConstraintSolve:
      solve(x, dt, stats);
      return;
    case Phase::Correct: x.for_each(VelocityFn{x.particles(), dt}); return;
    case Phase::Forces: {
      // The continuum surface force (surface_forces.h) at the end of the step, at the positions and densities
      // the solve ended at, applied with vorticity confinement as an acceleration over dt: the next step's
      // prediction carries it, as it carries gravity. XSPH, vorticity confinement and the surface force from
      // the velocities of the correction; the viscosity from the same velocities (apply_viscosity), added
      // before the others. Measured on drop_oscillation under the continuum surface force (docs/results.md):
      // this way, with the plain iteration, no particle left the cube at 10 to 18 across (3 corners at 12
      // with XSPH at c = 0.1 as well); with the viscosity applied first and XSPH taken from the velocities it
      // left, the 12-across cube lost one from a face's tip.
      const bool csf = x.host_constants().csf_enabled != 0;
      if (s.vorticity_epsilon > 0.0f) x.for_each(VorticityFn<C>{x.constants(), x.grid(), x.particles()});
      const bool corrections = s.vorticity_epsilon > 0.0f || s.xsph_c > 0.0f || csf;
      if (corrections) {
        x.for_each(VelocityCorrectionFn<C>{x.constants(), x.grid(), x.particles()});
        if (csf) {
          x.for_each(SyncGridPositionsFn{x.particles()});
          continuum_surface_force(x, x.particles().delta_pos);
        }
      }
      stats.viscous_substeps = apply_viscosity(x, dt);
      if (corrections) x.for_each(ApplyVelocityFn{x.particles(), dt});
      return;
    }
    case Phase::Recycle: x.recycle(); return;
    default: return;  // not a phase of a PBF step: the back ends refuse it before
  }
}

// The grid and densities of an uploaded state (for its first metrics; a step computes its own).
template <class Exec>
void initialise(Exec& x) {
  using C = typename Exec::Constants;
  x.build_grid();
  x.for_each(DensityFn<C>{x.constants(), x.grid(), x.particles()});
}

}  // namespace pbf
}  // namespace sph
