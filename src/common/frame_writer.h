// Particle frames as binary little-endian PLY point clouds (x y z, velocity, density, pressure, fluid, id):
// ParaView and Blender open them directly.
#pragma once

#include <string>

#include "particle_state.h"

namespace sph {

// Writes path; throws std::runtime_error when the file cannot be written.
void write_ply_frame(const std::string& path, const ParticleState& ps, double time);

}  // namespace sph
