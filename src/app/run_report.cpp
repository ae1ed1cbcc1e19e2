#include "run_report.h"

#include <algorithm>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

namespace sph {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// ", sph.kernel: ..." for DFSPH's kernel (src/common/dfsph.h, dfsph_w).
const char* dfsph_kernel_text(const SimConstants& c) {
  return c.dfsph_poly6_spiky ? ", sph.kernel: poly6_spiky" : ", sph.kernel: cubic_spline";
}

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

// The iterative solvers' lines of the summary: iterations per step (mean and maximum), the largest error a
// solve ended at, and a warning on standard error for every solve that stopped at its cap above tolerance.
void print_solver_summary(const Simulation& sim) {
  const Scene& scene = sim.scene();
  const SolverTotals& t = sim.solver_totals();
  std::cout << "solver: " << solver_name(scene.solver);
  if (scene.solver == Solver::Dfsph)
    std::cout << dfsph_kernel_text(sim.setup().constants);
  std::cout << "\n";
  // The rigid bodies where the run left them.
  for (const RigidBody& b : sim.backend().bodies())
    std::cout << "body: " << b.label << ": centre (" << b.centre[0] << ", " << b.centre[1] << ", " << b.centre[2]
              << ") m, velocity (" << b.velocity[0] << ", " << b.velocity[1] << ", " << b.velocity[2] << ") m/s, fluid force ("
              << b.force[0] << ", " << b.force[1] << ", " << b.force[2] << ") N" << (b.contact ? ", touching a wall" : "")
              << (b.body_contact ? ", touching another body" : "") << "\n";
  if (scene.solver == Solver::Wcsph || t.steps == 0) return;
  const double steps = double(t.steps);
  const bool dfsph = scene.solver == Solver::Dfsph;
  std::cout << (dfsph ? "density_solver_iterations" : "constraint_iterations") << ": mean "
            << double(t.density_iterations) / steps << ", max " << t.max_density_iterations << "\n";
  if (dfsph)
    std::cout << "divergence_solver_iterations: mean " << double(t.divergence_iterations) / steps << ", max "
              << t.max_divergence_iterations << "\n";
  // Steps whose density (PBF: constraint) solve stopped at its cap above tolerance; DFSPH's divergence solve
  // on a line of its own.
  std::cout << "solver_density_error_max: " << t.max_density_error << "\n"
            << "solver_capped_steps: " << t.density_capped_steps << "\n";
  if (dfsph) std::cout << "divergence_capped_steps: " << t.divergence_capped_steps << "\n";
  // DFSPH's sub-cycled non-pressure forces and PBF's viscosity (the viscosities above their explicit bound;
  // viscous_limit.h): the most sub-steps a step took, and how many steps took more than one (their extra force
  // passes are timed in DFSPH's predict phase, in PBF's forces phase).
  if (scene.solver != Solver::Wcsph)
    std::cout << "viscous_substeps: max " << t.max_viscous_substeps << ", sub-cycled steps " << t.substepped_steps
              << " of " << t.steps << "\n";
  // PBF's coarse grid: its conjugate-gradient solve a step, and the steps it stopped at its cap (its density
  // error then shows in solver_density_error_max: the Jacobi iterations take what it left).
  if (scene.solver == Solver::Pbf && scene.pbf.coarse_grid != 0) {
    std::cout << "coarse_grid_iterations: mean " << double(t.coarse_iterations) / steps << ", max "
              << t.max_coarse_iterations << "\n"
              << "coarse_grid_capped_steps: " << t.coarse_capped_steps << "\n";
    if (t.coarse_capped_steps > 0)
      std::cerr << "warning: PBF's coarse grid stopped at pbf.coarse_iterations = " << scene.pbf.coarse_iterations
                << " above its tolerance (1% of its starting residual) in " << t.coarse_capped_steps << " of " << t.steps
                << " steps; raise pbf.coarse_iterations\n";
  }
  if (t.density_capped_steps > 0)
    std::cerr << "warning: the " << (dfsph ? "density solver" : "constraint solve") << " did not converge in "
              << t.density_capped_steps << " of " << t.steps << " steps: it stopped at "
              << (dfsph ? "dfsph.max_iterations = " + std::to_string(scene.dfsph.max_iterations)
                        : "pbf.iterations = " + std::to_string(scene.pbf.iterations))
              << " above its tolerance ("
              << (dfsph ? double(scene.dfsph.density_tolerance) : double(scene.pbf.density_tolerance))
              << "); the largest mean compression left was " << t.max_density_error
              << " (solver_density_error in metrics.csv). Raise the iteration cap or lower the time step\n";
  if (t.divergence_capped_steps > 0)
    std::cerr << "warning: the divergence solver did not converge in " << t.divergence_capped_steps << " of "
              << t.steps << " steps: it stopped at dfsph.max_iterations = " << scene.dfsph.max_iterations
              << " above dfsph.divergence_tolerance = " << scene.dfsph.divergence_tolerance
              << " (divergence_error in metrics.csv). Raise the iteration cap or lower the time step\n";
}

}  // namespace

