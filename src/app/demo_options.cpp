#include "demo_options.h"

#include <cmath>
#include <iostream>

#include <CLI/CLI.hpp>

#include "cli_errors.h"

namespace sph {

int parse_demo_options(int argc, char** argv, DemoOptions& o) {
  CLI::App app{"sph_demo: watch and play with an SPH fluid in real time (OpenGL window, Dear ImGui panel).\n"
               "Controls: space pause, N step, R reset, [ ] scenes, B back end, arrows tilt gravity, J/L push,\n"
               "ctrl+drag pull/push the water, mouse orbit/pan/zoom, +/- substeps, C colour, V points, S surface,\n"
               "G wall particles, D drop a box, P screenshot.\n"
               "--replay DIR plays an sph_run recording instead: space play/pause, N/B step, L loop, +/- speed,\n"
               "M its surface meshes.\n"
               "Exit status: 0 done, 1 bad input, 2 no display or OpenGL, 3 the simulation became unstable."};
  sph::use_error_prefix(app);
  app.add_option("--scene,scene", o.scene, "scene file (JSON)")->capture_default_str();
  app.add_option("--backend,-b", o.backend, "back end: cpu, host or cuda")->capture_default_str();
  app.add_option("--frames", o.frames, "render this many frames without input, then exit (headless runs)");
  app.add_option("--screenshot", o.screenshot, "with --frames: write the last frame to this PNG");
  app.add_option("--keys", o.keys, "press these keys, one per frame from the first (space N R [ ] B C V G D S L M + -)")
      ->check([](const std::string& k) {
        return k.find_first_not_of(" NRBCVGDSLM[]+-") == std::string::npos ? std::string()
                                                                              : "allowed keys: space N R [ ] B C V G D S L M + -";
      });
  app.add_option("--width", o.width, "window width")->capture_default_str()->check(CLI::Range(64, 8192));
  app.add_option("--height", o.height, "window height")->capture_default_str()->check(CLI::Range(64, 8192));
  app.add_option("--substeps", o.substeps, "simulation steps per frame (default: about 1/60 s per frame)");
  app.add_option("--colour", o.colour, "fluid, speed, density_error, pressure or cell")
      ->capture_default_str()->check(CLI::IsMember({"fluid", "speed", "density_error", "pressure", "cell"}));
  app.add_option("--render", o.render,
                 "spheres; surface: the screen-space fluid surface (S toggles); mesh (with --replay): the recording's\n"
                 "exported surface meshes (M toggles)")
      ->capture_default_str()->check(CLI::IsMember({"spheres", "surface", "mesh"}));
  app.add_option("--cull", o.cull,
                 "with --replay: auto draws only the particle nearest the camera in each pixel while a sphere at the\n"
                 "camera's target is at most 2 pixels across and the particles outnumber a quarter of the pixels (a 1M\n"
                 "recording played about 14 times faster under software OpenGL); off draws every particle")
      ->capture_default_str()->check(CLI::IsMember({"auto", "off"}));
  app.add_option("--budget-ms", o.budget_ms, "simulation time budget per frame, milliseconds")->capture_default_str();
  app.add_option("--set,-s", o.sets, "override a scene value, key=value (as sph_run)");
  app.add_option("--replay", o.replay,
                 "play the frames (frame_NNNNN.ply) of an sph_run output folder at their recorded times instead of\n"
                 "simulating: space plays or pauses, N and B step, L loops, + and - change the speed, the panel seeks;\n"
                 "the colours' rest densities come from the scene NAME.json beside --scene's file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;  // --help: 0; every parse error is bad input (CLI11's own codes are 100+)
  }
  if (app.count("--cull") && o.replay.empty()) {
    std::cerr << "error: --cull chooses how a recording is drawn: it goes with --replay DIR\n";
    return 1;
  }
  if (o.frames < 0) {
    std::cerr << "error: --frames must be 0 (interactive) or a positive number of frames, got " << o.frames << "\n";
    return 1;
  }
  if (!o.screenshot.empty() && o.frames == 0) {
    std::cerr << "error: --screenshot needs --frames N with N > 0\n";
    return 1;
  }
  if (app.count("--substeps") && o.substeps < 1) {
    std::cerr << "error: --substeps must be at least 1, got " << o.substeps << "\n";
    return 1;
  }
  if (!(std::isfinite(o.budget_ms) && o.budget_ms > 0.0)) {
    std::cerr << "error: --budget-ms must be a finite number of milliseconds above 0, got "
              << app.get_option("--budget-ms")->results().front() << "\n";
    return 1;
  }
  return -1;
}

}  // namespace sph
