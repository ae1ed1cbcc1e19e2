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

// f = h^T Q h at h = (x, y, z, 1), in the precision T (float in the solver, double in the set-up checks).
template <class T>
SPH_HD inline T quadric_form(const float* q, T x, T y, T z) {
  const T h[4] = {x, y, z, T(1)};
  T f = T(0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) f += h[i] * T(q[4 * i + j]) * h[j];
  return f;
}

// grad f = 2 Q_sub h (seed 000, eq. 23): the first three rows of Q times the homogeneous point.
template <class T>
SPH_HD inline void quadric_form_gradient(const float* q, T x, T y, T z, T g[3]) {
  const T h[4] = {x, y, z, T(1)};
  for (int i = 0; i < 3; ++i) {
    g[i] = T(0);
    for (int j = 0; j < 4; ++j) g[i] += T(2) * T(q[4 * i + j]) * h[j];
  }
}

SPH_HD inline float quadric_value(const float* q, Vec3 p) { return quadric_form(q, p.x, p.y, p.z); }

SPH_HD inline Vec3 quadric_gradient(const float* q, Vec3 p) {
  float g[3];
  quadric_form_gradient(q, p.x, p.y, p.z, g);
  return {g[0], g[1], g[2]};
}

// Continuous collision (issue 10, item 7): a step can carry a fast particle through a thin obstacle, so
// the shapes whose forbidden region a segment can cross between two allowed points (box and sphere
// obstacles, quadrics) test the whole segment x0 -> x1 the particle moved during the step and find its
// first entry exactly: slabs for a box, a quadratic in t for a sphere or quadric. The allowed region of a
// box or sphere container and of a plane is convex, so there the end point decides (a sign change).
// Response at the entry point e with normal n: the motion along n past the surface is undone and the
// tangential motion kept, x' = x1 + d n with d = (e - x1).n, a point of the tangent plane at e (for a plane
// or a box face, the surface itself), then v is reflected as above. Keeping the tangential motion is what
// lets fluid slide over an obstacle: moving the particle back to e itself would stop it there.
// A particle that starts inside (created there, or pushed in by another shape) leaves as before: through
// the nearest face, radially, or along the quadric's gradient.

// Moves x1 onto the tangent plane at the entry point e (normal n) and reflects v there.
SPH_HD inline void entry_response(const Shape& s, Vec3 e, Vec3 n, Vec3& x, Vec3& v, float dt, Vec3 g) {
  const float depth = dot(e - x, n);
  if (depth > 0.0f) penalty_response(s, n, depth, x, v, dt, g);
}

SPH_HD inline float axis_of(const Vec3& p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }
SPH_HD inline float& axis_of(Vec3& p, int axis) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); }

// The solid a box obstacle occupies: its box, extended through the faces that lie on a wall or on another
// obstacle (Shape::reach_lo / reach_hi, obstacle_contacts.h), so that no path runs along such a face.
SPH_HD inline void obstacle_solid(const Shape& s, float lo[3], float hi[3]) {
  for (int i = 0; i < 3; ++i) {
    lo[i] = axis_of(s.a, i) - axis_of(s.reach_lo, i);
    hi[i] = axis_of(s.b, i) + axis_of(s.reach_hi, i);
  }
}

// First entry of the segment x0 + t (x1 - x0), t in [0, 1], into the open box (lo, hi) (a point on a face
// is outside): the axis and side (0 low, 1 high) of the face crossed. False when the segment misses the
// box or starts inside it.
SPH_HD inline bool box_entry(const float lo[3], const float hi[3], Vec3 x0, Vec3 x1, int& axis, int& side) {
  float t_in = -1.0f, t_out = 2.0f;
  for (int i = 0; i < 3; ++i) {
    const float p = axis_of(x0, i), dp = axis_of(x1, i) - p;
    if (dp == 0.0f) {
      if (p <= lo[i] || p >= hi[i]) return false;  // runs outside this slab (or along a face)
      continue;
    }
    const float t_lo = (lo[i] - p) / dp, t_hi = (hi[i] - p) / dp;
    const float t_near = dp > 0.0f ? t_lo : t_hi, t_far = dp > 0.0f ? t_hi : t_lo;
    if (t_near > t_in) {
      t_in = t_near;
      axis = i;
      side = dp > 0.0f ? 0 : 1;
    }
    if (t_far < t_out) t_out = t_far;
  }
  return t_in >= 0.0f && t_in <= 1.0f && t_in < t_out;
}

