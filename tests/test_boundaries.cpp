// Penalty boundaries (thesis 3.5.1, src/common/boundaries.h): a particle found outside its allowed region
// is moved back onto the surface and its velocity reflected as v' = -C_bounce v_N + C_slip v_T, the
// energy-conserving variant scaling the normal part by d / (|v| dt). Here collide_shape on random particles
// just outside every shape type: they end on the surface, the speed never grows, and each coefficient does
// exactly what the formula says. Whole runs against the walls: test_boundary_runs.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "common/boundaries.h"
#include "boundary_geometry.h"

using namespace sph_test;

namespace {

Shape base_shape(ShapeType type) {
  Shape s{};
  s.type = type;
  s.bounce = 0.0f;
  s.slip = 1.0f;
  return s;
}

Shape box_container(bool open_top = false) {
  Shape s = base_shape(ShapeType::Box);
  s.keep_inside = 1;
  s.open_top = open_top ? 1 : 0;
  s.a = {-0.5f, 0.0f, -0.3f};
  s.b = {0.5f, 1.0f, 0.3f};
  return s;
}
Shape box_obstacle() {
  Shape s = base_shape(ShapeType::Box);
  s.keep_inside = 0;
  s.a = {0.2f, 0.1f, 0.3f};
  s.b = {0.6f, 0.4f, 0.7f};
  return s;
}
Shape plane() {
  Shape s = base_shape(ShapeType::Plane);
  s.a = {0.1f, 0.2f, -0.3f};
  s.b = f3(unit({1.0, 2.0, 0.5}));
  return s;
}
Shape sphere(bool container) {
  Shape s = base_shape(ShapeType::Sphere);
  s.keep_inside = container ? 1 : 0;
  s.a = {0.1f, 0.5f, -0.2f};
  s.radius = container ? 0.4f : 0.25f;
  return s;
}
// Sphere |p - c|^2 - R^2 >= 0 as a quadric: the fluid stays outside.
const D3 kQuadricCentre{0.2, 0.3, 0.1};
const double kQuadricRadius = 0.3;
Shape quadric_sphere_obstacle() {
  Shape s = base_shape(ShapeType::Quadric);
  const D3 c = kQuadricCentre;
  const double q[16] = {1, 0, 0, -c.x, 0, 1, 0, -c.y, 0, 0, 1, -c.z, -c.x, -c.y, -c.z,
                        dotd(c, c) - kQuadricRadius * kQuadricRadius};
  for (int i = 0; i < 16; ++i) s.q[i] = float(q[i]);
  return s;
}
// Ellipsoid 1 - sum ((p_i - c_i) / a_i)^2 >= 0 as a quadric: the fluid stays inside.
const D3 kEllipsoidCentre{-0.1, 0.4, 0.2};
const D3 kEllipsoidAxes{0.5, 0.3, 0.4};
Shape quadric_ellipsoid_container() {
  Shape s = base_shape(ShapeType::Quadric);
  const D3 c = kEllipsoidCentre, a = kEllipsoidAxes;
  double q[16] = {};
  double c2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double inv = 1.0 / (comp(a, i) * comp(a, i));
    q[4 * i + i] = -inv;
    q[4 * i + 3] = q[12 + i] = comp(c, i) * inv;
    c2 += comp(c, i) * comp(c, i) * inv;
  }
  q[15] = 1.0 - c2;
  for (int i = 0; i < 16; ++i) s.q[i] = float(q[i]);
  return s;
}

// ---------------------------------------------------------------------------------------------------
// Random particles just outside a shape.

struct Sample {
  Vec3 x;
  D3 n;             // unit normal into the allowed region, where one is defined (has_normal)
  bool has_normal;
  double depth = 0.0;  // exact penetration depth of the float position x, where has_normal
};

// Random points near each shape, from RandomDraws' seeded numbers (boundary_geometry.h).
class Sampler : public RandomDraws {
 public:
  using RandomDraws::RandomDraws;
  double depth() { return std::exp(uniform(std::log(1e-4), std::log(0.02))); }  // 0.1 mm to 2 cm
  D3 velocity() { return uniform(0.1, 5.0) * direction(); }

