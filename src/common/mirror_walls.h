// Mirror walls: every particle near a wall is reflected across it as a ghost particle.
//
// Penalty walls (thesis 3.5.1) only stop particles at the surface. Near a wall a particle's kernel reaches
// past it, where there are no particles, so a summation density reads low there (18% low at the first
// layer) and the pressure sum is one-sided: the fluid pushes the particle into the wall and a layer packs
// against it (in the dam break it clings to the back wall; the hydrostatic column settles 30% low). With
// mirror walls (scene key sph.walls = "mirror", the default) each neighbour b of a particle a near a wall
// also acts as its mirror image b' across that wall (and across both walls of an edge and all three of a
// corner), with b's mass and density, its velocity mirrored (normal part reversed; tangential part kept on a free-slip
// wall, slip = 1, and reversed on a no-slip wall, slip = 0) and its pressure extrapolated hydrostatically,
// P_b' = P_b + rho_b g.(x_b' - x_b) [Adami, Hu & Adams 2012, eq. 27 with a wall at rest], so a column at
// rest is held by the wall exactly. A ghost only pushes: the part of its pair term that points into the
// wall is dropped (push_only), so no wall pulls fluid towards it or holds it there, whatever
// sph.negative_pressure says. Where there is no fluid there are no ghosts: a free surface meeting a
// wall stays free. A ghost b' lies within h of a only if b does (reflection across a wall with a and b on
// the same side only lengthens a - b), so the ghosts come from the neighbour loop a already runs.
// Walls: the faces of box containers (not an open top), non-absorbing planes, and sphere containers by
// their tangent plane nearest the particle; obstacles have no ghosts.
#pragma once

#include "grid.h"
#include "params.h"
#include "particle_view.h"