// Box container: per axis, so a particle leaving through an edge or a corner is handled on each axis it
// crossed. Box obstacle: the face the segment entered through, else (started inside) the nearest face.
SPH_HD inline void collide_box(const Shape& s, Vec3 x0, Vec3& x, Vec3& v, float dt, Vec3 g) {
  if (s.keep_inside) {
    const float lo[3] = {s.a.x, s.a.y, s.a.z};
    const float hi[3] = {s.b.x, s.b.y, s.b.z};
    for (int axis = 0; axis < 3; ++axis) {
      const float xi = axis_of(x, axis);
      Vec3 n{0.0f, 0.0f, 0.0f};
      float depth = 0.0f;
      if (xi < lo[axis]) {
        depth = lo[axis] - xi;
        axis_of(n, axis) = 1.0f;
      } else if (xi > hi[axis] && !(axis == 1 && s.open_top)) {
        depth = xi - hi[axis];
        axis_of(n, axis) = -1.0f;
      }
      if (depth > 0.0f) penalty_response(s, n, depth, x, v, dt, g);
    }
    return;
  }
  float lo[3], hi[3];
  obstacle_solid(s, lo, hi);
  int axis = 0, side = 0;
  if (box_entry(lo, hi, x0, x, axis, side)) {
    Vec3 n{0.0f, 0.0f, 0.0f};
    axis_of(n, axis) = side == 0 ? -1.0f : 1.0f;
    const float face = side == 0 ? lo[axis] : hi[axis];
    const float depth = side == 0 ? axis_of(x, axis) - face : face - axis_of(x, axis);
    if (depth <= 0.0f) return;  // touches the face only
    axis_of(x, axis) = face;    // on the face exactly, which counts as outside
    reflect_velocity(s, n, depth, v, dt, g);
    return;
  }
  const float d[6] = {x.x - lo[0], hi[0] - x.x, x.y - lo[1], hi[1] - x.y, x.z - lo[2], hi[2] - x.z};
  for (int i = 0; i < 6; ++i)
    if (d[i] <= 0.0f) return;  // outside the box
  int best = 0;
  for (int i = 1; i < 6; ++i)
    if (d[i] < d[best]) best = i;
  Vec3 n{0.0f, 0.0f, 0.0f};
  axis_of(n, best / 2) = (best % 2 == 0) ? -1.0f : 1.0f;
  axis_of(x, best / 2) = (best % 2 == 0) ? lo[best / 2] : hi[best / 2];
  reflect_velocity(s, n, d[best], v, dt, g);
}

// First t in [0, 1] at which f(t) = A t^2 + B t + C, with f(0) = C >= 0, becomes negative: the entry of a
// segment into the forbidden region of a sphere obstacle or a quadric. False when f stays >= 0.
SPH_HD inline bool quadratic_entry(float A, float B, float C, float& t) {
  if (A == 0.0f) {
    if (B >= 0.0f) return false;
    t = -C / B;
  } else {
    const float disc = B * B - 4.0f * A * C;
    if (disc <= 0.0f && A > 0.0f) return false;  // f >= 0 on the whole line
    const float root = sqrtf(disc > 0.0f ? disc : 0.0f);
    if (B <= 0.0f) {
      // The smaller root for A > 0, the larger for A < 0, both equal to 2C / (-B + root) (no cancellation).
      const float den = -B + root;
      t = den > 0.0f ? 2.0f * C / den : 0.0f;
    } else {
      if (A > 0.0f) return false;  // moving up a convex f: its minimum lies behind the start
      t = (-B - root) / (2.0f * A);
    }
  }
  return t >= 0.0f && t <= 1.0f;
}

SPH_HD inline void collide_sphere(const Shape& s, Vec3 x0, Vec3& x, Vec3& v, float dt, Vec3 g) {
  const Vec3 rel = x - s.a;
  const float dist = length(rel);
  if (s.keep_inside) {
    if (dist > s.radius) penalty_response(s, (-1.0f / dist) * rel, dist - s.radius, x, v, dt, g);
    return;
  }
  // Obstacle: |x0 + t (x - x0) - c|^2 - r^2 = A t^2 + B t + C.
  const Vec3 step = x - x0, rel0 = x0 - s.a;
  const float C = dot(rel0, rel0) - s.radius * s.radius;
  float t = 0.0f;
  if (C >= 0.0f && quadratic_entry(dot(step, step), 2.0f * dot(step, rel0), C, t)) {
    const Vec3 e = x0 + t * step;
    const Vec3 radial = e - s.a;
    const float re = length(radial);
    if (re > 0.0f) entry_response(s, e, (1.0f / re) * radial, x, v, dt, g);
    return;
  }
  if (dist < s.radius) {
    const Vec3 n = dist > 0.0f ? (1.0f / dist) * rel : Vec3{0.0f, 1.0f, 0.0f};
    penalty_response(s, n, s.radius - dist, x, v, dt, g);
  }
}

