// sph_run: the headless runner. Loads a scene, runs it on a back end, writes metrics.csv and optional PLY
// frames, shows progress on a terminal, and prints a summary (particles, steps, ms per step).
// Nothing is lost silently: every write is checked (exit 4), SIGINT / SIGTERM stop after the current step
// with the output flushed (exit 130 / 143), and a non-finite state never ends with exit 0.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <new>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "../common/frame_reader.h"
#include "../common/frame_writer.h"
#include "../common/metrics.h"
#include "../common/solid_penetration.h"
#include "../common/setup_budget.h"
#include "../common/simulation.h"
#include "backends.h"
#include "cli_errors.h"
#include "metrics_file.h"
#include "option_values.h"
#include "run_report.h"
#include "state_checks.h"
#include "stop_signals.h"
#include "surface_output.h"

namespace fs = std::filesystem;
using namespace sph;

namespace {

// Exit statuses (documented in --help and the README); a stop by signal N exits with 128 + N.
constexpr int kDone = 0, kBadInput = 1, kUnstable = 3, kOutputFailed = 4;

// Limits of the numeric options: longer runs are taken as mistakes (the scene's run.time has the same bound).
constexpr double kMaxTime = 1e7;          // simulated seconds
constexpr long long kMaxSteps = 1000000000000LL;

struct Options {
  std::string scene;
  std::string backend = "cpu";
  double time = -1.0;      // < 0: the scene's run.time
  long long steps = -1;    // < 0: run by time
  std::string out = "out";
  double frames_every = -1.0;  // < 0: the scene's run.frames_every
  double metrics_every = 0.0;
  double surface_every = 0.0;       // > 0: a surface mesh OUT/surface_NNNNN.ply every this many seconds
  double surface_resolution = 2.0;  // voxels per particle spacing
  std::vector<std::string> sets;
  bool quiet = false;
  std::string restart;  // frame to continue from
};

const char* limit_name(StepLimit l) {
  switch (l) {
    case StepLimit::Fixed: return "fixed";
    case StepLimit::Velocity: return "velocity CFL";
    case StepLimit::Acceleration: return "acceleration";
    case StepLimit::Sound: return "sound speed";
    case StepLimit::Viscosity: return "viscosity";
    case StepLimit::Springs: return "springs";
    case StepLimit::Minimum: return "dt_min";
    case StepLimit::Maximum: return "dt_max";
  }
  return "?";
}

const char* const kMetricsHeader =
    "time,dt,step,kinetic_energy,potential_energy,energy_budget,density_error_mean,density_error_max,v_max,front_x,"
    "top_y,height_at_x0,particles,outside_domain,wall_ms,solver_iterations,solver_density_error,divergence_iterations,"
    "divergence_error,deepest_in_solid,particles_in_solids";

// The header with a depth_<name> column per probe of the scene, then per rigid body k its centre, velocity,
// orientation quaternion and the fluid's force on it: body<k>_x, _y, _z [m], _vx, _vy, _vz [m/s], _qw, _qx,
// _qy, _qz, _fx, _fy, _fz [N].
std::string metrics_header(const Scene& scene) {
  std::string header = kMetricsHeader;
  for (const ProbeSpec& p : scene.probes) header += ",depth_" + p.name;
  for (std::size_t k = 0; k < scene.bodies.size(); ++k)
    for (const char* q : {"x", "y", "z", "vx", "vy", "vz", "qw", "qx", "qy", "qz", "fx", "fy", "fz"})
      header += ",body" + std::to_string(k) + "_" + q;
  return header;
}

// Writes one row, the probes' depths (metrics.h, probe_depth) last, and updates the extremes.
void write_metrics_row(MetricsFile& csv, Simulation& sim, const std::vector<ProbeSpec>& probes, double wall_ms,
                       RowExtremes& worst) {
  const Setup& setup = sim.setup();
  const SimConstants& c = setup.constants;
  const Metrics m = measure(c, sim.particles(), sim.potential_reference());
  const Penetration pen = solid_penetration(c, setup.meshes, sim.backend().bodies(), sim.particles(), 0.5 * setup.spacing);
  worst.most_outside = std::max(worst.most_outside, m.outside_domain);
  worst.deepest = std::max(worst.deepest, pen.deepest);
  worst.most_in_solids = std::max(worst.most_in_solids, pen.count);
  std::ostringstream row;
  row.precision(9);
  row << sim.time() << ',' << sim.last_dt() << ',' << sim.steps() << ',' << m.kinetic_energy << ',' << m.potential_energy
      << ',' << sim.energy_budget() << ',' << m.density_error_mean << ',' << m.density_error_max << ',' << m.v_max << ',' << m.front_x << ',' << m.top_y
      << ',' << m.height_at_x0 << ',' << m.particles << ',' << m.outside_domain << ',' << wall_ms;
  const SolverStats& st = sim.solver_stats();  // the last step's solves (zero under WCSPH)
  row << ',' << st.density_iterations << ',' << st.density_error << ',' << st.divergence_iterations << ','
      << st.divergence_error << ',' << pen.deepest << ',' << pen.count;
  for (const ProbeSpec& p : probes) row << ',' << probe_depth(c, sim.particles(), p.position);
  for (std::size_t k = 0; k < sim.scene().bodies.size(); ++k) {  // the scene's bodies (not the demo's drops)
    const RigidBody& b = sim.backend().bodies().at(k);
    for (const double v : {b.centre[0], b.centre[1], b.centre[2], b.velocity[0], b.velocity[1], b.velocity[2], b.orientation[0],
                           b.orientation[1], b.orientation[2], b.orientation[3], b.force[0], b.force[1], b.force[2]})
      row << ',' << v;
  }
  csv.write_row(row.str());
}

// --restart: the frame to continue from (nullptr without the option), read and checked before the
// simulation is set up.
std::unique_ptr<Frame> restart_frame(const Options& o, const Scene& scene) {
  if (o.restart.empty()) return nullptr;
  return std::make_unique<Frame>(read_ply_frame(o.restart, scene.max_particles));
}

// Time of the next frame after frame `index`, by the same repeated sum as an uninterrupted run.
double frame_time_after(int index, double frames_every) {
  double t = frames_every;
  for (int i = 0; i < index; ++i) t += frames_every;
  return t;
}

// Set-up turns its own std::bad_alloc into "out of memory" with its estimate; the back end allocates its
// arrays after set-up, so where those do not fit, set-up is repeated for its estimate (it fitted before).
Simulation make_simulation(const Scene& scene, const BackendFactory& factory, double run_time, const Frame* restart) {
  try {
    return Simulation(scene, factory, run_time, restart);
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(out_of_memory_text(scene, create_setup(scene, run_time).expected_particles));
  }
}

// Refuses a set-up whose state is already NaN or infinite: the first step would only blame the time step.
void check_initial_state(const Scene& scene, Simulation& sim) {
  const std::string bad = describe_non_finite(sim.particles());
  if (bad.empty()) return;
  std::ostringstream os;
  os << scene.source << ": the state right after set-up is not finite: " << bad
     << ". Likely cause: a spacing (here " << sim.setup().spacing << " m, h = " << sim.setup().h
     << " m) whose kernel coefficients or masses leave single precision's range, or particles created on top of "
        "each other; change resolution or the emitters";
  throw SceneError(os.str());
}

int run(const Options& o) {
  Scene scene = load_scene(o.scene, o.sets);
  const double run_time = o.time > 0.0 ? o.time : scene.run_time;
  const bool by_steps = o.steps > 0;
  const double frames_every = o.frames_every >= 0.0 ? o.frames_every : scene.frames_every;
  BackendFactory factory = backend_factory(o.backend);

  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) throw OutputError("cannot create the output directory " + o.out + ": " + ec.message());
  const std::unique_ptr<Frame> restart = restart_frame(o, scene);
  // A continued run keeps the rows of metrics.csv up to its frame's step and appends after them.
  if (restart && (by_steps ? o.steps <= restart->info.step : run_time <= restart->info.time)) {
    std::ostringstream os;
    os << o.restart << ": the frame is at step " << restart->info.step << ", t = " << restart->info.time
       << " s, already past the end asked (" << (by_steps ? "--steps " + std::to_string(o.steps) : "--time " + std::to_string(run_time))
       << "); --time and --steps count from the original start";
    throw SceneError(os.str());
  }
  MetricsFile csv((fs::path(o.out) / "metrics.csv").string(), metrics_header(scene), restart ? restart->info.step : -1,
                  restart ? restart->info.time : 0.0);

