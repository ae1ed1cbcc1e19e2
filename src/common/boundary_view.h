// Boundary particles [Akinci et al. 2012, "Versatile rigid-fluid coupling for incompressible SPH"; seed 002,
// section 4.1]: static particles that sample the walls (sph.walls = "particles"), each with a volume V_b
// that enters the fluid's sums as the mass Psi_b = rho0_i V_b ([AIA12] eq. 5) of the fluid particle i that
// reads it. They are sampled once (boundary_particles.cpp) and kept in a dense grid of cells of h over their
// bounding box, so that a fluid particle finds them in 9 index ranges; far from every wall its cell lies
// outside that box, or in it with empty ranges.
//
// A raw-pointer view (trivially copyable, like ParticleView): the same struct reaches a CUDA kernel, an
// OpenMP loop or the serial reference through GridView::boundary. n = 0: no boundary particles.
#pragma once

#include <cstdint>

#include "sph_hd.h"
#include "vec3.h"

namespace sph {

struct BoundaryView {
  int32_t n;                // boundary particles
  const Vec4* pos_volume;   // n: x, y, z [m] and the volume V_b [m^3], sorted by cell
  const float* friction;    // n: the boundary's viscosity factor, 1 - slip of the shape it samples
  const Vec4* normal_depth;  // n: unit normal of the nearest surface, towards the fluid, and the depth below it [m]
  const int32_t* solid;      // n: which solid it samples (a shape or mesh index of the scene; 0 in a body)
  const int32_t* cell_start;  // nx * ny * nz + 1: first particle of each cell (x fastest), then n
  Vec3 origin;              // corner of cell (0, 0, 0) [m]
  float inv_cell;           // 1 / cell size [1/m]; the cell size is at least h
  int32_t nx, ny, nz;
};

// Calls f(b, x - x_b, r2, V_b) for every boundary particle b within sqrt(h2) of x (r2 < h2). The 3 x 3 rows of
// 3 cells around x's cell, each one index range.
template <class F>
SPH_HD_ALWAYS_INLINE void for_each_boundary(const BoundaryView& bv, Vec3 x, float h2, F&& f) {
  if (bv.n == 0) return;
  // In floating point first: a position far outside (or not finite) has no boundary neighbour.
  const float fx = floorf((x.x - bv.origin.x) * bv.inv_cell), fy = floorf((x.y - bv.origin.y) * bv.inv_cell),
              fz = floorf((x.z - bv.origin.z) * bv.inv_cell);
  if (!(fx >= -1.0f && fy >= -1.0f && fz >= -1.0f && fx <= float(bv.nx) && fy <= float(bv.ny) && fz <= float(bv.nz)))
    return;
  const int32_t cx = int32_t(fx), cy = int32_t(fy), cz = int32_t(fz);
  const int32_t x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < bv.nx ? cx + 1 : bv.nx - 1;
  if (x0 > x1) return;
  for (int32_t z = cz - 1; z <= cz + 1; ++z) {
    if (z < 0 || z >= bv.nz) continue;
    for (int32_t y = cy - 1; y <= cy + 1; ++y) {
      if (y < 0 || y >= bv.ny) continue;
      const int32_t row = (z * bv.ny + y) * bv.nx;
      const int32_t end = bv.cell_start[row + x1 + 1];
      for (int32_t b = bv.cell_start[row + x0]; b < end; ++b) {
        const Vec4 pb = bv.pos_volume[b];
        const Vec3 xb = xyz(pb);
        const Vec3 xab = x - xb;
        const float r2 = length2(xab);
        if (r2 < h2) f(b, xab, r2, pb.w);
      }
    }
  }
}

// A rigid body (issue 13, src/common/rigid_body.h) as the fluid's loops see it: its boundary particles in its
// own frame, a BoundaryView whose positions are relative to the centre of mass and never change, and its pose
// and velocity this step. World position of a body particle: centre + R x_local, R = (axis_x axis_y axis_z)
// (columns); its velocity: velocity + omega x (R x_local).
struct BodyView {
  BoundaryView local;
  Vec3 centre;                  // [m]
  Vec3 axis_x, axis_y, axis_z;  // the rotation's columns
  Vec3 velocity;                // [m/s]
  Vec3 omega;                   // angular velocity [1/s]
  float reach2;                 // (radius of the body's particles about its centre + h)^2 [m^2]: a quick reject
};

SPH_HD inline Vec3 body_to_world(const BodyView& b, Vec3 v) { return v.x * b.axis_x + v.y * b.axis_y + v.z * b.axis_z; }
SPH_HD inline Vec3 world_to_body(const BodyView& b, Vec3 v) { return Vec3{dot(v, b.axis_x), dot(v, b.axis_y), dot(v, b.axis_z)}; }

// Calls f(k, b, x - x_b, r2, V_b, v_b) for every particle b of every body k within sqrt(h2) of x (world
// frame: x - x_b, and the particle's velocity v_b). In the body's frame through its own grid, so a body needs
// no grid rebuilt as it moves.
template <class F>
SPH_HD inline void for_each_body_particle(const BodyView* bodies, int32_t num_bodies, Vec3 x, float h2, F&& f) {
  for (int32_t k = 0; k < num_bodies; ++k) {
    const BodyView& body = bodies[k];
    const Vec3 rel = x - body.centre;
    if (!(length2(rel) < body.reach2)) continue;
    for_each_boundary(body.local, world_to_body(body, rel), h2, [&](int32_t b, Vec3 xab_local, float r2, float volume) {
      const Vec3 xab = body_to_world(body, xab_local);
      f(k, b, xab, r2, volume, body.velocity + cross(body.omega, rel - xab));
    });
  }
}

// The last line of defence of walls of boundary particles, as the penalty response (boundaries.h) is for the
// analytic shapes, and the only one of meshes and rigid bodies. Each boundary particle b describes the
// surface above it as the plane at depth_b above x_b along its normal n_b. A point counts as inside when it
// lies behind the plane of every boundary particle within 1.5 times the distance of the nearest one (the
// nearest's neighbours in its layer): near a convex edge the planes of both faces must agree, so a fluid
// particle beside a box, below the plane of its bottom face, is not taken for one inside it (deciding by the
// deepest plane did that, and flung water off a floating box). It is then moved out by the smallest of those
// depths, along that plane's normal, and loses the velocity it had into the wall. Where two solids meet
// (a cup standing on the floor) the floor's planes may overrule the cup's, and a particle can stay inside
// the cup's base (results.md). Pressure keeps the fluid about half a spacing off the walls; this catches what
// an impact drives between the boundary particles, where their repulsion, symmetric about the gap, would
// no longer push it out.

// The deciding boundary particle of bv for a point x (in bv's frame) among those of solid `solid` (-1: the
// solid of the nearest): the one whose plane x lies least far behind, when x lies behind the plane of every
// particle of that solid within 1.5 times the distance of its nearest; else -1. `behind` gets that depth,
// `nearest_solid` the solid examined.
SPH_HD_ALWAYS_INLINE int32_t deciding_plane(const BoundaryView& bv, Vec3 x, float h2, int32_t solid, float& behind,
                                           int32_t& nearest_solid) {
  float nearest = h2;
  nearest_solid = -1;
  for_each_boundary(bv, x, h2, [&](int32_t b, Vec3, float r2, float) {
    const int32_t s = bv.solid[b];
    if (r2 < nearest && (solid < 0 ? true : s == solid)) {
      nearest = r2;
      nearest_solid = s;
    }
  });
  behind = 0.0f;
  if (nearest_solid < 0) return -1;
  const float near2 = 2.25f * nearest;
  int32_t deciding = -1;
  float least = 3.0e38f;  // above any depth
  for_each_boundary(bv, x, h2, [&](int32_t b, Vec3 xab, float r2, float) {
    if (r2 > near2 || bv.solid[b] != nearest_solid) return;
    const Vec4 nd = bv.normal_depth[b];
    const float depth = nd.w - dot(xyz(nd), xab);  // > 0: behind the surface
    if (depth < least) {
      least = depth;
      deciding = b;
    }
  });
  if (!(least > 0.0f)) return -1;
  behind = least;
  return deciding;
}

// The deciding particle for x among the nearest solid's, else among the next nearest solid's (where two
// solids meet: a cup standing on the floor), as deciding_plane.
SPH_HD_ALWAYS_INLINE int32_t inside_solid(const BoundaryView& bv, Vec3 x, float h2, float& behind) {
  int32_t first = -1, second = -1;
  int32_t b = deciding_plane(bv, x, h2, -1, behind, first);
  if (b >= 0 || first < 0) return b;
  // The nearest particle of any other solid.
  float nearest = h2;
  for_each_boundary(bv, x, h2, [&](int32_t k, Vec3, float r2, float) {
    if (bv.solid[k] != first && r2 < nearest) {
      nearest = r2;
      second = bv.solid[k];
    }
  });
  if (second < 0) return -1;
  int32_t examined = -1;
  return deciding_plane(bv, x, h2, second, behind, examined);
}

// Particle i against the static boundary particles, then against each rigid body's (in the body's frame;
// there the position only).
SPH_HD_ALWAYS_INLINE void collide_boundary_particles(const BoundaryView& bv, const BodyView* bodies, int32_t num_bodies, float h2,
                                                     Vec3* pos, Vec3* vel, int32_t i) {
  float behind = 0.0f;
  const int32_t b = bv.n > 0 ? inside_solid(bv, pos[i], h2, behind) : -1;
  if (b >= 0) {
    const Vec3 n = xyz(bv.normal_depth[b]);
    pos[i] = pos[i] + behind * n;
    const Vec3 v = vel[i];
    const float vn = dot(v, n);
    if (vn < 0.0f) vel[i] = v - vn * n;
  }
  for (int32_t k = 0; k < num_bodies; ++k) {
    const BodyView& body = bodies[k];
    const Vec3 rel = pos[i] - body.centre;
    if (!(length2(rel) < body.reach2)) continue;
    int32_t examined = -1;
    const int32_t c = deciding_plane(body.local, world_to_body(body, rel), h2, -1, behind, examined);
    if (c < 0) continue;
    // Only the position: a velocity taken away here would be momentum the body never received (the
    // fluid's push on a body is its pressure, summed as the reaction, src/solvers/rigid_bodies.h).
    pos[i] = pos[i] + behind * body_to_world(body, xyz(body.local.normal_depth[c]));
  }
}

}  // namespace sph
