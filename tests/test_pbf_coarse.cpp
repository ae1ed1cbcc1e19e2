// PBF's coarse-grid correction (pbf.coarse_grid; src/common/pbf_coarse.h, src/solvers/pbf_coarse.h) on the
// serial reference: issue 12's resting column within 1% at 4 ms and 4 iterations, where the iteration alone
// misses it; the 16k dam break; a fluid that touches no air, where the coarse problem has no unique solution.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/metrics.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

struct ColumnRun {
  double worst_late = 0.0;   // largest mean compression at the end of a solve over the last second
  double v_max_late = 0.0;   // largest speed over the last 0.5 s [m/s]
  double top_change = 0.0;   // top layer's height at the end minus at the start [m]
  double spacing = 0.0;
};

// hydrostatic_tank (20 particles deep at 10 across, mirror walls) under PBF at fixed 4 ms steps for 2 s.
ColumnRun resting_column(const std::vector<std::string>& extra) {
  std::vector<std::string> set = {"solver=pbf", "time_step.mode=fixed", "time_step.dt=0.004"};
  set.insert(set.end(), extra.begin(), extra.end());
  const double run = 2.0;
  sph::Simulation sim(scene_file("hydrostatic_tank.json", set), cpu_factory(), run);
  ColumnRun r;
  r.spacing = sim.setup().spacing;
  const double top0 = top_layer_height(sim.particles());
  while (sim.time() < run - 1e-9) {
    sim.advance();
    if (sim.time() > run - 1.0) r.worst_late = std::max(r.worst_late, sim.solver_stats().density_error);
    if (sim.time() > run - 0.5)
      r.v_max_late = std::max(r.v_max_late, double(sph::measure(sim.setup().constants, sim.particles()).v_max));
  }
  r.top_change = top_layer_height(sim.particles()) - top0;
  return r;
}

}  // namespace

TEST_CASE("PBF's coarse grid holds a resting column within 1% at 4 ms and 4 iterations, where the iteration alone does not",
          "[solvers][pbf][coarse]") {
  // Issue 12: density error at most 1% and no drift of the column's height over 2 s at dt = 4 ms with 4
  // iterations. The iteration alone leaves 2.5% (the compression grows with depth as g dt^2 / k per spacing:
  // docs/results.md, "Why PBF misses 1%"). Measured with the coarse grid at 10 across: 0.044%, the top layer
  // 1.4 mm lower after 2 s (a spacing is 5 mm), the fastest particle over the last 0.5 s 0.024 m/s (the
  // iteration alone: 0.029). At 11 across the box's top wall cuts the grid's cells short, which before the
  // cells' open share was counted made them air beside the wall: 0.99% and 0.44 m/s then, 0.057% and 0.034 m/s
  // now.
  for (const char* across : {"10", "11"}) {
    const ColumnRun coarse = resting_column({"pbf.coarse_grid=true", std::string("resolution.particles_across=") + across});
    INFO(across << " across, coarse grid: largest mean compression over the last second " << coarse.worst_late
         << ", top layer moved " << coarse.top_change << " m, fastest particle over the last 0.5 s " << coarse.v_max_late << " m/s");
    CHECK(coarse.worst_late <= 0.01);
    CHECK(std::fabs(coarse.top_change) <= coarse.spacing);
    CHECK(coarse.v_max_late < 0.1);  // at rest by issue 15's measure (0.1 m/s)
  }
  const ColumnRun alone = resting_column({});
  INFO("the iteration alone: " << alone.worst_late << ", " << alone.top_change << " m, " << alone.v_max_late << " m/s");
  CHECK(alone.worst_late > 0.01);  // the method without it, where it fails
}

TEST_CASE("PBF's coarse grid keeps the 16k dam break within 1% at 4 ms and 4 iterations", "[solvers][pbf][coarse]") {
  // Issue 12's dam-break setting. Measured over the first second: the largest mean compression at the end of
  // a solve 0.12% with the coarse grid, 7.1% without (at 0.1 s, the column 40 particles deep); no energy lost
  // before the impact (0.2079 J at 0.144 s, 0.189 J without).
  const double seconds = 0.4;
  sph::Simulation sim(scene_file("dam_break.json", {"solver=pbf", "time_step.mode=fixed", "time_step.dt=0.004",
                                                    "pbf.coarse_grid=true"}),
                      cpu_factory(), seconds);
  double worst = 0.0, front = 0.0;
  while (sim.time() < seconds - 1e-9) {
    sim.advance();
    worst = std::max(worst, sim.solver_stats().density_error);
    front = std::max(front, double(sph::measure(sim.setup().constants, sim.particles()).front_x));
  }
  INFO("largest mean compression " << worst << ", front at most " << front << " m");
  CHECK(worst <= 0.01);
  CHECK(front > 0.45);  // met the far wall (0.457 m) and ran on through the impact
}

TEST_CASE("PBF's coarse grid leaves a fluid that touches no air as the iteration does", "[solvers][pbf][coarse]") {
  // A closed box filled to its lid: no cell of air, so A phi = b fixes phi only up to a constant and has a
  // solution only for b of zero sum; the solve then only evens the compression out (src/solvers/pbf_coarse.h).
  // Before that, phi's constant part grew without bound and the box blew up within 3 steps. Measured: the
  // largest mean compression at the end of a solve over 0.2 s 0.97% with the coarse grid, 4.0% without.
  const auto run = [](bool coarse) {
    std::vector<std::string> set = {"solver=pbf", "time_step.mode=fixed", "time_step.dt=0.004",
                                    "boundaries.0.max.1=0.1"};
    if (coarse) set.push_back("pbf.coarse_grid=true");
    const double seconds = 0.2;
    sph::Simulation sim(scene_file("hydrostatic_tank.json", set), cpu_factory(), seconds);
    double worst = 0.0;
    while (sim.time() < seconds - 1e-9) {
      sim.advance();
      worst = std::max(worst, sim.solver_stats().density_error);
    }
    return worst;
  };
  const double with = run(true), without = run(false);
  INFO("largest mean compression over 0.2 s: with the coarse grid " << with << ", without " << without);
  CHECK(std::isfinite(with));
  CHECK(with <= without);
}

TEST_CASE("PBF's coarse grid reports a solve that stops at its iteration cap", "[solvers][pbf][coarse]") {
  // Issue 12: a solve that does not converge never continues silently. The summary's coarse_grid_capped_steps
  // (run_report.cpp) counts the steps whose conjugate-gradient solve stopped at pbf.coarse_iterations.
  const auto run = [](const std::string& cap) {
    sph::Simulation sim(scene_file("hydrostatic_tank.json", {"solver=pbf", "time_step.mode=fixed", "time_step.dt=0.004",
                                                             "pbf.coarse_grid=true", "pbf.coarse_iterations=" + cap}),
                        cpu_factory(), 0.1);
    while (sim.time() < 0.1 - 1e-9) sim.advance();
    return sim.solver_totals();
  };
  const sph::SolverTotals three = run("3"), fifty = run("50");
  INFO("cap 3: " << three.coarse_capped_steps << " of " << three.steps << " steps capped; cap 50: "
       << fifty.coarse_capped_steps << ", at most " << fifty.max_coarse_iterations << " iterations a step");
  CHECK(three.coarse_capped_steps == three.steps);
  CHECK(three.max_coarse_iterations == 3);
  CHECK(fifty.coarse_capped_steps == 0);
  CHECK(fifty.max_coarse_iterations > 3);
  CHECK(fifty.max_coarse_iterations < 50);
}