  Simulation sim = make_simulation(scene, factory, run_time, restart.get());
  check_initial_state(scene, sim);
  print_setup(RunDescription{o.scene, o.out, o.restart, by_steps, o.steps, run_time}, scene, sim, restart.get());
  const Setup& st = sim.setup();

  int frame = restart ? restart->info.frame_index + 1 : 0;  // a continued run numbers on
  const int first_frame = frame;
  auto write_frame = [&] {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%05d.ply", frame);
    try {
      write_ply_frame((fs::path(o.out) / name).string(), sim.particles(), sim.frame_info(frame));
    } catch (const std::runtime_error& e) {
      throw OutputError(e.what());
    }
    ++frame;
  };
  int surfaces_written = 0;
  int surface = 0;  // surface_NNNNN.ply holds the surface at time NNNNN x --surface-every (so a restart numbers on)
  auto write_surface_mesh = [&] {
    const ParticleState& ps = sim.particles();
    const std::string path = (fs::path(o.out) / surface_file_name(surface)).string();
    try {
      write_surface(path, std::vector<Vec3>(ps.pos.begin(), ps.pos.end()), st.spacing, o.surface_resolution, sim.time());
    } catch (const std::runtime_error& e) {
      throw OutputError(e.what());
    }
    ++surface;
    ++surfaces_written;
  };

