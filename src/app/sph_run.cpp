// sph_run: the headless runner. Loads a scene, runs it on a back end, writes metrics.csv and optional PLY
// frames, shows progress on a terminal, and prints a summary (particles, steps, median ms per step).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "../common/frame_writer.h"
#include "../common/metrics.h"
#include "../common/simulation.h"
#include "backends.h"

namespace fs = std::filesystem;
using namespace sph;

namespace {

struct Options {
  std::string scene;
  std::string backend = "cpu";
  double time = -1.0;
  long steps = -1;
  std::string out = "out";
  double frames_every = -1.0;
  double metrics_every = 0.0;
  std::vector<std::string> sets;
  bool quiet = false;
};

const char* limit_name(StepLimit l) {
  switch (l) {
    case StepLimit::Fixed: return "fixed";
    case StepLimit::Velocity: return "velocity CFL";
    case StepLimit::Acceleration: return "acceleration";
    case StepLimit::Sound: return "sound speed";
    case StepLimit::Viscosity: return "viscosity";
    case StepLimit::Minimum: return "dt_min";
    case StepLimit::Maximum: return "dt_max";
  }
  return "?";
}

void write_metrics_row(std::ofstream& csv, const Simulation& sim, const Metrics& m, double wall_ms) {
  csv << sim.time() << ',' << sim.last_dt() << ',' << sim.steps() << ',' << m.kinetic_energy << ',' << m.potential_energy
      << ',' << sim.energy_budget() << ',' << m.density_error_mean << ',' << m.density_error_max << ',' << m.v_max << ','
      << m.front_x << ',' << m.top_y << ',' << m.height_at_x0 << ',' << m.particles << ',' << wall_ms << '\n';
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

int run(const Options& o) {
  Scene scene = load_scene(o.scene, o.sets);
  const double run_time = o.time > 0.0 ? o.time : scene.run_time;
  const bool by_steps = o.steps > 0;
  const double frames_every = o.frames_every >= 0.0 ? o.frames_every : scene.frames_every;
  BackendFactory factory = backend_factory(o.backend);

  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) throw std::runtime_error("cannot create output directory " + o.out + ": " + ec.message());
  const std::string csv_path = (fs::path(o.out) / "metrics.csv").string();
  std::ofstream csv(csv_path);
  if (!csv) throw std::runtime_error("cannot write " + csv_path);
  csv.precision(9);
  csv << "time,dt,step,kinetic_energy,potential_energy,energy_budget,density_error_mean,density_error_max,v_max,front_x,"
         "top_y,height_at_x0,particles,wall_ms\n";

  Simulation sim(scene, factory, run_time);
  const Setup& st = sim.setup();
  std::cout << "scene: " << scene.name << " (" << o.scene << ")\n"
            << "backend: " << sim.backend().name() << "\n"
            << "spacing: " << st.spacing << " m, h: " << st.h << " m, neighbours: " << scene.neighbours
            << ", lattice kernel sum: " << st.lattice_density << "\n"
            << "grid: " << st.constants.grid.nx << " x " << st.constants.grid.ny << " x " << st.constants.grid.nz
            << " cells of " << st.constants.grid.cell_size << " m\n"
            << "integrator: " << integrator_name(scene.integrator) << ", speed bound: " << sim.speed_bound()
            << " m/s, energy budget: " << sim.energy_budget() << " J\n"
            << (sim.relaxation().ran ? sim.relaxation().summary() + "\n" : std::string())
            << "run: " << (by_steps ? std::to_string(o.steps) + " steps" : std::to_string(run_time) + " s simulated")
            << ", output: " << o.out << "\n";
  std::cout.flush();

  int frame = 0;
  auto write_frame = [&] {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%05d.ply", frame++);
    write_ply_frame((fs::path(o.out) / name).string(), sim.particles(), sim.time());
  };
  double next_frame = 0.0, next_metrics = 0.0;
  if (frames_every > 0.0) {
    write_frame();
    next_frame = frames_every;
  }
  write_metrics_row(csv, sim, measure(st.constants, sim.particles(), sim.potential_reference()), 0.0);
  next_metrics = o.metrics_every;

  const bool tty = isatty(STDERR_FILENO) && !o.quiet;
  std::vector<double> step_ms;
  const auto start = std::chrono::steady_clock::now();
  auto last_progress = start;
  int status = 0;
  while (by_steps ? sim.steps() < o.steps : sim.time() < run_time - 1e-12) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      sim.advance();
    } catch (const BlowUp& e) {
      if (tty) std::cerr << '\n';
      std::cerr << "error: " << e.what() << "\n";
      status = 3;
      break;
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    step_ms.push_back(ms);
    if (sim.time() >= next_metrics - 1e-12) {
      write_metrics_row(csv, sim, measure(st.constants, sim.particles(), sim.potential_reference()), ms);
      next_metrics = sim.time() + o.metrics_every;
    }
    if (frames_every > 0.0 && sim.time() >= next_frame - 1e-12) {
      write_frame();
      next_frame += frames_every;
    }
    if (tty && std::chrono::duration<double>(t1 - last_progress).count() > 0.25) {
      last_progress = t1;
      const double wall = std::chrono::duration<double>(t1 - start).count();
      const double frac = by_steps ? double(sim.steps()) / o.steps : sim.time() / run_time;
      const double eta = frac > 0 ? wall * (1.0 - frac) / frac : 0.0;
      std::fprintf(stderr, "\r  t = %.4f s  step %ld  dt = %.2e s (%s)  %.1f steps/s  %zu particles  %3.0f%%  ETA %.0f s   ",
                   sim.time(), sim.steps(), sim.last_dt(), limit_name(sim.last_limit()), sim.steps() / wall,
                   sim.backend().size(), 100.0 * frac, eta);
    }
  }
  if (tty) std::fprintf(stderr, "\n");
  csv.flush();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Metrics m = measure(st.constants, sim.particles(), sim.potential_reference());
  const double med = median(step_ms);
  std::cout << "simulated_time: " << sim.time() << "\n"
            << "particles: " << sim.backend().size() << "\n"
            << "steps: " << sim.steps() << "\n"
            << "ms_per_step: " << med << "\n"
            << "particle_steps_per_second: " << (med > 0 ? 1e3 * double(sim.backend().size()) / med : 0.0) << "\n"
            << "wall_seconds: " << wall << "\n"
            << "kinetic_energy: " << m.kinetic_energy << "\n"
            << "density_error_mean: " << m.density_error_mean << "\n"
            << "density_error_max: " << m.density_error_max << "\n"
            << "front_x: " << m.front_x << "\n";
  const PhaseTimes& pt = sim.backend().phase_times();
  if (pt.steps > 0) {
    std::cout << "phase_ms_per_step:";
    for (int p = 0; p < int(Phase::Count); ++p)
      std::cout << ' ' << phase_name(Phase(p)) << '=' << 1e3 * pt.seconds[std::size_t(p)] / double(pt.steps);
    std::cout << "\n";
  }
  std::cout << "metrics: " << csv_path << (frame > 0 ? ", frames: " + std::to_string(frame) : std::string()) << "\n";
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "sph_run: run an SPH scene headless and record what happens.\n\n"
      "Writes OUT/metrics.csv (time, dt, step, kinetic_energy, potential_energy, energy_budget, density_error_mean,\n"
      "density_error_max, v_max, front_x, top_y, height_at_x0, particles, wall_ms) and, with --frames-every, PLY point clouds OUT/frame_NNNNN.ply\n"
      "(ParaView, Blender). Ends with a summary: particles, steps, median ms_per_step, time by phase.\n"
      "Exit status: 0 done, 1 bad input, 3 the simulation became unstable."};
  app.add_option("scene", o.scene, "scene file (JSON), for example scenes/dam_break.json")->required();
  app.add_option("--backend,-b", o.backend, "back end: " + [] {
    std::string s;
    for (const auto& b : available_backends()) s += (s.empty() ? "" : ", ") + b;
    return s;
  }())->capture_default_str();
  auto* t = app.add_option("--time,-t", o.time, "simulated seconds to run (default: the scene's run.time)");
  auto* n = app.add_option("--steps,-n", o.steps, "number of steps to run instead of a time");
  t->excludes(n);
  app.add_option("--out,-o", o.out, "output directory")->capture_default_str();
  app.add_option("--frames-every", o.frames_every, "write a PLY frame every this many simulated seconds (0: none)");
  app.add_option("--metrics-every", o.metrics_every, "write a metrics row at most every this many simulated seconds (0: every step)");
  app.add_option("--set,-s", o.sets,
                 "override a scene value, key=value with a dotted path, repeatable; for example\n"
                 "--set fluids.0.viscosity=0.01 --set resolution.particles_across=40 --set integrator=leapfrog");
  app.add_flag("--quiet,-q", o.quiet, "no progress line");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (o.time == 0.0 || (o.time < 0.0 && app.count("--time"))) {
    std::cerr << "error: --time must be positive\n";
    return 1;
  }
  if (app.count("--steps") && o.steps <= 0) {
    std::cerr << "error: --steps must be positive\n";
    return 1;
  }
  if (!(o.metrics_every >= 0.0) || (app.count("--frames-every") && !(o.frames_every >= 0.0))) {
    std::cerr << "error: --metrics-every and --frames-every must be zero or positive\n";
    return 1;
  }
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
