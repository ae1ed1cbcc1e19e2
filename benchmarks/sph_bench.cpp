// sph_bench: the CPU-vs-GPU benchmark. Fixed workloads on every usable back end: the thesis's performance
// cube (16^3 and 32^3, thesis 5.2 parameters), the dam break at several sizes, and the 16k dam break under
// each pressure solver (WCSPH, DFSPH, PBF at 4 ms) and each wall model (mirror walls, boundary particles:
// their cost ratio per step is printed). Warm-up steps, repeated runs. ms/step is the median of
// the measured steps (robust to other work on the machine); the time by phase is a mean per step (the back
// ends accumulate it), and ms_mean is the mean of the same steps, so the two can be compared. The solvers
// take steps of very different length, so a step's cost does not compare them: each workload also reports
// the wall seconds per simulated second of its measured steps (their summed wall time over the simulated
// time they covered), the mean dt and the solver iterations per step; the solver workloads all measure the
// same stretch of the flow, from t = 0 to --solver-time. Prints tables and writes CSV and JSON that name
// the hardware.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "app/backends.h"
#include "app/cli_errors.h"
#include "common/simulation.h"
#include "cuda/device_backend.h"

namespace fs = std::filesystem;
using namespace sph;

namespace {

struct Workload {
  std::string name;
  std::string scene;
  std::vector<std::string> sets;
  // The thesis's published ms/step for this workload (thesis 5.2), 0 when it has none.
  double thesis_cpu_ms = 0.0, thesis_gpu_ms = 0.0;
  bool cuda_only = false;
  // Simulated seconds to measure from t = 0, after a warm-up on a run that is thrown away (the solver
  // workloads: solvers whose steps differ are measured over the same stretch of the flow); 0: --steps steps
  // after --warmup steps of the measured run.
  double simulated_s = 0.0;
};

struct Result {
  std::string backend, workload;
  long particles = 0;
  double ms_per_step = 0.0;  // median over the measured steps of all repeats
  double ms_mean = 0.0, ms_min = 0.0, ms_max = 0.0;
  PhaseTimes phases;         // mean ms per step by phase
  double speedup_vs_cpu = 0.0;
  double thesis_cpu_ms = 0.0, thesis_gpu_ms = 0.0;
  std::string solver;        // the scene's pressure solver (solver_name)
  long steps = 0;            // measured steps, all repeats
  double simulated_s = 0.0;  // the simulated time they covered [s]
  double wall_s = 0.0;       // their summed wall time [s]
  // Iterations of the measured steps (SolverTotals): DFSPH's density solve or PBF's constraint iterations,
  // DFSPH's divergence solve, and the solves that stopped at their cap above tolerance.
  long solver_iterations = 0, divergence_iterations = 0, capped_solves = 0;
  // solver_wcsph's wall seconds per simulated second on the same back end over this workload's (solver
  // workloads only, else 0): how many times cheaper a simulated second is than under WCSPH.
  double speedup_vs_wcsph = 0.0;