  // From here on a signal stops the run after the current step; during the set-up above it ends the
  // program at once (the set-up may take minutes, and nothing but the metrics header is written then).
  install_stop_handlers();
  const bool tty = isatty(STDERR_FILENO) && !o.quiet;
  std::vector<double> step_ms;
  RowExtremes worst;  // the worst of the metrics rows
  const auto start = std::chrono::steady_clock::now();
  auto last_progress = start;
  int status = kDone;
  std::string output_error;
  try {
    double next_frame = 0.0, next_metrics = 0.0, next_surface = 0.0;
    if (o.surface_every > 0.0) {
      surface = int(std::llround(sim.time() / o.surface_every));
      write_surface_mesh();
      next_surface = sim.time() + o.surface_every;
    }
    if (frames_every > 0.0) {
      if (!restart) write_frame();  // a continued run starts from a frame that already exists
      next_frame = frame_time_after(restart ? restart->info.frame_index : 0, frames_every);
    }
    long last_row_step = sim.steps();  // the last step metrics.csv has a row for
    double last_ms = 0.0;
    if (!csv.continued())
      write_metrics_row(csv, sim, scene.probes, 0.0, worst);
    next_metrics = o.metrics_every;
    while (!stop_requested() && (by_steps ? sim.steps() < o.steps : sim.time() < run_time - 1e-12)) {
      const auto t0 = std::chrono::steady_clock::now();
      try {
        sim.advance();
      } catch (const BlowUp& e) {
        if (tty) std::cerr << '\n';
        std::cerr << "error: " << e.what() << "\n";
        status = kUnstable;
        break;
      }
      const auto t1 = std::chrono::steady_clock::now();
      const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
      step_ms.push_back(ms);
      last_ms = ms;
      if (sim.time() >= next_metrics - 1e-12) {
        write_metrics_row(csv, sim, scene.probes, ms, worst);
        next_metrics = sim.time() + o.metrics_every;
        last_row_step = sim.steps();
      }
      csv.flush_if_due();
      if (frames_every > 0.0 && sim.time() >= next_frame - 1e-12) {
        write_frame();
        next_frame += frames_every;
      }
      if (o.surface_every > 0.0 && sim.time() >= next_surface - 1e-12) {
        write_surface_mesh();
        next_surface += o.surface_every;
      }
      if (tty && std::chrono::duration<double>(t1 - last_progress).count() > 0.25) {
        last_progress = t1;
        const double wall = std::chrono::duration<double>(t1 - start).count();
        const double frac = by_steps ? double(sim.steps()) / double(o.steps) : sim.time() / run_time;
        const double eta = frac > 0 && frac < 1 ? wall * (1.0 - frac) / frac : 0.0;  // never "-0 s"
        std::fprintf(stderr, "\r  t = %.4f s  step %ld  dt = %.2e s (%s)  %.1f steps/s  %zu particles  %3.0f%%  ETA %.0f s   ",
                     sim.time(), sim.steps(), sim.last_dt(), limit_name(sim.last_limit()), sim.steps() / wall,
                     sim.backend().size(), 100.0 * frac, eta);
      }
    }
    // The final state always has its row, whatever --metrics-every skipped (and a blown-up one shows how).
    if (sim.steps() != last_row_step)
      write_metrics_row(csv, sim, scene.probes, last_ms, worst);
    csv.close();
  } catch (const OutputError& e) {
    output_error = e.what();
    status = kOutputFailed;
  }
  if (tty) std::fprintf(stderr, "\n");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const ParticleState& final_state = sim.particles();
  const Metrics m = measure(st.constants, final_state, sim.potential_reference());

