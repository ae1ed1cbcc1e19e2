// Triangle meshes as binary PLY files: the fluid's surface meshes that sph_run --surface-every and
// sph_surface write (src/surface/particle_surface.h builds them), read back by sph_demo --replay.
#pragma once

#include <string>

#include "mesh.h"

namespace sph {

// Writes the mesh as a binary little-endian PLY (vertex x, y, z as float; face lists of 3 int indices), which
// ParaView and Blender open, with "comment time T" (simulated seconds, 17 digits) in its header. Written to
// path.tmp and renamed, so a failed write leaves no partial file; throws std::runtime_error naming the file.
void write_ply_mesh(const std::string& path, const TriangleMesh& mesh, double time);

// Reads a mesh write_ply_mesh wrote: its vertices, triangles and bounds, and the time of its header comment
// (NaN without one). Throws std::runtime_error naming the file: unreadable, another format or property list,
// a face that is not a triangle, an index out of range, a non-finite vertex, or a file shorter or longer than
// its header says.
TriangleMesh read_ply_mesh(const std::string& path, double& time);

}  // namespace sph
