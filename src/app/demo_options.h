// sph_demo's command line: the options, parsed and checked before any window opens.
#pragma once

#include <string>
#include <vector>

namespace sph {

struct DemoOptions {
  std::string scene = "scenes/dam_break.json";
  std::string backend = "host";
  int frames = 0;        // 0: interactive; N > 0: render N frames without input, then exit
  std::string screenshot;
  std::string keys;      // pressed one per frame from the first frame (scripted headless runs)
  int width = 1280, height = 720;
  int substeps = 0;      // 0: about 1/60 s of simulated time per frame
  std::string colour = "speed";
  std::string render = "spheres";  // "spheres" or "surface" (screen-space fluid surface)
  std::string cull = "auto";       // --replay: "auto" draws only the nearest particle of each pixel when that
                                   // gives the same picture (render/occlusion_cull.h); "off" draws every one
  std::vector<std::string> sets;
  double budget_ms = 40.0;  // simulation time per frame [ms], finite and > 0
  std::string replay;       // non-empty: play this sph_run output folder's frames instead of simulating
};

// Parses argv into o. Returns -1 when the demo should run, else the exit status: 0 after --help, 1 with a
// message on stderr for any parse error or bad value (the scene itself is checked later, by loading it).
int parse_demo_options(int argc, char** argv, DemoOptions& o);

}  // namespace sph
