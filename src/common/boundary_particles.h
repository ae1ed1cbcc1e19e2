// Boundary particles on the host: the walls sampled once at set-up (sph.walls = "particles"), their Akinci
// volumes and their cell grid, which every back end copies and reads through a BoundaryView
// (boundary_view.h, Backend::set_boundary).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "boundary_view.h"
#include "mesh.h"
#include "params.h"

namespace sph {

// A closed triangle mesh as a solid (scene key "meshes"): an obstacle, or with `inside` a container.
struct MeshSolid {
  TriangleMesh mesh;
  bool inside = false;
  float slip = 1.0f;
};

struct BoundaryParticles {
  std::vector<Vec4> pos_volume;  // x, y, z [m] and V_b [m^3], sorted by cell
  std::vector<float> friction;   // 1 - slip of the sampled shape
  std::vector<Vec4> normal_depth;  // the surface's normal towards the fluid and the depth below it [m]
  std::vector<int32_t> solid;      // the shape (0 .. num_shapes - 1) or mesh (num_shapes + m) it samples
  std::vector<int32_t> cell_start;
  Vec3 origin{0.0f, 0.0f, 0.0f};
  float cell = 0.0f;  // cell size [m]
  int32_t nx = 0, ny = 0, nz = 0;

  std::size_t size() const { return pos_volume.size(); }
  // The view of these host arrays (the cpu back end reads them in place).
  BoundaryView view() const;
};

// The sampling (issue 13: "state and test the sampling"). [AIA12] samples a wall with one layer and gives each
// boundary particle the volume V_b = 1 / sum_k W_bk over the boundary particles k (its eq. 4). With this
// project's kernels (Poly6 density, h = 1.97 d) one layer at the wall reads a fluid particle at d / 2 from it
// 58% too dense (one layer d / 2 behind the wall: 11%), measured on a lattice. So here the solid is sampled
// on the fluid's lattice continued through the wall, in every layer a fluid particle inside can reach (within
// h of the wall: 2 layers at the default resolution), and V_b is [AIA12]'s sum, with the run's density kernel
// (params.h, density_cubic_spline), taken over the lattice on both
// sides within reach (boundary particles and virtual points on the fluid's side, which are then dropped, as
// are virtual points inside another shape's solid). A particle at a wall, in an edge or in a corner then
// finds behind it what it would find in the bulk: on a lattice V_b is the fluid's m / rho0 and the particle
// reads rest density; where samplings overlap (an obstacle on the floor) the sums share the volume. Along a
// wall the lattice is stretched to fit the wall's length exactly (n = round(L / d) points), so a wall's
// samples line up with the emitters' fill of a box that spans the tank.
// Meshes (mesh.h): the lattice anchored half a spacing inside the mesh's bounding box, each point sorted by
// its signed distance; a box given as 12 triangles, with sides whole multiples of d, gives the box shape's
// sampling.
// Shapes: box containers (open tops left open) and box obstacles as above; planes in layers parallel to them
// over the domain; spheres and quadrics on the lattice anchored at the domain's origin, each point sorted by
// its clearance (setup_checks.h): a curved wall is a staircase of lattice points, smoothed by the volumes.
// Absorbing planes are outflows and get none. Every shape keeps its penalty response as well, the last
// line of defence against a leak. `notes` gets lines for the report. Throws std::invalid_argument (naming
// the shape) when the sampling would exceed max_particles.
BoundaryParticles sample_boundary_particles(const SimConstants& c, const std::vector<MeshSolid>& meshes, double spacing,
                                            double max_particles, std::vector<std::string>& notes);

// Sorts b's particles into a new cell grid over their bounding box (cells of at least h), after their
// positions changed (a rigid body's, taken into its own frame).
void regrid_boundary_particles(BoundaryParticles& b, double h);

}  // namespace sph
