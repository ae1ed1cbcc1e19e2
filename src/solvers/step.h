// A step of the scene's solver (SimConstants::solver): which solver's phases run. The back ends call these
// two functions and nothing else of the physics; the order of each solver's phases is step_phases() in
// backend.h, and each phase is written once, in src/solvers/wcsph.h, dfsph.h and pbf.h.
#pragma once

#include "../common/backend.h"
#include "dfsph.h"
#include "pbf.h"
#include "wcsph.h"

namespace sph {

// Phase p of a step of the solver of x's constants; the iterative solvers record what they did in stats.
template <class Exec>
void run_solver_phase(Exec& x, Phase p, float dt, SolverStats& stats) {
  switch (x.host_constants().solver) {
    case Solver::Wcsph: wcsph::run_phase(x, p, dt); return;
    case Solver::Dfsph: dfsph::run_phase(x, p, dt, stats); return;
    case Solver::Pbf: pbf::run_phase(x, p, dt, stats); return;
  }
}

// What the solver needs of an uploaded state before its first step.
template <class Exec>
void initialise_solver(Exec& x) {
  switch (x.host_constants().solver) {
    case Solver::Wcsph: wcsph::initialise(x); return;
    case Solver::Dfsph: dfsph::initialise(x); return;
    case Solver::Pbf: pbf::initialise(x); return;
  }
}

}  // namespace sph
