// Surface meshes of frames (surface_output.h).
#include "surface_output.h"

#include <cstdio>
#include <stdexcept>

#ifdef SPH_HAVE_SURFACE
#include "surface/particle_surface.h"
#endif

namespace sph {

bool surfaces_built_in() {
#ifdef SPH_HAVE_SURFACE
  return true;
#else
  return false;
#endif
}

std::size_t write_surface(const std::string& path, const std::vector<Vec3>& positions, double spacing,
                          double voxels_per_spacing, double time, bool colour_field) {
#ifdef SPH_HAVE_SURFACE
  SurfaceOptions o;
  o.spacing = spacing;
  o.voxels_per_spacing = voxels_per_spacing;
  o.colour_field = colour_field;
  const TriangleMesh mesh = particle_surface(positions, o);
  write_ply_mesh(path, mesh, time);
  return mesh.triangles.size();
#else
  (void)positions, (void)spacing, (void)voxels_per_spacing, (void)time, (void)colour_field;
  throw std::runtime_error("cannot write " + path + ": this build has no surface meshes (configured with "
                           "-DSPH_WITH_OPENVDB=OFF; install libopenvdb-dev and build with it ON)");
#endif
}

std::string surface_file_name(int index) {
  char name[64];
  std::snprintf(name, sizeof name, "surface_%05d.ply", index);
  return name;
}

}  // namespace sph
