// Continuous collision and obstacle contacts (boundaries.h, obstacle_contacts.h; issue 10, items 4 and 7):
//  (a) single particles crossing a thin shape within one step stop on the side they came from, for box
//      and sphere obstacles and quadrics, and keep their motion along the surface;
//  (b) a block of water hitting a 1 mm plate at 6 m/s with a step of 1.15 mm: no particle gets through;
//  (c) faces of box obstacles lying on walls or on other obstacles are sealed, and a dam break against a
//      box resting on the floor never has a particle inside or under the box.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "common/boundaries.h"
#include "common/obstacle_contacts.h"
#include "physics_helpers.h"

using namespace sph_test;
using sph::Shape;
using sph::ShapeType;
using sph::Vec3;

namespace {

constexpr float kDt = 2e-4f;
const Vec3 kNoGravity{0.0f, 0.0f, 0.0f};

Shape obstacle(ShapeType type) {
  Shape s{};
  s.type = type;
  s.keep_inside = 0;
  s.bounce = 0.0f;
  s.slip = 1.0f;
  return s;
}

// A 1 mm plate: x, z in [-1, 1], y in [0, 0.001].
Shape plate() {
  Shape s = obstacle(ShapeType::Box);
  s.a = {-1.0f, 0.0f, -1.0f};
  s.b = {1.0f, 0.001f, 1.0f};
  return s;
}

// A sphere of radius 1 mm at the origin, and the same sphere as a quadric |p|^2 - r^2 >= 0.
Shape small_sphere() {
  Shape s = obstacle(ShapeType::Sphere);
  s.radius = 0.001f;
  return s;
}
Shape small_quadric_sphere() {
  Shape s = obstacle(ShapeType::Quadric);
  const float q[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1e-6f};
  for (int i = 0; i < 16; ++i) s.q[i] = q[i];
  return s;
}

// Whether a particle lies inside the box strictly below its top face (inside or under it).
bool under_box(Vec3 x, const Shape& box) {
  return x.x > box.a.x && x.x < box.b.x && x.z > box.a.z && x.z < box.b.z && x.y < box.b.y;
}

}  // namespace

TEST_CASE("collision: a particle crossing a thin shape within one step stops on the side it came from",
          "[collision]") {
  // 6 m/s for 2e-4 s: 1.2 mm per step, more than the plate is thick or the sphere is wide.
  const Vec3 v0{0.0f, -6.0f, 0.0f};
  SECTION("box obstacle (a 1 mm plate)") {
    const Shape s = plate();
    for (const float x_offset : {0.0f, 0.3f, -0.7f}) {
      const Vec3 x0{x_offset, 0.0011f, 0.1f};
      Vec3 x = x0 + kDt * v0, v = v0;
      REQUIRE(x.y < s.a.y);  // the end point alone is outside the plate: a test of x1 would miss it
      sph::collide_shape(s, x0, x, v, kDt, kNoGravity);
      CHECK(x.y == s.b.y);   // on the top face
      CHECK(x.x == x0.x);    // straight down: no sideways shift
      CHECK(v.y == 0.0f);    // bounce 0: the normal speed is gone
    }
  }
  SECTION("sphere obstacle and the same sphere as a quadric") {
    for (const Shape& s : {small_sphere(), small_quadric_sphere()}) {
      const Vec3 x0{0.0002f, 0.0011f, 0.0f};
      Vec3 x = x0 + Vec3{0.0f, -0.0025f, 0.0f}, v = v0;
      REQUIRE(length(x) > 0.001f);  // ends beyond the sphere
      sph::collide_shape(s, x0, x, v, kDt, kNoGravity);
      INFO("shape type " << int(s.type) << ": ends at (" << x.x << ", " << x.y << ", " << x.z << ")");
      CHECK(x.y > 0.0f);                                 // still on the upper side
      CHECK(length(x) >= 0.001f * (1.0f - 1e-5f));       // not inside
      CHECK(dot(v, x) >= -1e-6f * length(v) * length(x));  // not moving into the sphere
    }
  }
}

TEST_CASE("collision: motion along an obstacle's surface is kept, only the motion into it is undone",
          "[collision]") {
  const Shape s = plate();
  const Vec3 x0{0.2f, s.b.y, 0.0f};  // resting on the plate
  const Vec3 v0{1.0f, -0.05f, 0.5f};
  Vec3 x = x0 + kDt * v0, v = v0;
  sph::collide_shape(s, x0, x, v, kDt, kNoGravity);
  CHECK(x.y == s.b.y);
  CHECK(x.x == Approx(x0.x + kDt * v0.x).epsilon(1e-6));
  CHECK(x.z == Approx(x0.z + kDt * v0.z).epsilon(1e-6));
  CHECK(v.x == v0.x);  // slip 1: the tangential velocity is kept
  CHECK(v.z == v0.z);
}