  if (const int sig = stop_requested(); sig != 0 && status == kDone) {
    std::cout << "interrupted: " << stop_signal_name(sig) << " at t = " << sim.time() << " s (step " << sim.steps()
              << "); the output written so far is complete\n";
    status = 128 + sig;
  }
  worst.most_outside = std::max(worst.most_outside, m.outside_domain);
  print_summary(sim, m, step_ms, wall, worst);
  if (worst.deepest > sim.setup().spacing)
    std::cerr << "warning: fluid got " << worst.deepest / sim.setup().spacing << " spacings deep into a solid (deeper than "
              << "one spacing is past a wall's first layer of boundary particles, where the wall no longer holds it: a "
              << "leak; deepest_in_solid and particles_in_solids in metrics.csv say when). A finer resolution, "
              << "thicker walls or a smaller time_step.max may help\n";
  if (worst.most_outside > 0) {
    // The domain of guided creation (make_grid): the scene's "domain", else its first box container, else the
    // fluid's start with half its size around it.
    bool container = sim.scene().has_domain;
    for (const BoundarySpec& b : sim.scene().boundaries) container = container || (b.shape.type == ShapeType::Box && b.shape.keep_inside);
    std::cerr << "warning: " << worst.most_outside << " particles left the domain ("
              << (container ? "the container or \"domain\" with a band of 2 h); they are still simulated, but the domain "
                              "does not enclose the fluid: check the boundaries\n"
                            : "no box container or \"domain\" given: the fluid's start with half its size around it and a "
                              "band of 2 h); they are still simulated. Give \"domain\" to enclose where the fluid goes, or "
                              "look in the frames for particles thrown off the fluid's surface\n");
  }
  std::cout << "metrics: " << csv.path() << (frame > first_frame ? ", frames: " + std::to_string(frame - first_frame) : std::string())
            << (surfaces_written > 0 ? ", surface meshes: " + std::to_string(surfaces_written) : std::string()) << "\n";
  std::cout.flush();

  if (status == kOutputFailed) {
    std::cerr << "error: " << output_error << " (the run stopped at t = " << sim.time() << " s, step " << sim.steps()
              << ")\n";
  } else if (status != kUnstable) {
    const std::string bad = describe_non_finite(final_state);
    if (!bad.empty() || !std::isfinite(m.kinetic_energy)) {
      std::cerr << "error: the final state at t = " << sim.time() << " s (step " << sim.steps() << ") is not finite: "
                << (bad.empty() ? "kinetic energy " + std::to_string(m.kinetic_energy) : bad)
                << ". Try a smaller time step (time_step.dt, time_step.max or the CFL factors) or more viscosity.\n";
      status = kUnstable;
    }
  }
  return status;
}

