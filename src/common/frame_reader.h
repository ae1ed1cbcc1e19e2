// Reading frames written by write_ply_frame (frame_writer.h has the format): for sph_run --restart and the
// scene key "initial_state". A frame that cannot be trusted is refused, never half used.
#pragma once

#include <string>

#include "frame_format.h"
#include "particle_state.h"
#include "scene.h"

namespace sph {

struct Frame {
  std::string path;  // the file it was read from, for messages
  FrameInfo info;
  ParticleState particles;  // every field the frame stores; the others (vel_force, ...) are zero
};

// Reads path. Refuses, with a SceneError naming the file and what is wrong: a missing or non-regular file,
// another format or property list (also frames of older versions without acceleration and age), a missing
// header line, more than max_particles records (checked before anything is allocated), a file shorter or
// longer than its records, non-finite values, densities <= 0, ids that are negative, repeated or not below
// next_id.
Frame read_ply_frame(const std::string& path, double max_particles);

// Refuses (SceneError naming the file, the particle id and the scene's fluids) a frame whose particles name
// a fluid the scene does not have.
void check_frame_fluids(const Frame& frame, const Scene& scene, const std::string& path);

// The scene's "initial_state" frame (scene.initial_state), read for a run that starts from it: its
// particles, except those still inside a jet's inlet (age < 0: the scene's own jets fill their inlets), and
// next_id raised past the frame's ids. The frame's spacing must match the scene's (the particle masses
// depend on it) within 1e-9 relative; otherwise, and for every refusal of read_ply_frame, a SceneError
// naming the file and the key "initial_state".
ParticleState initial_state_particles(const Scene& scene, double spacing, int32_t& next_id);

}  // namespace sph