  // A point beyond exactly one face of a box container (edges kept 5 cm away).
  Sample box_face(const Shape& s) {
    D3 x{};
    for (int i = 0; i < 3; ++i) ref(x, i) = uniform(comp(d3(s.a), i) + 0.05, comp(d3(s.b), i) - 0.05);
    const int axis = integer(0, 2);
    const bool low = s.open_top && axis == 1 ? true : integer(0, 1) == 0;
    D3 n{0, 0, 0};
    ref(n, axis) = low ? 1.0 : -1.0;
    ref(x, axis) = low ? comp(d3(s.a), axis) - depth() : comp(d3(s.b), axis) + depth();
    return with_depth(s, {f3(x), n, true});
  }
  // Beyond two or three faces of a box container at once (edges and corners).
  Sample box_corner(const Shape& s) {
    D3 x{};
    for (int i = 0; i < 3; ++i) ref(x, i) = uniform(comp(d3(s.a), i) + 0.05, comp(d3(s.b), i) - 0.05);
    const int skip = integer(0, 3);  // 3: a corner (all axes), else an edge (all axes but one)
    for (int axis = 0; axis < 3; ++axis) {
      if (axis == skip) continue;
      const bool low = s.open_top && axis == 1 ? true : integer(0, 1) == 0;
      ref(x, axis) = low ? comp(d3(s.a), axis) - depth() : comp(d3(s.b), axis) + depth();
    }
    return {f3(x), {0, 0, 0}, false};
  }
  // Inside a box obstacle, closer to one face than to any other.
  Sample box_obstacle_face(const Shape& s) {
    D3 x{};
    for (int i = 0; i < 3; ++i) ref(x, i) = uniform(comp(d3(s.a), i) + 0.05, comp(d3(s.b), i) - 0.05);
    const int axis = integer(0, 2);
    const bool low = integer(0, 1) == 0;
    D3 n{0, 0, 0};
    ref(n, axis) = low ? -1.0 : 1.0;
    ref(x, axis) = low ? comp(d3(s.a), axis) + depth() : comp(d3(s.b), axis) - depth();
    return with_depth(s, {f3(x), n, true});
  }
  Sample plane_side(const Shape& s) {
    const D3 n = d3(s.b);
    const D3 t1 = unit(std::fabs(n.x) < 0.9 ? D3{0.0, n.z, -n.y} : D3{-n.z, 0.0, n.x});
    const D3 t2{n.y * t1.z - n.z * t1.y, n.z * t1.x - n.x * t1.z, n.x * t1.y - n.y * t1.x};
    const D3 x = d3(s.a) + uniform(-1, 1) * t1 + uniform(-1, 1) * t2 - depth() * n;
    return with_depth(s, {f3(x), n, true});
  }
  Sample sphere_side(const Shape& s) {
    const D3 u = direction();
    const double r = s.keep_inside ? s.radius + depth() : s.radius - depth();
    return with_depth(s, {f3(d3(s.a) + r * u), s.keep_inside ? -1.0 * u : u, true});
  }
  Sample quadric_sphere_side() {
    const D3 u = direction();
    Sample smp{f3(kQuadricCentre + (kQuadricRadius - depth()) * u), u, true};
    smp.depth = kQuadricRadius - lend(d3(smp.x) - kQuadricCentre);  // f / |grad f| is only first order
    return smp;
  }
  // Outside the ellipsoid along its normal; the normal at the point found by the library differs from
  // this one by about depth / radius, so no exact normal is claimed.
  Sample ellipsoid_side() {
    const D3 u = direction();
    const D3 a = kEllipsoidAxes;
    const D3 on{a.x * u.x, a.y * u.y, a.z * u.z};
    const D3 outward = unit({on.x / (a.x * a.x), on.y / (a.y * a.y), on.z / (a.z * a.z)});
    return {f3(kEllipsoidCentre + on + depth() * outward), {0, 0, 0}, false};
  }

 private:
  // Box faces, planes and spheres: the signed distance is exact.
  static Sample with_depth(const Shape& s, Sample smp) {
    smp.depth = -allowed_distance(s, d3(smp.x));
    return smp;
  }
};

