// The interface every back end implements (cpu: serial reference; host: device code on OpenMP; cuda).
// A back end owns the particle arrays in its own layout and runs the phases of one step of the scene's
// solver (src/solvers/), in the order step_phases() gives; WCSPH's is
//   predict -> build grid -> density -> pressure -> forces -> correct -> boundaries -> recycle
// (emission is requested by the Simulation between steps through emit()).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "boundary_particles.h"
#include "rigid_body.h"
#include "springs.h"
#include "params.h"
#include "particle_state.h"

namespace sph {

enum class Phase : int {
  Predict,
  BuildGrid,
  Density,
  Pressure,
  Forces,
  Correct,
  Boundaries,
  Recycle,
  DensitySolve,     // DFSPH's constant-density solver ([BK15] algorithm 3)
  DivergenceSolve,  // DFSPH's divergence-free solver ([BK15] algorithm 2)
  ConstraintSolve,  // PBF's density constraint iterations ([MM13] algorithm 1)
  Emit,
  Count
};
const char* phase_name(Phase p);
// The phases of a WCSPH step(dt), in the order it runs them.
constexpr Phase kStepPhases[] = {Phase::Predict, Phase::BuildGrid, Phase::Density,    Phase::Pressure,
                                 Phase::Forces,  Phase::Correct,   Phase::Boundaries, Phase::Recycle};
// DFSPH ([BK15] algorithm 1, src/solvers/dfsph.h, begun at its neighbourhood update so that a step starts
// from any uploaded or emitted state): the grid, density and alpha, the divergence solver, non-pressure
// forces, v* = v + dt a, the density solver, x += dt v* (and the shapes).
constexpr Phase kDfsphPhases[] = {Phase::BuildGrid, Phase::Density,      Phase::DivergenceSolve,
                                  Phase::Forces,    Phase::Predict,      Phase::DensitySolve,
                                  Phase::Correct,   Phase::Boundaries,   Phase::Recycle};
// PBF ([MM13] algorithm 1, src/solvers/pbf.h): v += dt a_ext, x* = x + dt v, the grid on x*, the constraint
// iterations (with the shapes), v = (x* - x) / dt, vorticity confinement and XSPH.
constexpr Phase kPbfPhases[] = {Phase::Predict, Phase::BuildGrid, Phase::ConstraintSolve, Phase::Correct,
                                Phase::Forces,  Phase::Recycle};

// The phases of a step of solver s, in order: begin() and end() for a range-for.
struct PhaseList {
  const Phase* first;
  const Phase* last;
  const Phase* begin() const { return first; }
  const Phase* end() const { return last; }
  bool contains(Phase p) const {
    for (const Phase q : *this)
      if (q == p) return true;
    return false;
  }
};
inline PhaseList step_phases(Solver s) {
  switch (s) {
    case Solver::Dfsph: return PhaseList{std::begin(kDfsphPhases), std::end(kDfsphPhases)};
    case Solver::Pbf: return PhaseList{std::begin(kPbfPhases), std::end(kPbfPhases)};
    case Solver::Wcsph: break;
  }
  return PhaseList{std::begin(kStepPhases), std::end(kStepPhases)};
}

// What the iterative solvers did in the last step (zero for WCSPH): iterations, and the error each solve
// ended at, as the fractions the tolerances are given in (params.h: DfsphConstants, PbfConstants). capped: the
// solve stopped at its iteration cap above its tolerance.
struct SolverStats {
  int32_t density_iterations = 0;     // DFSPH's density solver, PBF's constraint iterations
  int32_t divergence_iterations = 0;  // DFSPH's divergence solver
  double density_error = 0.0;         // mean compression max(rho / rho0 - 1, 0) after the solve
  double divergence_error = 0.0;      // DFSPH: mean max(dt D rho / Dt, 0) / rho0 after the solve
  bool density_capped = false;
  bool divergence_capped = false;
  int32_t viscous_substeps = 1;       // DFSPH: sub-steps of the non-pressure forces, PBF: of its viscosity (viscous_limit.h)
  int32_t coarse_iterations = 0;      // PBF's coarse grid (pbf.coarse_grid): conjugate-gradient iterations
  bool coarse_capped = false;         // it stopped at pbf.coarse_iterations above its tolerance
};

// Accumulated wall time per phase, for the runner's summary, the benchmark and the demo panel.
struct PhaseTimes {
  std::array<double, int(Phase::Count)> seconds{};
  long steps = 0;
};

// What the driver needs after each step: the adaptive time step and the blow-up check.
struct Diagnostics {
  float max_speed = 0.0f;
  float max_accel = 0.0f;
  int32_t fastest = -1;      // index of the fastest particle
  int32_t non_finite = -1;   // index of a particle with a NaN or infinite position or velocity, or -1
};

// How particles are coloured for drawing: render::ColourMode and the range of the mapped quantity
// (render/particle_colours.h). Plain numbers, so this header needs no render header.
struct RenderColouring {
  int colour_mode = 0;         // render::ColourMode
  float lo = 0.0f, hi = 1.0f;  // colour range
};

// OpenGL buffers a back end may write straight into (CUDA-OpenGL interop): positions and colours as
// 3 floats per particle. Plain integers, so this header needs no GL or CUDA header.
struct GlBuffers {
  uint32_t position_vbo = 0, colour_vbo = 0;
  std::size_t capacity = 0;   // particles the buffers hold
  uint32_t generation = 0;    // changes whenever the buffers are reallocated (register them again)
  RenderColouring colouring;
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;
  virtual void upload(const ParticleState& state) = 0;   // replaces the particles
  // Replaces the static boundary particles (sph.walls = "particles"; none by default): a copy in the back
  // end's memory, read by every neighbour loop through GridView::boundary.
  virtual void set_boundary(const BoundaryParticles& boundary) = 0;
  // Replaces the rigid bodies (rigid_body.h; none by default): their particles and state. A WCSPH step moves
  // the free ones; bodies() gives their state now.
  virtual void set_bodies(const std::vector<RigidBody>& bodies) = 0;
  // Replaces the viscoelastic springs (springs.h; none by default): a copy in the back end's memory, which
  // the WCSPH forces phase updates (plasticity, breaking).
  virtual void set_springs(const SpringNetwork& springs) = 0;
  virtual SpringNetwork download_springs() = 0;  // their state now (rest lengths, broken ones)
  virtual const std::vector<RigidBody>& bodies() const = 0;
  virtual void initialise_forces() = 0;                   // accelerations of the uploaded state, no motion
  virtual void step(float dt) = 0;                        // the phases of step_phases(solver), in order
  // Runs one phase of the solver's step alone, exactly as step(dt) runs it, so that tests can compare back
  // ends phase by phase; step(dt) is step_phase(p, dt) for each p in order, and each is timed as in a step.
  // Throws std::invalid_argument for a phase that is not one of the solver's steps (Emit, Count included).
  virtual void step_phase(Phase p, float dt) = 0;
  virtual void emit(const std::vector<Spawn>& spawns) = 0;
  virtual const ParticleState& download() = 0;            // current particles, in the back end's order
  virtual std::size_t size() const = 0;
  virtual Diagnostics diagnose() = 0;
  virtual const PhaseTimes& phase_times() const = 0;
  // What the last step's iterative solves did (SolverStats; all zero under WCSPH).
  virtual SolverStats solver_stats() const = 0;
  // Replaces the constants between steps (live parameters: viscosity, stiffness, gravity, user force).
  // The grid geometry must stay the same.
  virtual void set_constants(const SimConstants& constants) = 0;
  // Writes positions and colours into the OpenGL buffers without a copy through the host, from the thread
  // whose OpenGL context owns them. Returns false when the back end cannot, with the reason in `why`
  // (empty where the back end has no interop at all); then the caller downloads and uploads, and need not
  // ask again: a back end that failed once does not retry. Throws std::runtime_error when capacity <
  // size() or a CUDA call fails once the buffers are registered.
  virtual bool write_gl_buffers(const GlBuffers&, std::string& why) {
    why.clear();
    return false;
  }
  // Lets go of the OpenGL buffers (unregisters them): the caller calls it before it reallocates or deletes
  // them. A later write_gl_buffers registers them again.
  virtual void release_gl_buffers() {}
  // The positions and colours the interop kernel writes, into host arrays of size() elements in the back
  // end's order (the device test compares them with the host path, render/particle_colours.h). False
  // where the back end has no such kernel (cpu).
  virtual bool write_render_arrays(const RenderColouring&, std::vector<Vec3>& positions, std::vector<Vec3>& colours) {
    positions.clear();
    colours.clear();
    return false;
  }
};

using BackendFactory = std::function<std::unique_ptr<Backend>(const SimConstants&)>;

}  // namespace sph