void print_setup(const RunDescription& o, const Scene& scene, Simulation& sim, const Frame* restart) {
  const Setup& st = sim.setup();
  std::cout << "scene: " << scene.name << " (" << o.scene_path << ")\n"
            << "backend: " << sim.backend().name() << "\n"
            << "spacing: " << st.spacing << " m, h: " << st.h << " m, neighbours: " << scene.neighbours
            << ", lattice kernel sum: " << st.lattice_density << "\n"
            << "grid: cells of " << st.constants.grid.cell_size << " m, only where particles are; domain "
            << st.constants.grid.nx << " x " << st.constants.grid.ny << " x " << st.constants.grid.nz << " cells\n"
            << "solver: " << solver_name(scene.solver)
            << (scene.solver == Solver::Wcsph ? std::string(", integrator: ") + integrator_name(scene.integrator) +
                                                    (st.constants.cubic_spline ? ", sph.kernel: cubic_spline" : ", sph.kernel: poly6_spiky")
                                              : std::string());
  if (scene.solver == Solver::Dfsph) {
    std::cout << dfsph_kernel_text(st.constants)
              << ", chebyshev: " << scene.dfsph.chebyshev;
    if (scene.dfsph.warm_start) std::cout << ", warm_start_fraction: " << scene.dfsph.warm_start_fraction;
    else std::cout << ", warm start: off";
  }
  if (scene.solver == Solver::Pbf)
    std::cout << ", iterations: " << scene.pbf.iterations << ", jacobi_weight: " << scene.pbf.jacobi_weight
              << ", chebyshev: " << scene.pbf.chebyshev;
  if (scene.solver == Solver::Pbf && st.constants.surface_tension_enabled)  // PBF has the continuum surface force only
    std::cout << ", surface tension: none (pbf ignores the cohesion)";
  else
    std::cout << (st.constants.csf_enabled ? ", surface tension: csf"
                                           : (st.constants.surface_tension_enabled ? ", surface tension: cohesion" : ""));
  if (!scene.interface_tensions.empty())
    std::cout << ", interface tension: " << scene.interface_tensions.size()
              << (scene.interface_tensions.size() == 1 ? " pair" : " pairs");
  if (st.constants.adhesion_enabled) std::cout << ", adhesion to walls (contact_angle)";
  if (st.constants.csf_contact_enabled) std::cout << ", contact angles at walls (contact_angle)";
  std::cout << ", speed bound: " << sim.speed_bound()
            << " m/s, energy budget: " << sim.energy_budget() << " J\n"
            << (sim.relaxation().ran ? sim.relaxation().summary() + "\n" : std::string())
            << (restart ? "restart: " + o.restart + " (frame " + std::to_string(restart->info.frame_index) + ", step " +
                              std::to_string(sim.steps()) + ", t = " + std::to_string(sim.time()) + " s)\n"
                        : std::string())
            << "run: " << (o.by_steps ? std::to_string(o.steps) + " steps" : std::to_string(o.run_time) + " s simulated")
            << ", output: " << o.out << "\n";
  for (const std::string& line : st.report) std::cout << "setup: " << line << "\n";
  std::cout.flush();
  // A probe outside the domain the fluid can fill reads 0 for ever: say so (probes only read, so it runs).
  const GridGeometry& g = st.constants.grid;
  const double hi[3] = {g.origin.x + g.cell_size * g.nx, g.origin.y + g.cell_size * g.ny, g.origin.z + g.cell_size * g.nz};
  const double lo[3] = {g.origin.x, g.origin.y, g.origin.z};
  for (std::size_t i = 0; i < scene.probes.size(); ++i) {
    const ProbeSpec& p = scene.probes[i];
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside = inside && p.position[std::size_t(a)] >= lo[a] && p.position[std::size_t(a)] <= hi[a];
    if (!inside)
      std::cerr << "warning: " << scene.source << ": probes." << i << " (\"" << p.name << "\") at (" << p.position[0] << ", "
                << p.position[1] << ", " << p.position[2] << ") m lies outside the domain (" << lo[0] << ".." << hi[0] << ", "
                << lo[1] << ".." << hi[1] << ", " << lo[2] << ".." << hi[2] << " m): its depth_" << p.name
                << " will read 0\n";
  }
}

// The summary: figures of the whole run. ms_per_step is the median wall time of one step (benchmarks
// parse it); the means are named as such.
void print_summary(Simulation& sim, const Metrics& m, const std::vector<double>& step_ms, double wall,
                   const RowExtremes& worst) {
  const double med = median(step_ms);
  std::cout << "simulated_time: " << sim.time() << "\n"
            << "particles: " << sim.backend().size() << "\n"
            << "steps: " << sim.steps() << "\n"
            << "ms_per_step: " << med << "\n"
            << "ms_per_step_mean: " << mean(step_ms) << "\n"
            << "particle_steps_per_second: " << (med > 0 ? 1e3 * double(sim.backend().size()) / med : 0.0) << "\n"
            << "wall_seconds: " << wall << "\n"
            << "kinetic_energy: " << m.kinetic_energy << "\n"
            << "density_error_mean: " << m.density_error_mean << "\n"
            << "density_error_max: " << m.density_error_max << "\n"
            << "front_x: " << m.front_x << "\n"
            << "particles_outside_domain: " << m.outside_domain << " (most in a metrics row: " << worst.most_outside << ")\n"
            << "deepest_in_solid: " << worst.deepest << " m = " << worst.deepest / sim.setup().spacing
            << " spacings (particles deeper than half a spacing, the most in a metrics row: " << worst.most_in_solids << ")\n";
  print_solver_summary(sim);
  const PhaseTimes& pt = sim.backend().phase_times();
  if (pt.steps > 0) {
    std::cout << "phase_ms_per_step_mean:";
    for (int p = 0; p < int(Phase::Count); ++p)
      std::cout << ' ' << phase_name(Phase(p)) << '=' << 1e3 * pt.seconds[std::size_t(p)] / double(pt.steps);
    std::cout << "\n";
  }
}

}  // namespace sph