// u^T Q w for homogeneous points or directions u, w (w = 1 for a point, 0 for a direction).
SPH_HD inline float quadric_form(const float* q, Vec3 u, float uw, Vec3 w, float ww) {
  const float hu[4] = {u.x, u.y, u.z, uw}, hw[4] = {w.x, w.y, w.z, ww};
  float f = 0.0f;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) f += hu[i] * q[4 * i + j] * hw[j];
  return f;
}

// Allowed where f >= 0. Newton steps along the gradient find the surface point; first-order distance
// f / |grad f| is exact for planes and close for smooth quadrics. Used from inside the forbidden region.
SPH_HD inline void quadric_push_out(const Shape& s, Vec3& x, Vec3& v, float dt, Vec3 g) {
  Vec3 y = x;
  Vec3 n{0.0f, 1.0f, 0.0f};
  float f = quadric_value(s.q, y);
  if (f >= 0.0f) return;
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
}

// Along the segment f(x0 + t (x - x0)) = (d^T Q d) t^2 + 2 (d^T Q x0) t + f(x0), d = x - x0 (a direction).
SPH_HD inline void collide_quadric(const Shape& s, Vec3 x0, Vec3& x, Vec3& v, float dt, Vec3 g) {
  const Vec3 step = x - x0;
  const float C = quadric_value(s.q, x0);
  float t = 0.0f;
  const float A = quadric_form(s.q, step, 0.0f, step, 0.0f), B = 2.0f * quadric_form(s.q, step, 0.0f, x0, 1.0f);
  if (C >= 0.0f && quadratic_entry(A, B, C, t)) {
    const Vec3 e = x0 + t * step;
    const Vec3 grad = quadric_gradient(s.q, e);
    const float gl = length(grad);
    if (gl > 0.0f) entry_response(s, e, (1.0f / gl) * grad, x, v, dt, g);
  }
  quadric_push_out(s, x, v, dt, g);  // still inside: a curved surface bent over the tangent plane, or a start inside
}

// One shape for a particle that moved from x0 to x during the step (x0 = x: a particle found at x with
// no known path, as the shape tests use it). g: the gravity acceleration (see reflect_velocity); zero when
// only the geometry matters.
SPH_HD inline void collide_shape(const Shape& s, Vec3 x0, Vec3& x, Vec3& v, float dt, Vec3 g) {
  switch (s.type) {
    case ShapeType::Box:
      collide_box(s, x0, x, v, dt, g);
      break;
    case ShapeType::Plane: {
      const float phi = dot(x - s.a, s.b);
      if (phi < 0.0f) penalty_response(s, s.b, -phi, x, v, dt, g);
      break;
    }
    case ShapeType::Sphere:
      collide_sphere(s, x0, x, v, dt, g);
      break;
    case ShapeType::Quadric:
      collide_quadric(s, x0, x, v, dt, g);
      break;
  }
}

// A particle found at x with no known path.
SPH_HD inline void collide_shape(const Shape& s, Vec3& x, Vec3& v, float dt, Vec3 g = Vec3{0.0f, 0.0f, 0.0f}) {
  collide_shape(s, x, x, v, dt, g);
}

// Whether x lies outside the shape's allowed region (only planes absorb; see Shape::absorb).
SPH_HD inline bool crossed_plane(const Shape& s, Vec3 x) { return dot(x - s.a, s.b) < 0.0f; }

// Phase "boundaries" for one particle: every shape in scene order, each testing the segment from where the
// step started (recorded by predict) to where the particle is now. An absorbing plane marks the particle
// for removal instead of reflecting it.
SPH_HD inline void boundaries_of(const SimConstants& c, const ParticleView& p, int32_t i, float dt) {
  for (int32_t s = 0; s < c.num_shapes; ++s) {
    const Shape& shape = c.shapes[s];
    if (shape.absorb && crossed_plane(shape, p.pos[i])) {
      p.age[i] = kRemovedAge;
      return;
    }
    collide_shape(shape, p.pos_start[i], p.pos[i], p.vel[i], dt, c.gravity);
  }
}

// The boundary particles' and the rigid bodies' collision (boundary_view.h, collide_boundary_particles) of
// particle i, a loop of its own after the shapes': in the shapes' loop it made the GPU keep the box tests'
// small arrays in a stack frame (ptxas, sm_90). h2: the support radius squared [m^2].
struct BoundaryParticleCollisionFn {
  GridView g;
  ParticleView p;
  float h2;
  SPH_HD void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) collide_boundary_particles(g.boundary, g.bodies, g.num_bodies, h2, p.pos, p.vel, i);
  }
};

}  // namespace sph
