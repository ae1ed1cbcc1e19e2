// Contact between rigid bodies (issue 13; rigid_body.h, contact_between_bodies): a box dropped on another
// comes to rest on top of it, one dropped on a fixed body leaves that body where it is, and two boxes that
// collide without gravity conserve their momentum and do not stay inside each other. The bodies are those of
// scenes/floating_box.json's set-up, stepped here without fluid (no fluid force), so only gravity, the
// container and the contact act.
#include <array>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "common/body_contact.h"
#include "common/body_math.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

sph::BodySpec box(sph::Vec3d lo, sph::Vec3d hi, double density) {
  sph::BodySpec b;
  b.min = lo;
  b.max = hi;
  b.density = density;
  return b;
}

// The scene's set-up with `bodies` instead of its own (the fluid stays below y = 0.15 m; the bodies here sit
// above it or the fluid is removed where they are, which does not matter: it is not stepped).
struct BodiesAlone {
  sph::Simulation sim;
  std::vector<sph::RigidBody> bodies;
  explicit BodiesAlone(const std::vector<sph::BodySpec>& specs, const std::vector<std::string>& overrides = {})
      : sim(make(specs, overrides), cpu_factory(), 1.0), bodies(sim.setup().bodies) {}
  static sph::Scene make(const std::vector<sph::BodySpec>& specs, const std::vector<std::string>& overrides) {
    sph::Scene s = scene_file("floating_box.json", overrides);
    s.bodies = specs;
    return s;
  }
  void step(double dt) {
    for (sph::RigidBody& b : bodies) {
      b.force = {0.0, 0.0, 0.0};
      b.torque = {0.0, 0.0, 0.0};
      sph::advance_body(b, sim.setup().constants, dt);
    }
    sph::contact_between_bodies(bodies);
  }
};

double bottom(const sph::RigidBody& b) { return b.centre[1] - b.half_extent[1]; }
double top(const sph::RigidBody& b) { return b.centre[1] + b.half_extent[1]; }

}  // namespace

TEST_CASE("body contact: a box dropped on another box comes to rest on top of it", "[bodies][contact]") {
  // Lower box 0.12 x 0.06 x 0.12 m on the floor of the tank (at y = 0.0005: set-up refuses a body that
  // crosses a wall), the upper one 0.06 m cube 4 cm above it, both free. Without contact the upper box would
  // fall through to the floor.
  BodiesAlone s({box({0.14, 0.0005, 0.04}, {0.26, 0.0605, 0.16}, 800.0), box({0.17, 0.1, 0.07}, {0.23, 0.16, 0.13}, 500.0)});
  const double d = s.sim.setup().spacing;
  for (int k = 0; k < 3000; ++k) s.step(5e-4);  // 1.5 s
  const sph::RigidBody& lower = s.bodies[0];
  const sph::RigidBody& upper = s.bodies[1];
  INFO("lower box from " << bottom(lower) << " to " << top(lower) << " m, upper box from " << bottom(upper) << " m; speeds "
                         << lower.velocity[1] << ", " << upper.velocity[1] << " m/s; spacing " << d << " m");
  CHECK(std::fabs(bottom(lower)) <= 0.1 * d);               // on the floor
  CHECK(std::fabs(bottom(upper) - top(lower)) <= 0.1 * d);  // on the lower box, not in it
  CHECK(std::fabs(upper.velocity[1]) <= 0.01);              // at rest
  CHECK(std::fabs(upper.centre[0] - 0.2) <= 0.1 * d);       // dropped squarely: it did not slide off
}

TEST_CASE("body contact: a fixed body stays put when a box lands on it", "[bodies][contact]") {
  sph::BodySpec base = box({0.14, 0.05, 0.04}, {0.26, 0.08, 0.16}, 800.0);
  base.free = false;  // "motion": "fixed"
  BodiesAlone s({base, box({0.17, 0.12, 0.07}, {0.23, 0.18, 0.13}, 500.0)});
  const std::array<double, 3> start = s.bodies[0].centre;
  for (int k = 0; k < 2000; ++k) s.step(5e-4);
  CHECK(s.bodies[0].centre == start);
  CHECK(std::fabs(bottom(s.bodies[1]) - top(s.bodies[0])) <= 0.1 * s.sim.setup().spacing);
}