  double mean_dt() const { return simulated_s / double(steps); }
  double wall_per_simulated() const { return wall_s / simulated_s; }
  double per_step(long n) const { return double(n) / double(steps); }
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

int host_threads() {
#if defined(_OPENMP)
  return omp_get_max_threads();
#else
  return int(std::thread::hardware_concurrency());
#endif
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

Result run_one(const std::string& scene_dir, const Workload& w, const std::string& backend, int warmup, int steps,
               int repeats) {
  Result r;
  r.backend = backend;
  r.workload = w.name;
  r.thesis_cpu_ms = w.thesis_cpu_ms;
  r.thesis_gpu_ms = w.thesis_gpu_ms;
  std::vector<double> samples;
  for (int rep = 0; rep < repeats; ++rep) {
    // A fresh simulation each repeat: every repeat measures the same steps of the same workload.
    const Scene scene = load_scene(scene_dir + "/" + w.scene, w.sets);
    const double run_time = std::max(scene.run_time, w.simulated_s);
    r.solver = solver_name(scene.solver);
    if (w.simulated_s > 0.0 && warmup > 0) {  // warm-up on a run thrown away: the measured one starts at t = 0
      Simulation warm(scene, backend_factory(backend), run_time);
      for (int i = 0; i < warmup; ++i) warm.advance();
    }
    Simulation sim(scene, backend_factory(backend), run_time);  // set-up checks as sph_run's
    if (w.simulated_s == 0.0)
      for (int i = 0; i < warmup; ++i) sim.advance();
    const PhaseTimes before = sim.backend().phase_times();
    const SolverTotals totals_before = sim.solver_totals();
    const double t_begin = sim.time();
    // The relative margin keeps round-off in the summed time from adding a step (PBF: 0.004 s steps).
    auto measuring = [&](long done) { return w.simulated_s > 0.0 ? sim.time() < w.simulated_s * (1.0 - 1e-9) : done < steps; };
    for (long done = 0; measuring(done); ++done) {
      const auto t0 = std::chrono::steady_clock::now();
      sim.advance();
      samples.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      ++r.steps;
    }
    const PhaseTimes& after = sim.backend().phase_times();
    for (std::size_t p = 0; p < after.seconds.size(); ++p) r.phases.seconds[p] += 1e3 * (after.seconds[p] - before.seconds[p]);
    const SolverTotals& totals = sim.solver_totals();
    r.solver_iterations += totals.density_iterations - totals_before.density_iterations;
    r.divergence_iterations += totals.divergence_iterations - totals_before.divergence_iterations;
    r.capped_solves += totals.density_capped_steps - totals_before.density_capped_steps + totals.divergence_capped_steps -
                       totals_before.divergence_capped_steps;
    r.simulated_s += sim.time() - t_begin;
    r.particles = long(sim.backend().size());
  }
  for (double& s : r.phases.seconds) s /= double(r.steps);
  r.wall_s = 1e-3 * std::accumulate(samples.begin(), samples.end(), 0.0);
  r.ms_per_step = median(samples);
  r.ms_mean = std::accumulate(samples.begin(), samples.end(), 0.0) / double(samples.size());
  r.ms_min = *std::min_element(samples.begin(), samples.end());
  r.ms_max = *std::max_element(samples.begin(), samples.end());
  return r;
}

// The output folder must take files before any workload runs (a bad --out would waste the whole run).
void check_writable(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path probe = fs::path(dir) / ".sph_bench_write_check";
  std::ofstream f(probe);
  if (ec || !f || !(f << "ok\n") || !(f.flush()))
    throw std::invalid_argument("--out " + dir + ": cannot create or write files there" + (ec ? " (" + ec.message() + ")" : std::string()));
  f.close();
  fs::remove(probe, ec);
}

std::string json_escape(const std::string& s) {
  std::string out;
  for (char ch : s) out += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
  return out;
}

// The scenes the workloads load: ./scenes where sph_bench runs from a checkout (as the README does), else
// the source tree's that this binary was built from.
std::string default_scene_dir() {
  std::error_code ec;
  if (std::filesystem::is_directory("scenes", ec)) return "scenes";
  return SPH_SOURCE_DIR "/scenes";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> backends;
  std::string out = "out/bench", scene_dir = default_scene_dir();
  int warmup = 3, steps = 10, repeats = 3;
  std::vector<int> dam_sizes{20, 37, 80};  // particles across a: about 16k, 100k and 1M particles
  int dam_cuda_only = 127;                 // about 4M particles, on cuda only
  int solver_size = 20;                    // the solver workloads' dam break: about 16k particles
  double solver_time = 0.05;               // simulated seconds each solver workload measures
  bool quick = false;
  CLI::App app{"sph_bench: ms per step and particle-steps per second of fixed workloads on every back end.\n"
               "Workloads: the thesis's performance cube (16^3 and 32^3 particles, thesis 5.2 parameters), a cube of\n"
               "8,000 particles in a 0.2 m and a 50 m tank (the grid's cost against the domain's size), the\n"
               "dam break at several resolutions, and the dam break under each pressure solver: solver_wcsph,\n"
               "solver_dfsph (its CFL step, at most the scene's time_step.max), solver_pbf (fixed dt 4 ms) and\n"
               "solver_pbf_coarse (the same with pbf.coarse_grid), and under each wall model, walls_mirror and\n"
               "walls_particles (boundary particles), each\n"
               "measured over the first --solver-time simulated seconds, with wall seconds per simulated second,\n"
               "mean dt and solver iterations per step. Writes OUT/bench.csv and OUT/bench.json naming the hardware."};
  sph::use_error_prefix(app);
  app.add_option("--backends", backends, "back ends to measure (default: every usable one)");
  app.add_option("--out,-o", out, "output directory")->capture_default_str();
  app.add_option("--scenes", scene_dir,
                 "scene directory (default: ./scenes if there is one, else the source tree's, " SPH_SOURCE_DIR "/scenes)");
  app.add_option("--warmup", warmup, "steps before measuring")->capture_default_str()->check(CLI::Range(0, 100000));
  app.add_option("--steps", steps, "measured steps per repeat")->capture_default_str()->check(CLI::Range(1, 100000));
  app.add_option("--repeats", repeats, "repeats (fresh simulation each)")->capture_default_str()->check(CLI::Range(1, 1000));
  app.add_option("--dam-sizes", dam_sizes, "dam break resolutions: particles across the column width a")
      ->capture_default_str()->check(CLI::Range(4, 400));
  app.add_option("--dam-cuda", dam_cuda_only, "an extra dam break resolution for cuda only (0: none)")->capture_default_str();
  app.add_option("--solver-size", solver_size, "the solver workloads' dam break resolution: particles across the column width a")
      ->capture_default_str()->check(CLI::Range(4, 400));
  app.add_option("--solver-time", solver_time,
                 "simulated seconds each solver workload measures, from t = 0 (after a warm-up run of --warmup steps "
                 "that is thrown away); --steps does not apply to them")
      ->capture_default_str()->check(CLI::Range(1e-4, 10.0));
  app.add_flag("--quick", quick, "small and short: a smoke test (under a minute)");
  std::vector<std::string> only;
  app.add_option("--workload,-w", only, "run only these workloads (repeatable; names as in the table)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;  // --help: 0; every parse error is bad input (CLI11's own codes are 100+)
  }
  if (quick) {
    warmup = 1;
    steps = 2;
    repeats = 1;
    dam_sizes = {10};
    dam_cuda_only = 0;
    solver_size = 10;
    solver_time = 0.008;  // two PBF steps
  }
  std::vector<Workload> workloads{
      {"thesis_cube_16", "thesis_perf_cube.json", {}, 241.0, 3.0, false, 0.0},
      {"thesis_cube_32", "thesis_perf_cube_32.json", {}, 2677.0, 18.0, false, 0.0}};
  if (quick) workloads.pop_back();
  for (int n : dam_sizes)
    workloads.push_back({"dam_break_" + std::to_string(n), "dam_break.json",
                         {"resolution.particles_across=" + std::to_string(n)}, 0.0, 0.0, false, 0.0});
  if (dam_cuda_only > 0)
    workloads.push_back({"dam_break_" + std::to_string(dam_cuda_only), "dam_break.json",
                         {"resolution.particles_across=" + std::to_string(dam_cuda_only)}, 0.0, 0.0, true, 0.0});
  // The dam break under each pressure solver (issue 12): WCSPH and DFSPH with their adaptive steps, PBF at
  // one 60 Hz frame in four substeps. Not named dam_break_*: studies.py's scaling chart takes those.
  const std::string across = "resolution.particles_across=" + std::to_string(solver_size);
  workloads.push_back({"solver_wcsph", "dam_break.json", {across, "solver=wcsph"}, 0.0, 0.0, false, solver_time});
  workloads.push_back({"solver_dfsph", "dam_break.json", {across, "solver=dfsph"}, 0.0, 0.0, false, solver_time});
  workloads.push_back({"solver_pbf", "dam_break.json", {across, "solver=pbf", "time_step.mode=fixed", "time_step.dt=0.004"},
                       0.0, 0.0, false, solver_time});
  workloads.push_back({"solver_pbf_coarse", "dam_break.json",
                       {across, "solver=pbf", "time_step.mode=fixed", "time_step.dt=0.004", "pbf.coarse_grid=true"}, 0.0,
                       0.0, false, solver_time});
  // The wall models on the same dam break (issue 13: boundary particles at most 1.3 times mirror walls per
  // step), over the same stretch of the flow.
  for (const char* walls : {"mirror", "particles"})
    workloads.push_back({std::string("walls_") + walls, "dam_break.json", {across, std::string("sph.walls=") + walls}, 0.0,
                         0.0, false, solver_time});
  // The same 0.1 m cube of 8,000 particles in a 0.2 m and a 50 m tank: the grid's cost must follow the
  // particles, not the domain (issue 11, item 7: at most 1.5 times).
  if (!quick)
    for (const char* side : {"0.2", "50"})
      workloads.push_back({std::string("cube_tank_") + side + "m", "dam_break.json",
                           {"emitters.0.min=[0.05,0,0.05]", "emitters.0.max=[0.15,0.1,0.15]",
                            std::string("boundaries.0.max=[") + side + "," + side + "," + side + "]",
                            "resolution.particles_across=20"},
                           0.0, 0.0, false, 0.0});

  // Every argument is checked before the first workload runs.
  if (!only.empty()) {
    std::string names;
    for (const Workload& w : workloads) names += (names.empty() ? "" : ", ") + w.name;
    for (const std::string& name : only)
      if (std::none_of(workloads.begin(), workloads.end(), [&](const Workload& w) { return w.name == name; })) {
        std::cerr << "error: unknown --workload \"" << name << "\"; workloads" << (quick ? " with --quick" : "") << ": " << names << "\n";
        return 1;
      }
    workloads.erase(std::remove_if(workloads.begin(), workloads.end(),
                                   [&](const Workload& w) { return std::find(only.begin(), only.end(), w.name) == only.end(); }),
                    workloads.end());
  }
  try {
    for (const std::string& b : backends) (void)backend_factory(b);  // unknown, not built, or no GPU
    for (const Workload& w : workloads) (void)load_scene(scene_dir + "/" + w.scene, w.sets);  // --scenes, --dam-sizes
    check_writable(out);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  if (backends.empty()) {
    backends.push_back("cpu");
    for (const std::string& b : available_backends()) {
      if (b == "cpu") continue;
      std::string why;
      if (b == "cuda" && !cuda_device_available(&why)) {
        std::cerr << "cuda: skipped (" << why << ")\n";
        continue;
      }
      backends.push_back(b);
    }
  }

  const std::string cpu = cpu_model(), gpu = cuda_device_name();
  std::cout << "CPU: " << cpu << ", host threads: " << host_threads() << "\nGPU: " << (gpu.empty() ? "none" : gpu)
            << "\nwarm-up " << warmup << " steps, " << steps << " measured steps x " << repeats
            << " repeats; ms/step: median of the measured steps, time by phase: mean\nsolver workloads: the dam break at "
            << solver_size << " particles across from t = 0 to " << solver_time << " s, after a warm-up run thrown away\n\n";

  std::vector<Result> results;
  try {
    for (const Workload& w : workloads) {
      double cpu_ms = 0.0;
      for (const std::string& b : backends) {
        if (w.cuda_only && b != "cuda") continue;
        std::cerr << "  " << w.name << " on " << b << " ..." << std::flush;
        Result r = run_one(scene_dir, w, b, warmup, steps, repeats);
        std::cerr << " " << r.ms_per_step << " ms/step\n";
        if (b == "cpu") cpu_ms = r.ms_per_step;
        r.speedup_vs_cpu = cpu_ms > 0.0 ? cpu_ms / r.ms_per_step : 0.0;
        results.push_back(r);
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return 1;
  }
  for (Result& r : results) {
    if (r.workload.rfind("solver_", 0) != 0) continue;
    for (const Result& base : results)
      if (base.workload == "solver_wcsph" && base.backend == r.backend)
        r.speedup_vs_wcsph = base.wall_per_simulated() / r.wall_per_simulated();
  }

  std::printf("\n%-8s %-16s %10s %11s %14s %9s %11s %11s\n", "backend", "workload", "particles", "ms/step",
              "particle-st/s", "vs cpu", "vs thesis", "vs thesis");
  std::printf("%-8s %-16s %10s %11s %14s %9s %11s %11s\n", "", "", "", "(median)", "", "", "CPU", "GTX 480");
  for (const Result& r : results) {
    char vs_cpu[32] = "-", vs_tc[32] = "-", vs_tg[32] = "-";
    if (r.speedup_vs_cpu > 0.0) std::snprintf(vs_cpu, sizeof vs_cpu, "%.2fx", r.speedup_vs_cpu);
    if (r.thesis_cpu_ms > 0.0) std::snprintf(vs_tc, sizeof vs_tc, "%.0fx", r.thesis_cpu_ms / r.ms_per_step);
    if (r.thesis_gpu_ms > 0.0) std::snprintf(vs_tg, sizeof vs_tg, "%.2fx", r.thesis_gpu_ms / r.ms_per_step);
    std::printf("%-8s %-16s %10ld %11.3f %14.3e %9s %11s %11s\n", r.backend.c_str(), r.workload.c_str(), r.particles,
                r.ms_per_step, 1e3 * double(r.particles) / r.ms_per_step, vs_cpu, vs_tc, vs_tg);
  }
  std::printf("\ntime by phase, mean ms per step (the mean of the whole step is ms_mean in the CSV):\n%-8s %-16s",
              "backend", "workload");
  for (int p = 0; p < int(Phase::Count); ++p) std::printf(" %10s", phase_name(Phase(p)));
  std::printf("\n");
  for (const Result& r : results) {
    std::printf("%-8s %-16s", r.backend.c_str(), r.workload.c_str());
    for (int p = 0; p < int(Phase::Count); ++p) std::printf(" %10.3f", r.phases.seconds[std::size_t(p)]);
    std::printf("\n");
  }
  std::printf("\ntime steps and solver iterations of the measured steps (wall s per simulated s: their summed wall time\n"
              "over the simulated time they covered; solver iterations: DFSPH's density solve, PBF's constraint solve):\n"
              "%-8s %-16s %-6s %7s %11s %12s %12s %9s %11s %11s %7s\n", "backend", "workload", "solver", "steps", "mean dt ms",
              "sim s/wall s", "wall s/sim s", "vs wcsph", "solver it.", "diverg. it.", "capped");
  for (const Result& r : results) {
    char vs_wcsph[32] = "-";
    if (r.speedup_vs_wcsph > 0.0) std::snprintf(vs_wcsph, sizeof vs_wcsph, "%.2fx", r.speedup_vs_wcsph);
    std::printf("%-8s %-16s %-6s %7ld %11.4f %12.4f %12.2f %9s %11.2f %11.2f %7ld\n", r.backend.c_str(), r.workload.c_str(),
                r.solver.c_str(), r.steps, 1e3 * r.mean_dt(), 1.0 / r.wall_per_simulated(), r.wall_per_simulated(), vs_wcsph,
                r.per_step(r.solver_iterations), r.per_step(r.divergence_iterations), r.capped_solves);
  }
  for (const Result& r : results) {
    if (r.workload != "walls_particles") continue;
    for (const Result& base : results)
      if (base.workload == "walls_mirror" && base.backend == r.backend)
        std::printf("%s: boundary particles cost %.2f times mirror walls per step (mean ms/step %.3f / %.3f)\n",
                    r.backend.c_str(), r.ms_mean / base.ms_mean, r.ms_mean, base.ms_mean);
  }

  std::error_code ec;
  fs::create_directories(out, ec);
  std::ofstream csv(fs::path(out) / "bench.csv"), js(fs::path(out) / "bench.json");
  if (!csv || !js) {
    std::cerr << "error: cannot write results into " << out << "\n";
    return 1;
  }
  csv << "backend,workload,particles,ms_per_step,ms_mean,ms_min,ms_max,particle_steps_per_second,speedup_vs_cpu,thesis_cpu_ms,thesis_gpu_ms"
      << ",solver,steps_measured,simulated_s,mean_dt_s,wall_s_per_simulated_s,simulated_s_per_wall_s,speedup_vs_wcsph"
      << ",solver_iterations_per_step,divergence_iterations_per_step,capped_solves";
  for (int p = 0; p < int(Phase::Count); ++p) csv << ",ms_" << phase_name(Phase(p));
  csv << ",cpu,host_threads,gpu\n";
  js << "{\n  \"cpu\": \"" << json_escape(cpu) << "\",\n  \"host_threads\": " << host_threads() << ",\n  \"gpu\": \""
     << json_escape(gpu) << "\",\n  \"warmup\": " << warmup << ", \"steps\": " << steps << ", \"repeats\": " << repeats
     << ",\n  \"solver_size\": " << solver_size << ", \"solver_time\": " << solver_time
     << ",\n  \"statistics\": \"ms_per_step: median of the measured steps; ms_mean and phases_ms: mean per step; "
        "wall_s_per_simulated_s: the measured steps' summed wall time over the simulated time they covered; "
        "solver_iterations_per_step: DFSPH's density solve or PBF's constraint solve, mean over the measured steps\""
     << ",\n  \"results\": [\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Result& r = results[i];
    const double pss = 1e3 * double(r.particles) / r.ms_per_step;
    csv << r.backend << ',' << r.workload << ',' << r.particles << ',' << r.ms_per_step << ',' << r.ms_mean << ',' << r.ms_min << ','
        << r.ms_max << ',' << pss << ',' << r.speedup_vs_cpu << ',' << r.thesis_cpu_ms << ',' << r.thesis_gpu_ms << ',' << r.solver
        << ',' << r.steps << ',' << r.simulated_s << ',' << r.mean_dt() << ',' << r.wall_per_simulated() << ','
        << 1.0 / r.wall_per_simulated() << ',' << r.speedup_vs_wcsph << ',' << r.per_step(r.solver_iterations) << ','
        << r.per_step(r.divergence_iterations) << ',' << r.capped_solves;
    js << "    {\"backend\": \"" << r.backend << "\", \"workload\": \"" << r.workload << "\", \"particles\": " << r.particles
       << ", \"ms_per_step\": " << r.ms_per_step << ", \"ms_mean\": " << r.ms_mean << ", \"ms_min\": " << r.ms_min << ", \"ms_max\": " << r.ms_max
       << ", \"particle_steps_per_second\": " << pss << ", \"speedup_vs_cpu\": " << r.speedup_vs_cpu << ", \"solver\": \""
       << r.solver << "\", \"steps_measured\": " << r.steps << ", \"simulated_s\": " << r.simulated_s << ", \"mean_dt_s\": "
       << r.mean_dt() << ", \"wall_s_per_simulated_s\": " << r.wall_per_simulated() << ", \"simulated_s_per_wall_s\": "
       << 1.0 / r.wall_per_simulated() << ", \"speedup_vs_wcsph\": " << r.speedup_vs_wcsph
       << ", \"solver_iterations_per_step\": " << r.per_step(r.solver_iterations)
       << ", \"divergence_iterations_per_step\": " << r.per_step(r.divergence_iterations)
       << ", \"capped_solves\": " << r.capped_solves << ", \"phases_ms\": {";
    for (int p = 0; p < int(Phase::Count); ++p) {
      csv << ',' << r.phases.seconds[std::size_t(p)];
      js << (p ? ", " : "") << '"' << phase_name(Phase(p)) << "\": " << r.phases.seconds[std::size_t(p)];
    }
    csv << ",\"" << cpu << "\"," << host_threads() << ",\"" << (gpu.empty() ? "none" : gpu) << "\"\n";
    js << "}}" << (i + 1 < results.size() ? "," : "") << "\n";
  }
  js << "  ]\n}\n";
  std::cout << "\nwritten: " << (fs::path(out) / "bench.csv").string() << ", " << (fs::path(out) / "bench.json").string() << "\n";
  return 0;
}