namespace sph {

constexpr int kMaxMirrorWalls = 3;

// The walls within h of one particle: reflect(x) = x - 2 (n.x - offset) n, n the unit normal towards the fluid.
// Every loop over the walls runs over all kMaxMirrorWalls slots and tests i < count, so that each slot is
// named by a constant index once the loop is unrolled: on a GPU the walls then stay in registers, where a
// loop up to count (or a write to slot [count]) indexes them at run time and puts them in local memory,
// a stack frame in every density and forces thread (issue 11, item 1).
struct NearWalls {
  int32_t count;
  Vec3 normal[kMaxMirrorWalls];
  float offset[kMaxMirrorWalls];
  float slip[kMaxMirrorWalls];  // the shape's C_slip: the ghost's tangential velocity is (2 slip - 1) v_T
};

SPH_HD inline void add_wall(NearWalls& w, Vec3 n, float offset, float slip) {
  for (int32_t i = 0; i < kMaxMirrorWalls; ++i) {
    if (i != w.count) continue;
    w.normal[i] = n;
    w.offset[i] = offset;
    w.slip[i] = slip;
  }
  if (w.count < kMaxMirrorWalls) ++w.count;
}

SPH_HD inline NearWalls near_walls(const SimConstants& c, Vec3 x) {
  NearWalls w{};
  const float h = c.kernel.h;
  for (int32_t s = 0; s < c.num_shapes; ++s) {
    const Shape& shape = c.shapes[s];
    if (shape.type == ShapeType::Box && shape.keep_inside) {
      const float xs[3] = {x.x, x.y, x.z}, lo[3] = {shape.a.x, shape.a.y, shape.a.z}, hi[3] = {shape.b.x, shape.b.y, shape.b.z};
      for (int i = 0; i < 3; ++i) {
        const Vec3 e{i == 0 ? 1.0f : 0.0f, i == 1 ? 1.0f : 0.0f, i == 2 ? 1.0f : 0.0f};
        if (xs[i] - lo[i] < h) add_wall(w, e, lo[i], shape.slip);  // the nearer face of each axis only
        else if (hi[i] - xs[i] < h && !(i == 1 && shape.open_top)) add_wall(w, -1.0f * e, -hi[i], shape.slip);
      }
    } else if (shape.type == ShapeType::Plane && !shape.absorb) {
      if (dot(x - shape.a, shape.b) < h) add_wall(w, shape.b, dot(shape.a, shape.b), shape.slip);
    } else if (shape.type == ShapeType::Sphere && shape.keep_inside) {
      const Vec3 to_centre = shape.a - x;
      const float r = length(to_centre);
      if (r > 0.0f && shape.radius - r < h) {
        const Vec3 n = (1.0f / r) * to_centre;
        add_wall(w, n, dot(shape.a, n) - shape.radius, shape.slip);
      }
    }
  }
  return w;
}

// Moves x out to `distance` [m] from each mirror wall (near_walls) it is nearer than that, along the wall's
// normal. PBF's collision (boundaries.h) puts a particle that crossed a wall onto the wall's plane, where it
// coincides with its own image: the pair is at r = 0, which no constraint gradient acts along, so nothing
// pushes it off the wall, and the particles a front drives into a wall pile up on its plane (the 16k dam
// break under PBF blew up where its front met the far wall, at 2 and at 4 ms steps; docs/results.md). At
// half a spacing its image is a spacing away, as in the mirror-extended lattice.
SPH_HD inline void keep_off_mirror_walls(const SimConstants& c, Vec3& x, float distance) {
  const NearWalls w = near_walls(c, x);
  for (int32_t i = 0; i < kMaxMirrorWalls; ++i) {
    if (i >= w.count) continue;
    const float gap = dot(x, w.normal[i]) - w.offset[i];
    if (gap < distance) x += (distance - gap) * w.normal[i];
  }
}

// Number of images of a neighbour: itself (image 0) and its ghosts, one per non-empty subset of the walls.
SPH_HD inline int32_t image_count(const NearWalls& w) { return 1 << w.count; }

// A position x and a velocity v as their mirror image number `image` >= 1: reflected across each wall
// whose bit is set. Two functions, so that a ghost's velocity is computed only for a ghost within h, and
// only by the pairs that use it.
SPH_HD inline Vec3 mirror_position(const NearWalls& w, int32_t image, Vec3 x) {
  for (int32_t i = 0; i < kMaxMirrorWalls; ++i) {
    if (i >= w.count || !(image & (1 << i))) continue;
    const Vec3 n = w.normal[i];
    x -= (2.0f * (dot(x, n) - w.offset[i])) * n;
  }
  return x;
}

SPH_HD inline Vec3 mirror_velocity(const NearWalls& w, int32_t image, Vec3 v) {
  for (int32_t i = 0; i < kMaxMirrorWalls; ++i) {
    if (i >= w.count || !(image & (1 << i))) continue;
    const Vec3 n = w.normal[i];
    const float vn = dot(v, n);
    v = (2.0f * w.slip[i] - 1.0f) * (v - vn * n) - vn * n;
  }
  return v;
}

// A direction (a surface normal) as its mirror image number `image`: its part along each wall's normal
// reversed, its tangential part kept (mirror_velocity on free-slip walls).
SPH_HD inline Vec3 mirror_direction(const NearWalls& w, int32_t image, Vec3 u) {
  for (int32_t i = 0; i < kMaxMirrorWalls; ++i) {
    if (i >= w.count || !(image & (1 << i))) continue;
    u -= (2.0f * dot(u, w.normal[i])) * w.normal[i];
  }
  return u;
}

// Calls f(b, image, x_ghost, r2) for every ghost within h of particle a (at xa): each neighbour b's
// images 1.. across `walls`, r2 = |xa - x_ghost|^2 < h^2; the ghost's velocity is
// mirror_velocity(walls, image, v_b). Only neighbours within h can have one.
// The same, for neighbours selected by another radius and placed at other positions: the neighbours b of a
// within sqrt(select_r2) at the grid's positions `select` (for_each_neighbour), their ghosts taken from
// their positions `pos`, and only those within h of a's own (PBF: src/common/pbf.h, whose iterations
// move the particles after the grid phase). for_each_ghost is select = pos = pos_mass, select_r2 = h^2.
template <class Pos, class F>
SPH_HD inline void for_each_ghost_of(const SimConstants& c, const GridView& grid, const Vec4* select, float select_r2,
                                     const Pos* pos, const NearWalls& walls, int32_t a, F&& f) {
  if (walls.count == 0) return;
  const Vec3 xa = xyz(pos[a]);
  const float h2 = c.kernel.h2;
  for_each_neighbour(grid, select, a, select_r2, [&](int32_t b, Vec3, float) {
    const Vec3 xb = xyz(pos[b]);
    for (int32_t image = 1; image < image_count(walls); ++image) {
      const Vec3 xg = mirror_position(walls, image, xb);
      const float r2 = length2(xa - xg);
      if (r2 < h2) f(b, image, xg, r2);
    }
  });
}

template <class F>
SPH_HD inline void for_each_ghost(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                  const NearWalls& walls, int32_t a, F&& f) {
  for_each_ghost_of(c, grid, p.pos_mass, c.kernel.h2, p.pos_mass, walls, a, f);
}

// A wall pushes and never pulls. Negative pressure (sph.negative_pressure "keep") makes a ghost pair
// attractive, and the viscous drag of a ghost moving the other way holds a particle that leaves the wall;
// either would pull fluid towards the wall or hold it there. So for each wall the ghost lies behind, the
// part of its pair term `pair` along that wall's normal is dropped when it points into the wall.
SPH_HD inline Vec3 push_only(const NearWalls& w, Vec3 x_ghost, Vec3 pair) {
  for (int32_t i = 0; i < kMaxMirrorWalls; ++i) {
    if (i >= w.count || dot(x_ghost, w.normal[i]) >= w.offset[i]) continue;  // not reflected across this wall
    const float along = dot(pair, w.normal[i]);
    if (along < 0.0f) pair -= along * w.normal[i];
  }
  return pair;
}

// Pressure of the ghost of b at x_ghost: hydrostatic extrapolation [Adami et al. 2012, eq. 27].
SPH_HD inline float ghost_pressure(const SimConstants& c, float pb, float rhob, Vec3 xb, Vec3 x_ghost) {
  const float p = pb + rhob * dot(c.gravity, x_ghost - xb);
  return (c.clamp_negative_pressure && p < 0.0f) ? 0.0f : p;
}

}  // namespace sph