// Reads the numeric options from their text (see option_values.h); throws OptionError.
void check_numbers(const CLI::App& app, Options& o, const std::string& time, const std::string& steps,
                   const std::string& frames_every, const std::string& metrics_every, const std::string& surface_every,
                   const std::string& surface_resolution) {
  if (o.out.empty()) throw OptionError("--out: the output directory must be a non-empty path");
  if (app.count("--time")) o.time = finite_option("--time", time, 0.0, kMaxTime, true, "seconds");
  if (app.count("--steps")) o.steps = whole_option("--steps", steps, 1, kMaxSteps);
  if (app.count("--frames-every"))
    o.frames_every = finite_option("--frames-every", frames_every, 0.0, kMaxTime, false, "seconds");
  if (app.count("--metrics-every"))
    o.metrics_every = finite_option("--metrics-every", metrics_every, 0.0, kMaxTime, false, "seconds");
  if (app.count("--surface-every"))
    o.surface_every = finite_option("--surface-every", surface_every, 0.0, kMaxTime, false, "seconds");
  if (app.count("--surface-resolution"))
    o.surface_resolution = finite_option("--surface-resolution", surface_resolution, 1.0, 8.0, false, "voxels per spacing");
  if (app.count("--surface-resolution") && !(o.surface_every > 0.0))
    throw OptionError("--surface-resolution: goes with --surface-every SECONDS (> 0), which writes the meshes");
  if (o.surface_every > 0.0 && !surfaces_built_in())
    throw OptionError("--surface-every: this sph_run was built without surface meshes (-DSPH_WITH_OPENVDB=OFF); "
                      "rebuild with libopenvdb-dev installed");
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  std::string time, steps, frames_every, metrics_every, surface_every, surface_resolution;
  CLI::App app{
      "sph_run: run an SPH scene headless and record what happens.\n\n"
      "Writes OUT/metrics.csv (time, dt, step, kinetic_energy, potential_energy, energy_budget, density_error_mean,\n"
      "density_error_max, v_max, front_x, top_y, height_at_x0, particles, outside_domain, wall_ms, and the iterative\n"
      "solvers' solver_iterations, solver_density_error, divergence_iterations, divergence_error, deepest_in_solid\n"
      "(m: the deepest any fluid particle is inside a wall, obstacle or body), particles_in_solids (deeper than\n"
      "half a spacing), then depth_<name> for each of the scene's \"probes\" (water-height gauges) and, for each\n"
      "rigid body k, body<k>_x, _y, _z, _vx, _vy, _vz, _qw, _qx, _qy, _qz (orientation), _fx, _fy, _fz; flushed at\n"
      "least once per second), with --frames-every PLY point clouds OUT/frame_NNNNN.ply and with --surface-every\n"
      "surface meshes OUT/surface_NNNNN.ply (ParaView, Blender). Ends\n"
      "with a summary: particles, steps, ms_per_step (median) and ms_per_step_mean, phase_ms_per_step_mean (time by\n"
      "phase), the solver and, for DFSPH and PBF, iterations per step and steps that reached the iteration cap.\n"
      "The pressure solver is the scene's \"solver\": wcsph (default), dfsph or pbf (--set solver=dfsph).\n"
      "SIGINT or SIGTERM stops the run after the current step; the output is flushed and the summary printed.\n"
      "Exit status: 0 done, 1 bad input (scene or options), 3 the simulation became unstable (or its state is\n"
      "not finite), 4 an output could not be written, 130 stopped by SIGINT, 143 stopped by SIGTERM."};
  sph::use_error_prefix(app);
  app.add_option("scene", o.scene, "scene file (JSON), for example scenes/dam_break.json")->required();
  app.add_option("--backend,-b", o.backend, "back end: " + [] {
    std::string s;
    for (const auto& b : available_backends()) s += (s.empty() ? "" : ", ") + b;
    return s;
  }())->capture_default_str();
  auto* t = app.add_option("--time,-t", time, "simulated seconds to run, in (0, 1e7] (default: the scene's run.time)");
  auto* n = app.add_option("--steps,-n", steps, "number of steps to run instead of a time, in [1, 1e12]");
  t->excludes(n);
  app.add_option("--out,-o", o.out, "output directory")->capture_default_str();
  app.add_option("--frames-every", frames_every,
                 "write a PLY frame every this many simulated seconds, in [0, 1e7] (0: none; default: the scene's)");
  app.add_option("--metrics-every", metrics_every,
                 "write a metrics row at most every this many simulated seconds, in [0, 1e7] (0: every step)");
  app.add_option("--set,-s", o.sets,
                 "override a scene value, key=value with a dotted path, repeatable; for example\n"
                 "--set fluids.0.viscosity=0.01 --set resolution.particles_across=40 --set integrator=leapfrog\n"
                 "(every key and its allowed values: README.md, \"Scenes\")");
  app.add_option("--surface-every", surface_every,
                 "write the fluid's surface as a closed triangle mesh OUT/surface_NNNNN.ply (binary PLY, OpenVDB; for\n"
                 "Blender and ParaView) every this many simulated seconds, in [0, 1e7] (0: none, the default);\n"
                 "NNNNN counts these intervals (t = NNNNN x SECONDS), not the frames");
  app.add_option("--surface-resolution", surface_resolution,
                 "voxels per particle spacing of the surface meshes, a number in [1, 8] (default 2)");
  app.add_flag("--quiet,-q", o.quiet, "no progress line");
  app.add_option("--restart", o.restart,
                 "continue the run from a frame OUT/frame_NNNNN.ply of this scene: the state, time, step and jets\n"
                 "come from the frame, bit for bit; --time and --steps count from the original start; frames\n"
                 "are numbered on from NNNNN + 1");
  try {
    app.parse(argc, argv);
    check_numbers(app, o, time, steps, frames_every, metrics_every, surface_every, surface_resolution);
  } catch (const CLI::ParseError& e) {
    // --help exits 0; every parse error is bad input (CLI11's own codes, 104 to 109, are not documented).
    return app.exit(e) == 0 ? kDone : kBadInput;
  } catch (const OptionError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kBadInput;
  }
  try {
    return run(o);
  } catch (const OutputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kOutputFailed;
  } catch (const std::bad_alloc&) {  // set-up reports its own estimate (make_simulation); this is a later step
    std::cerr << "error: out of memory while running " << o.scene << "; lower the resolution\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kBadInput;
  }
}