TEST_CASE("collision: a block hitting a 1 mm plate at 6 m/s with 1.15 mm steps stays on the plate", "[collision]") {
  sph::Scene scene = sph::load_scene(std::string(SPH_SOURCE_DIR) + "/tests/data/thin_plate.json");
  sph::Simulation sim(scene, cpu_factory(), scene.run_time);
  const Shape& p = sim.setup().constants.shapes[0];
  REQUIRE(sim.particles().size() == 2048);
  REQUIRE(6.0 * scene.time_step.dt > 1.1 * (p.b.y - p.a.y));  // a step is longer than the plate is thick
  int through = 0, inside = 0;
  float lowest = 1.0f;
  while (sim.time() < scene.run_time) {
    sim.advance();
    for (const Vec3& x : sim.particles().pos) {
      lowest = std::min(lowest, x.y);
      if (x.y < p.a.y) ++through;
      else if (under_box(x, p)) ++inside;
    }
  }
  INFO(sim.steps() << " steps; lowest particle at y = " << lowest << " m (plate top " << p.b.y << " m)");
  CHECK(through == 0);
  CHECK(inside == 0);
  CHECK(lowest == p.b.y);  // the block did reach the plate
}

TEST_CASE("contacts: faces of box obstacles on walls or on other obstacles are sealed", "[collision]") {
  Shape shapes[5] = {};
  Shape& tank = shapes[0];
  tank.type = ShapeType::Box;
  tank.keep_inside = 1;
  tank.open_top = 1;
  tank.a = {0.0f, 0.0f, 0.0f};
  tank.b = {1.0f, 1.0f, 0.2f};
  Shape& on_floor = shapes[1] = obstacle(ShapeType::Box);  // on the floor, spanning the depth, up to the open top
  on_floor.a = {0.4f, 0.0f, 0.0f};
  on_floor.b = {0.5f, 1.0f, 0.2f};
  Shape& stacked = shapes[2] = obstacle(ShapeType::Box);  // on top of the next one, inside its footprint
  stacked.a = {0.7f, 0.3f, 0.05f};
  stacked.b = {0.8f, 0.4f, 0.15f};
  Shape& base = shapes[3] = obstacle(ShapeType::Box);  // floats 2 cm above the floor: a resolved gap
  base.a = {0.65f, 0.02f, 0.02f};
  base.b = {0.85f, 0.3f, 0.18f};
  Shape& floor_plane = shapes[4];
  floor_plane.type = ShapeType::Plane;
  floor_plane.a = {0.0f, 0.0f, 0.0f};
  floor_plane.b = {0.0f, 1.0f, 0.0f};
  sph::seal_obstacle_contacts(shapes, 5, 0.005f);  // half a spacing of 1 cm

  CHECK(on_floor.reach_lo.y > 1e29f);  // floor (box container and plane)
  CHECK(on_floor.reach_lo.z > 1e29f);  // front and back walls
  CHECK(on_floor.reach_hi.z > 1e29f);
  CHECK(on_floor.reach_hi.y == 0.0f);  // open top: no ceiling to seal against
  CHECK(on_floor.reach_lo.x == 0.0f);  // free sides
  CHECK(on_floor.reach_hi.x == 0.0f);
  CHECK(stacked.reach_lo.y == Approx(0.3f - 0.02f));  // through the base, not beyond it
  CHECK(stacked.reach_lo.x == 0.0f);
  CHECK(base.reach_lo.y == 0.0f);  // 2 cm above the floor, four spacings: fluid may pass under it
  CHECK(base.reach_hi.y == 0.0f);  // the stacked box does not cover its top face
}

TEST_CASE("contacts: a dam break against a box resting on the floor never gets under the box", "[collision]") {
  sph::Scene scene = sph::load_scene(std::string(SPH_SOURCE_DIR) + "/tests/data/dam_break_box.json");
  sph::Simulation sim(scene, cpu_factory(), 0.2);
  const Shape& box = sim.setup().constants.shapes[1];
  int under = 0, reached = 0;
  while (sim.time() < 0.2) {
    sim.advance();
    for (const Vec3& x : sim.particles().pos) {
      if (under_box(x, box)) ++under;
      if (x.x == box.a.x && x.y < box.b.y) ++reached;  // stopped on the box's upstream face
    }
  }
  INFO(sim.steps() << " steps; particle-steps on the upstream face: " << reached);
  CHECK(reached > 0);  // the water did hit the box
  CHECK(under == 0);
}