TEST_CASE("body contact: two boxes colliding without gravity conserve momentum and separate", "[bodies][contact]") {
  // A heavy box moving right into a light one moving left, offset vertically so that they also spin.
  BodiesAlone s({box({0.05, 0.2, 0.06}, {0.13, 0.26, 0.14}, 1000.0), box({0.2, 0.23, 0.07}, {0.26, 0.29, 0.13}, 300.0)},
                {"gravity=[0,0,0]"});
  s.bodies[0].velocity = {0.5, 0.0, 0.0};
  s.bodies[1].velocity = {-0.8, 0.0, 0.0};
  const auto momentum = [&] {
    std::array<double, 3> p{0.0, 0.0, 0.0};
    for (const sph::RigidBody& b : s.bodies)
      for (std::size_t k = 0; k < 3; ++k) p[k] += b.mass * b.velocity[k];
    return p;
  };
  const auto energy = [&] {  // translational plus rotational kinetic energy [J]
    double e = 0.0;
    for (const sph::RigidBody& b : s.bodies) {
      const Eigen::Matrix3d R = sph::quaternion(b.orientation).toRotationMatrix();
      const Eigen::Vector3d w = sph::e3(b.omega);
      e += 0.5 * b.mass * sph::e3(b.velocity).squaredNorm() + 0.5 * w.dot(R * sph::e3(b.inertia).asDiagonal() * R.transpose() * w);
    }
    return e;
  };
  const std::array<double, 3> before = momentum();
  const double energy_before = energy();
  bool touched = false;
  for (int k = 0; k < 400; ++k) {  // 0.2 s: they meet after about 0.05 s
    s.step(5e-4);
    touched = touched || s.bodies[0].body_contact;
  }
  const std::array<double, 3> after = momentum();
  REQUIRE(touched);
  const double scale = s.bodies[0].mass * 0.5 + s.bodies[1].mass * 0.8;
  for (std::size_t k = 0; k < 3; ++k) CHECK(std::fabs(after[k] - before[k]) <= 1e-12 * scale);
  // Inelastic impulses take energy out, never put it in; and the boxes no longer overlap.
  INFO("kinetic energy " << energy_before << " J before, " << energy() << " J after");
  CHECK(energy() <= energy_before);
  CHECK(energy() >= 0.2 * energy_before);  // not stopped dead either: momentum is kept
  CHECK(s.bodies[1].centre[0] - s.bodies[1].half_extent[0] >= s.bodies[0].centre[0] + s.bodies[0].half_extent[0] - 0.1 * s.sim.setup().spacing);
  // The light box was hit off its centre: it spins.
  CHECK(std::fabs(s.bodies[1].omega[2]) > 0.1);
}

TEST_CASE("body contact: a sphere dropped on a box rests on it, one dropped on a sphere rolls off it", "[bodies][contact]") {
  sph::BodySpec ball;
  ball.sphere = true;
  ball.center = {0.2, 0.14, 0.1};
  ball.radius = 0.03;
  ball.density = 500.0;
  SECTION("on a box") {
    BodiesAlone s({box({0.14, 0.0005, 0.04}, {0.26, 0.0605, 0.16}, 800.0), ball});
    for (int k = 0; k < 3000; ++k) s.step(5e-4);
    const sph::RigidBody& b = s.bodies[1];
    INFO("ball centre at " << b.centre[0] << ", " << b.centre[1] << " m");
    CHECK(std::fabs(b.centre[1] - (top(s.bodies[0]) + 0.03)) <= 0.1 * s.sim.setup().spacing);
  }
  SECTION("on a fixed sphere, a little off its top: it rolls off and lands on the floor beside it") {
    sph::BodySpec base = ball;
    base.center = {0.2, 0.05, 0.1};
    base.radius = 0.04;
    base.free = false;
    ball.center = {0.205, 0.15, 0.1};
    BodiesAlone s({base, ball});
    for (int k = 0; k < 4000; ++k) s.step(5e-4);
    const sph::RigidBody& b = s.bodies[1];
    INFO("ball centre at " << b.centre[0] << ", " << b.centre[1] << " m");
    CHECK(std::fabs(b.centre[1] - 0.03) <= 0.1 * s.sim.setup().spacing);  // on the floor
    CHECK((sph::e3(b.centre) - sph::e3(s.bodies[0].centre)).norm() >= 0.07 - 0.1 * s.sim.setup().spacing);  // not inside
  }
}