struct ShapeCase {
  std::string name;
  Shape shape;
  std::function<Sample(Sampler&)> sample;
  // Smallest radius of curvature of a quadric, 0 for the others. The quadric response projects with
  // Newton steps along the gradient and takes |projection - x| as the depth, which is exact to first
  // order: a convex f seen from the fluid side overshoots the surface by about depth^2 / (2 radius).
  double curvature_radius = 0.0;
};

std::vector<ShapeCase> shape_cases() {
  const Shape bc = box_container(), bo = box_obstacle(), pl = plane(), sc = sphere(true), so = sphere(false);
  const Shape open = box_container(true), qs = quadric_sphere_obstacle(), qe = quadric_ellipsoid_container();
  return {
      {"box container, faces", bc, [bc](Sampler& r) { return r.box_face(bc); }},
      {"box container, edges and corners", bc, [bc](Sampler& r) { return r.box_corner(bc); }},
      {"open-top box container, faces", open, [open](Sampler& r) { return r.box_face(open); }},
      {"open-top box container, edges and corners", open, [open](Sampler& r) { return r.box_corner(open); }},
      {"box obstacle", bo, [bo](Sampler& r) { return r.box_obstacle_face(bo); }},
      {"plane", pl, [pl](Sampler& r) { return r.plane_side(pl); }},
      {"sphere container", sc, [sc](Sampler& r) { return r.sphere_side(sc); }},
      {"sphere obstacle", so, [so](Sampler& r) { return r.sphere_side(so); }},
      {"quadric sphere obstacle", qs, [](Sampler& r) { return r.quadric_sphere_side(); }, kQuadricRadius},
      {"quadric ellipsoid container", qe, [](Sampler& r) { return r.ellipsoid_side(); }, 0.3 * 0.3 / 0.5},
  };
}

constexpr float kDt = 2e-3f;          // |v| dt from 0.2 mm to 1 cm: depth / (|v| dt) both below and above 1
constexpr double kPosTol = 1e-5;      // shapes are about 1 m across: 1e-5 relative
constexpr double kSpeedTol = 1e-6;    // float rounding of |v|
constexpr int kSamples = 2000;

}  // namespace

TEST_CASE("boundaries: sampled particles start outside their shape", "[boundaries]") {
  // Guards the unit tests below: they would pass vacuously if the samples were already allowed.
  for (const ShapeCase& c : shape_cases()) {
    INFO(c.name);
    Sampler r(7);
    for (int k = 0; k < 200; ++k) REQUIRE(allowed_distance(c.shape, d3(c.sample(r).x)) < 0.0);
  }
}

TEST_CASE("boundaries: particles inside the allowed region are left alone", "[boundaries]") {
  for (const ShapeCase& c : shape_cases()) {
    INFO(c.name);
    Sampler r(11);
    int tested = 0;
    for (int k = 0; k < 200000 && tested < 500; ++k) {
      const D3 p{r.uniform(-1.0, 1.5), r.uniform(-0.5, 1.5), r.uniform(-1.0, 1.0)};
      if (!(allowed_distance(c.shape, p) > 1e-4)) continue;
      ++tested;
      Vec3 x = f3(p), v = f3(r.velocity());
      const Vec3 x0 = x, v0 = v;
      sph::collide_shape(c.shape, x, v, kDt);
      REQUIRE(x.x == x0.x);
      REQUIRE(x.y == x0.y);
      REQUIRE(x.z == x0.z);
      REQUIRE(v.x == v0.x);
      REQUIRE(v.y == v0.y);
      REQUIRE(v.z == v0.z);
    }
    REQUIRE(tested == 500);
  }
}

