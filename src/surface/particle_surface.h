// The fluid's surface as a closed triangle mesh, built from particle positions with OpenVDB (Debian's
// libopenvdb-dev; the level-set tools film and VFX pipelines use): issue 14, for sph_run --surface-every and
// sph_surface. The particles are rasterised as spheres into a narrow-band level set, the union is smoothed by
// mean-curvature flow and eroded back to where the particles' own volume ends, then polygonised at the zero
// iso-value (OpenVDB's volumeToMesh, a dual-contouring relative of marching cubes; quads are split in two).
#pragma once

#include <string>
#include <vector>

#include "../common/mesh.h"
#include "../common/mesh_ply.h"
#include "../common/vec3.h"

namespace sph {

// How the surface is built. Lengths are in units of the particle spacing d, so one set of defaults fits every
// resolution.
struct SurfaceOptions {
  double spacing = 0.0;            // particle spacing d [m] (the frame's); > 0
  double voxels_per_spacing = 2.0;  // voxel size d / this; 1 to 8
  double radius = 1.5;             // sphere radius per particle [d]: large enough that the spheres of a
                                   // lattice overlap (> sqrt(3)/2) and its faces are nearly flat
  int smoothing = 2;               // mean-curvature flow iterations after the erosion; 0 to 20
  // false: the particles' spheres (above); true: the seed's colour field (seed 002, section 6), Phi(x) =
  // sum_j V_j W(|x - x_j|, h) with V_j = d^3 and the cubic spline of support h = 2 d, meshed at Phi = 1/2,
  // where a half-space of fluid ends (no calibration; radius and smoothing are not used).
  bool colour_field = false;
};

// The lengths the options mean and the check of their ranges. Throws std::invalid_argument naming the option
// and its allowed values.
void check_surface_options(const SurfaceOptions& o);

// Memory [bytes] a surface of `particles` particles needs at most with these options (the level set's narrow
// band around every particle's sphere, counted as if no sphere overlapped another), for refusing a
// resolution the machine cannot hold.
double surface_memory_estimate(std::size_t particles, const SurfaceOptions& o);

// The closed, outward-oriented (counter-clockwise seen from outside) triangle mesh of the fluid the particles
// at `positions` [m] fill. The erosion puts a lattice's flat face at half a spacing beyond its outer particles
// (each particle stands for d^3, as the emitters fill), calibrated on a lattice slab. Empty for no
// particles. Throws std::invalid_argument for bad options, std::runtime_error when the estimate of
// surface_memory_estimate exceeds the memory a run may use (setup_budget.h, usable_memory_bytes; naming both).
TriangleMesh particle_surface(const std::vector<Vec3>& positions, const SurfaceOptions& o);

// Surface area [m^2] and enclosed volume [m^3] of a closed mesh (the divergence theorem).
double mesh_area(const TriangleMesh& mesh);
double mesh_volume(const TriangleMesh& mesh);

}  // namespace sph
