// sph_run's report on standard output: the set-up lines before the run and the summary after it (the
// figures benchmarks parse: ms_per_step and the rest, documented in sph_run --help and the README).
#pragma once

#include <string>
#include <vector>

#include "../common/frame_reader.h"
#include "../common/metrics.h"
#include "../common/scene.h"
#include "../common/simulation.h"

namespace sph {

// The worst of the metrics rows, for the summary.
struct RowExtremes {
  long most_outside = 0;     // particles outside the domain
  double deepest = 0.0;      // [m] the deepest any fluid particle got into a solid (solid_penetration.h)
  long most_in_solids = 0;   // particles deeper than half a spacing in a solid
};

// What the run was asked to do, as the set-up lines name it.
struct RunDescription {
  std::string scene_path, out, restart;  // restart: the frame continued from, empty for none
  bool by_steps = false;                 // run for `steps` steps instead of run_time simulated seconds
  long long steps = 0;
  double run_time = 0.0;                 // [s]
};

// The set-up lines: scene, back end, resolution, solver and its settings, the set-up's report ("setup: ..."),
// and a warning on standard error for every probe outside the domain. restart: the frame read, or nullptr.
void print_setup(const RunDescription& o, const Scene& scene, Simulation& sim, const Frame* restart);

// The summary: figures of the whole run. ms_per_step is the median wall time of one step (step_ms, one entry
// per step [ms]); the means are named as such. m: the last metrics; wall: the run's wall time [s].
void print_summary(Simulation& sim, const Metrics& m, const std::vector<double>& step_ms, double wall,
                   const RowExtremes& worst);

}  // namespace sph