TEST_CASE("boundaries: every shape puts particles back on its surface and never speeds them up", "[boundaries]") {
  for (const ShapeCase& c : shape_cases()) {
    INFO(c.name);
    Sampler r(1234);
    for (int k = 0; k < kSamples; ++k) {
      Shape s = c.shape;
      s.bounce = float(r.uniform(0.0, 1.0));
      s.slip = float(r.uniform(0.0, 1.0));
      if (k % 4 == 0) s.bounce = 1.0f;
      if (k % 8 == 0) s.slip = 1.0f;
      s.energy_conserving = r.integer(0, 1);
      const Sample smp = c.sample(r);
      Vec3 x = smp.x, v = f3(r.velocity());
      const Vec3 x0 = x, v0 = v;
      sph::collide_shape(s, x, v, kDt);
      const double after = allowed_distance(s, d3(x));
      CAPTURE(k, s.bounce, s.slip, s.energy_conserving, x0.x, x0.y, x0.z, x.x, x.y, x.z, after);
      REQUIRE(after >= -kPosTol);  // inside or on the surface
      // Moved onto the surface, not somewhere deeper inside (quadrics: to second order in the depth).
      const double depth0 = -allowed_distance(s, d3(x0));
      const double second_order = c.curvature_radius > 0.0 ? depth0 * depth0 / c.curvature_radius : 0.0;
      REQUIRE(after <= kPosTol + second_order);
      REQUIRE(lend(d3(x) - d3(x0)) <= 0.0201 * std::sqrt(3.0));  // moved by about the penetration only
      REQUIRE(lend(d3(v)) <= lend(d3(v0)) * (1.0 + kSpeedTol));
    }
  }
}

TEST_CASE("boundaries: bounce 1, slip 1 without the energy-conserving scale reflects elastically", "[boundaries]") {
  for (const ShapeCase& c : shape_cases()) {
    INFO(c.name);
    Sampler r(99);
    Shape s = c.shape;
    s.bounce = 1.0f;
    s.slip = 1.0f;
    s.energy_conserving = 0;
    for (int k = 0; k < kSamples; ++k) {
      const Sample smp = c.sample(r);
      D3 vd = r.velocity();
      if (smp.has_normal && dotd(vd, smp.n) > 0.0) vd = vd - 2.0 * dotd(vd, smp.n) * smp.n;  // moving outwards
      Vec3 x = smp.x, v = f3(vd);
      const Vec3 v0 = v;
      sph::collide_shape(s, x, v, kDt);
      CAPTURE(k, v0.x, v0.y, v0.z, v.x, v.y, v.z);
      REQUIRE(lend(d3(v)) == Approx(lend(d3(v0))).epsilon(1e-6));
      if (smp.has_normal) {
        const D3 n = smp.n;
        const double vn0 = dotd(d3(v0), n), vn = dotd(d3(v), n);
        const D3 vt0 = d3(v0) - vn0 * n, vt = d3(v) - vn * n;
        REQUIRE(vn0 < 0.0);
        REQUIRE(vn == Approx(-vn0).margin(1e-5 * lend(d3(v0))));  // normal component flipped
        REQUIRE(lend(vt - vt0) <= 1e-5 * lend(d3(v0)));          // tangent component kept
      }
    }
  }
}

TEST_CASE("boundaries: box edges and corners reflect each crossed axis", "[boundaries]") {
  Shape s = box_container();
  s.bounce = 1.0f;
  s.slip = 1.0f;
  s.energy_conserving = 0;
  Sampler r(5);
  for (int k = 0; k < kSamples; ++k) {
    const Sample smp = r.box_corner(s);
    Vec3 x = smp.x, v = f3(r.velocity());
    const Vec3 x0 = x, v0 = v;
    sph::collide_shape(s, x, v, kDt);
    for (int axis = 0; axis < 3; ++axis) {
      const double xi = comp(d3(x0), axis), vi = comp(d3(v0), axis);
      const double lo = comp(d3(s.a), axis), hi = comp(d3(s.b), axis);
      double expect_x = xi, expect_v = vi;
      if (xi < lo) {
        expect_x = lo;
        expect_v = std::fabs(vi);
      } else if (xi > hi) {
        expect_x = hi;
        expect_v = -std::fabs(vi);
      }
      CAPTURE(k, axis, xi, vi);
      REQUIRE(comp(d3(x), axis) == Approx(expect_x).margin(1e-6));
      REQUIRE(comp(d3(v), axis) == Approx(expect_v).margin(1e-6));
    }
  }
}

