// The Dear ImGui panel: live parameters, live statistics, the colour legend and the controls' help.
#pragma once

#include <string>
#include <vector>

#include "../common/backend.h"
#include "colour_map.h"
#include "fluid_surface.h"
#include "particle_renderer.h"

namespace sph::render {

// Values the panel shows and edits; the demo applies the edits to the simulation after the frame.
struct PanelModel {
  // live parameters (first fluid's values; applied to every fluid)
  float viscosity = 0.0f;
  float speed_of_sound = 0.0f;
  float near_stiffness = 0.0f;
  float dt_max = 0.0f;
  int substeps = 1;
  int colour_mode = 0;
  bool paused = false;
  bool flat_points = false;
  bool surface = false;     // draw the fluid's surface (screen space) instead of spheres
  SurfaceLook look;         // its smoothing, sphere size, colour and absorption
  bool show_walls = false;  // draw the walls' boundary particles (sph.walls = "particles")
  long wall_particles = 0;  // how many there are
  // statistics
  std::string scene, backend, integrator;
  long particles = 0;
  double fps = 0.0, sim_ms = 0.0, draw_ms = 0.0, sim_time = 0.0, realtime_ratio = 0.0, dt = 0.0;
  double density_error = 0.0;
  // the iterative solvers' last step (DFSPH, PBF; solver_iterations < 0 under WCSPH): iterations and the
  // error the solve ended at (a fraction of rho0)
  int solver_iterations = -1;
  double solver_error = 0.0;
  PhaseTimes phase_per_step;  // ms per step by phase, averaged over the last frames
  ColourRange legend;
  std::vector<std::string> backends;
  std::vector<std::string> messages;  // what the demo skipped or stopped (scenes, overrides, emission)
  std::vector<std::string> setup_report;  // the load-time checks' findings (Setup::report), as sph_run prints them
  bool setup_changed = false;             // some finding removed particles or refit a lattice
};

// The surface toggle and, when on, its look's sliders (shared by the live demo's panel and the replay's).
bool surface_controls(bool& surface, SurfaceLook& look);

// Draws the panel; returns true when a parameter was edited.
bool draw_panel(PanelModel& m);

}  // namespace sph::render
