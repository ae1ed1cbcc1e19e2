// Penalty boundaries (thesis 3.5.1): a particle found outside its allowed region is moved back to the
// surface and its velocity split into normal and tangent parts, v' = -C_bounce v_N + C_slip v_T; the
// energy-conserving variant scales the reflected normal part by d / (|v| dt), d the penetration depth.
// Shapes: box, plane, sphere, and implicit quadrics p^T Q p (seed 000, section 3.8).
#pragma once

#include "params.h"
#include "particle_view.h"

namespace sph {

// Reflects v at a wall with unit normal n (pointing into the allowed region) after a penetration of depth.
// The particle is put back on the surface, which moves it by depth along n against gravity g; the normal
// speed reflected is the one it had when it crossed the surface, v_n^2 + 2 (g.n) depth, so an elastic
// wall returns exactly the energy that arrived instead of adding m |g.n| depth at every contact.
SPH_HD inline void reflect_velocity(const Shape& s, Vec3 n, float depth, Vec3& v, float dt, Vec3 g) {
  const float vn = dot(v, n);
  if (vn >= 0.0f) return;  // already leaving the wall
  const Vec3 v_tangent = v - vn * n;
  const float vn2_at_surface = vn * vn + 2.0f * dot(g, n) * depth;
  const Vec3 v_normal = (-sqrtf(vn2_at_surface > 0.0f ? vn2_at_surface : 0.0f)) * n;
  float bounce = s.bounce;
  if (s.energy_conserving) {
    const float travel = length(v) * dt;
    if (travel > 0.0f) bounce *= fminf(1.0f, depth / travel);
  }
  v = (-bounce) * v_normal + s.slip * v_tangent;
}

// Moves x by depth along n back to the surface and reflects v.
SPH_HD inline void penalty_response(const Shape& s, Vec3 n, float depth, Vec3& x, Vec3& v, float dt, Vec3 g) {
  x += depth * n;
  reflect_velocity(s, n, depth, v, dt, g);
}

SPH_HD inline float quadric_value(const float* q, Vec3 p) {
  const float h[4] = {p.x, p.y, p.z, 1.0f};
  float f = 0.0f;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) f += h[i] * q[4 * i + j] * h[j];
  return f;
}

// grad f = 2 Q_sub p (seed 000, eq. 23): the first three rows of Q times the homogeneous point.
SPH_HD inline Vec3 quadric_gradient(const float* q, Vec3 p) {
  const float h[4] = {p.x, p.y, p.z, 1.0f};
  float g[3] = {0.0f, 0.0f, 0.0f};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) g[i] += 2.0f * q[4 * i + j] * h[j];
  return {g[0], g[1], g[2]};
}

// Box: per axis, so a particle leaving through an edge or a corner is handled on each axis it crossed.
SPH_HD inline void collide_box(const Shape& s, Vec3& x, Vec3& v, float dt, Vec3 g) {
  if (s.keep_inside) {
    const float lo[3] = {s.a.x, s.a.y, s.a.z};
    const float hi[3] = {s.b.x, s.b.y, s.b.z};
    for (int axis = 0; axis < 3; ++axis) {
      const float xi = axis == 0 ? x.x : (axis == 1 ? x.y : x.z);
      Vec3 n{0.0f, 0.0f, 0.0f};
      float depth = 0.0f;
      if (xi < lo[axis]) {
        depth = lo[axis] - xi;
        (axis == 0 ? n.x : (axis == 1 ? n.y : n.z)) = 1.0f;
      } else if (xi > hi[axis] && !(axis == 1 && s.open_top)) {
        depth = xi - hi[axis];
        (axis == 0 ? n.x : (axis == 1 ? n.y : n.z)) = -1.0f;
      }
      if (depth > 0.0f) penalty_response(s, n, depth, x, v, dt, g);
    }
    return;
  }
  // Obstacle: leave through the nearest face.
  const float d[6] = {x.x - s.a.x, s.b.x - x.x, x.y - s.a.y, s.b.y - x.y, x.z - s.a.z, s.b.z - x.z};
  for (int i = 0; i < 6; ++i)
    if (d[i] <= 0.0f) return;  // outside the box
  int best = 0;
  for (int i = 1; i < 6; ++i)
    if (d[i] < d[best]) best = i;
  const float sign = (best % 2 == 0) ? -1.0f : 1.0f;
  Vec3 n{0.0f, 0.0f, 0.0f};
  (best / 2 == 0 ? n.x : (best / 2 == 1 ? n.y : n.z)) = sign;
  penalty_response(s, n, d[best], x, v, dt, g);
}

// g: the gravity acceleration (see reflect_velocity); zero when only the geometry matters.
SPH_HD inline void collide_shape(const Shape& s, Vec3& x, Vec3& v, float dt, Vec3 g = Vec3{0.0f, 0.0f, 0.0f}) {
  switch (s.type) {
    case ShapeType::Box:
      collide_box(s, x, v, dt, g);
      break;
    case ShapeType::Plane: {
      const float phi = dot(x - s.a, s.b);
      if (phi < 0.0f) penalty_response(s, s.b, -phi, x, v, dt, g);
      break;
    }
    case ShapeType::Sphere: {
      const Vec3 rel = x - s.a;
      const float dist = length(rel);
      if (s.keep_inside) {
        if (dist > s.radius) penalty_response(s, (-1.0f / dist) * rel, dist - s.radius, x, v, dt, g);
      } else if (dist < s.radius) {
        const Vec3 n = dist > 0.0f ? (1.0f / dist) * rel : Vec3{0.0f, 1.0f, 0.0f};
        penalty_response(s, n, s.radius - dist, x, v, dt, g);
      }
      break;
    }
    case ShapeType::Quadric: {
      // Allowed where f >= 0. Newton steps along the gradient find the surface point; first-order
      // distance f / |grad f| is exact for planes and close for smooth quadrics.
      Vec3 y = x;
      Vec3 n{0.0f, 1.0f, 0.0f};
      float f = quadric_value(s.q, y);
      if (f >= 0.0f) break;
      for (int iter = 0; iter < 8 && f < 0.0f; ++iter) {
        const Vec3 grad = quadric_gradient(s.q, y);
        const float gl = length(grad);
        if (gl <= 0.0f) break;
        n = (1.0f / gl) * grad;
        y += (-f / gl * 1.0001f + 1e-7f) * n;
        f = quadric_value(s.q, y);
      }
      const float depth = length(y - x);
      const Vec3 grad = quadric_gradient(s.q, y);
      const float gl = length(grad);
      if (gl > 0.0f) n = (1.0f / gl) * grad;
      x = y;
      reflect_velocity(s, n, depth, v, dt, g);
      break;
    }
  }
}

// Whether x lies outside the shape's allowed region (only planes absorb; see Shape::absorb).
SPH_HD inline bool crossed_plane(const Shape& s, Vec3 x) { return dot(x - s.a, s.b) < 0.0f; }

// Phase "boundaries" for one particle: every shape in scene order. An absorbing plane marks the particle
// for removal instead of reflecting it.
SPH_HD inline void boundaries_of(const SimConstants& c, const ParticleView& p, int32_t i, float dt) {
  for (int32_t s = 0; s < c.num_shapes; ++s) {
    const Shape& shape = c.shapes[s];
    if (shape.absorb && crossed_plane(shape, p.pos[i])) {
      p.age[i] = kRemovedAge;
      return;
    }
    collide_shape(shape, p.pos[i], p.vel[i], dt, c.gravity);
  }
}

}  // namespace sph
