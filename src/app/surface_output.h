// Surface meshes of frames for sph_run --surface-every and sph_surface (src/surface/particle_surface.h builds
// them with OpenVDB). A build without OpenVDB (-DSPH_WITH_OPENVDB=OFF, as scripts/gpu_check.sh's) has the
// options but refuses them with a message.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "common/vec3.h"

namespace sph {

// Whether this build can make surfaces.
bool surfaces_built_in();

// Writes the surface mesh of the fluid at `positions` [m] (particle spacing [m], voxels per spacing in [1, 8];
// colour_field: the seed's Phi instead of the particles' spheres, particle_surface.h)
// to path as binary PLY, with the simulated time [s] in its header; returns the number of triangles. Throws std::invalid_argument for options out of
// range, std::runtime_error when the build has no OpenVDB, the resolution needs more memory than the
// machine has, or the file cannot be written (each message names the option or the file).
std::size_t write_surface(const std::string& path, const std::vector<Vec3>& positions, double spacing,
                          double voxels_per_spacing, double time, bool colour_field = false);

// "surface_NNNNN.ply" for index NNNNN.
std::string surface_file_name(int index);

}  // namespace sph