TEST_CASE("boundaries: an open-top box does not collide with its ceiling", "[boundaries]") {
  const Shape s = box_container(true);
  Sampler r(8);
  for (int k = 0; k < 500; ++k) {
    const D3 p{r.uniform(-0.4, 0.4), 1.0 + r.depth(), r.uniform(-0.2, 0.2)};
    Vec3 x = f3(p), v = f3(r.velocity());
    const Vec3 x0 = x, v0 = v;
    sph::collide_shape(s, x, v, kDt);
    REQUIRE(x.y == x0.y);
    REQUIRE(v.y == v0.y);
    REQUIRE(v.x == v0.x);
    REQUIRE(v.z == v0.z);
  }
  // Above the rim and beyond a side wall: only the side wall acts.
  Vec3 x{0.6f, 1.5f, 0.0f}, v{1.0f, 2.0f, 0.0f};
  Shape t = s;
  t.bounce = 1.0f;
  t.energy_conserving = 0;
  sph::collide_shape(t, x, v, kDt);
  REQUIRE(x.x == Approx(0.5f));
  REQUIRE(x.y == 1.5f);
  REQUIRE(v.x == Approx(-1.0f));
  REQUIRE(v.y == 2.0f);
}

TEST_CASE("boundaries: bounce and slip coefficients act on the normal and tangent parts", "[boundaries]") {
  for (const ShapeCase& c : shape_cases()) {
    Sampler r(31);
    for (int k = 0; k < kSamples; ++k) {
      const Sample smp = c.sample(r);
      if (!smp.has_normal) break;  // edges, corners and the ellipsoid have no single exact normal here
      INFO(c.name);
      const D3 n = smp.n;
      D3 vd = r.velocity();
      if (dotd(vd, n) > 0.0) vd = vd - 2.0 * dotd(vd, n) * n;  // approaching the wall from inside
      const Vec3 v0 = f3(vd);
      const double speed = lend(d3(v0));
      const double vn0 = dotd(d3(v0), n);
      const D3 vt0 = d3(v0) - vn0 * n;
      auto run = [&](float bounce, float slip, int ec) {
        Shape s = c.shape;
        s.bounce = bounce;
        s.slip = slip;
        s.energy_conserving = ec;
        Vec3 x = smp.x, v = v0;
        sph::collide_shape(s, x, v, kDt);
        return d3(v);
      };
      auto normal = [&](D3 v) { return dotd(v, n); };
      auto tangent = [&](D3 v) { return v - dotd(v, n) * n; };
      CAPTURE(k, vn0, speed);

      // bounce 0: the normal part is removed, the tangent part kept (slip 1).
      const D3 v_b0 = run(0.0f, 1.0f, 0);
      REQUIRE(std::fabs(normal(v_b0)) <= 1e-5 * speed);
      REQUIRE(lend(tangent(v_b0) - vt0) <= 1e-5 * speed);

      // slip 0: the tangent part is removed, the normal part reflected (bounce 1).
      const D3 v_s0 = run(1.0f, 0.0f, 0);
      REQUIRE(lend(tangent(v_s0)) <= 1e-5 * speed);
      REQUIRE(normal(v_s0) == Approx(-vn0).margin(1e-5 * speed));

      // General coefficients: v' = -bounce v_N + slip v_T.
      const float bounce = float(r.uniform(0, 1)), slip = float(r.uniform(0, 1));
      const D3 v_g = run(bounce, slip, 0);
      REQUIRE(normal(v_g) == Approx(-bounce * vn0).margin(1e-5 * speed));
      REQUIRE(lend(tangent(v_g) - double(slip) * vt0) <= 1e-5 * speed);

      // Energy conserving: the reflected normal part is scaled by depth / (|v| dt), at most 1.
      const double depth = smp.depth;
      const double scale = std::min(1.0, depth / (speed * double(kDt)));
      CAPTURE(depth, scale);
      const D3 v_ec = run(bounce, slip, 1);
      const double second_order = c.curvature_radius > 0.0 ? depth / c.curvature_radius : 0.0;
      REQUIRE(normal(v_ec) == Approx(-bounce * scale * vn0).margin((3e-4 + second_order) * speed));
      REQUIRE(lend(tangent(v_ec) - double(slip) * vt0) <= 1e-5 * speed);
    }
  }
}
