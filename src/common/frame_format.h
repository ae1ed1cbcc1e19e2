// What a frame file records besides the particles: enough to continue the run bit for bit (sph_run
// --restart) or to start a scene from it (the scene key "initial_state"). frame_writer.cpp writes it as PLY
// header comments, frame_reader.cpp reads it back; README "Frames" documents the lines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sph {

struct FrameInfo {
  std::string scene;                // scene name, so a restart with another scene is refused
  std::string solver;               // "wcsph", "dfsph" or "pbf" (solver_name), so a restart with another is
                                    // refused; empty: not recorded (an initial_state frame may come from any)
  double time = 0.0;                // simulated time [s], written with 17 significant digits (exact)
  long step = 0;                    // steps taken
  int frame_index = 0;              // NNNNN of frame_NNNNN.ply; a continued run numbers from index + 1
  int32_t next_id = 0;              // id the next emitted particle gets
  double spacing = 0.0;             // particle spacing d [m]: the particle masses depend on it
  std::vector<double> jet_travelled;  // per jet: distance moved since its last layer was born [m]
  // The energy check's state (Simulation): energy [J] and mass [kg] put in, the largest specific energy put
  // in [J/kg] and the potential reference [J/kg], so a continued run is checked against the same budget.
  // Frames without the line (older ones) continue with a budget re-based on their own state.
  bool has_energy = false;
  double energy_in = 0.0, mass_in = 0.0, max_specific_in = 0.0, potential_reference = 0.0;
};

}  // namespace sph
