// Every boundary shape and response, emission with recycling, and a case above 100k particles, on the
// device back end against the serial reference (issue 11, items 5 and 10). Each case runs side by side
// (every field compared after every step), then one step phase by phase from where the run ended; the
// reference counts what really happened (shapes hit, particles absorbed or aged out), so a case cannot
// pass without exercising what it claims.
#include <catch2/catch.hpp>

#include <string>

#include "device_compare.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

sph::Scene device_scene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return sph::load_scene(std::string(SPH_SOURCE_DIR) + "/tests/data/device/" + name, overrides);
}

// One step phase by phase from where the reference's run ended, with its last time step.
void compare_last_step(sph::Simulation& ref) {
  const float dt = float(ref.last_dt());
  REQUIRE(dt > 0.0f);
  compare_phases(ref.setup().constants, ref.particles(), dt);
}

}  // namespace

TEST_CASE("device shapes: box container (open top, energy-conserving), box, sphere, quadric, plane", "[device][shapes]") {
  const sph::Scene scene = device_scene("shapes.json");
  std::unique_ptr<sph::Simulation> ref;
  const Contacts seen = compare_runs(scene, 200, &ref);
  const sph::SimConstants& c = ref->setup().constants;
  REQUIRE(c.num_shapes == 5);
  const char* names[] = {"box container (open top, energy-conserving)", "box obstacle", "sphere obstacle", "quadric", "plane"};
  REQUIRE(c.shapes[0].open_top == 1);
  REQUIRE(c.shapes[0].energy_conserving == 1);
  for (int k = 0; k < c.num_shapes; ++k) {
    INFO(names[k] << ": particle-steps with a hit " << seen.hits[std::size_t(k)]);
    CHECK(seen.hits[std::size_t(k)] > 0);
  }
  INFO("particle-steps above the open top " << seen.above_open_top);
  CHECK(seen.above_open_top > 0);
  compare_last_step(*ref);
}

TEST_CASE("device shapes: a sphere container with energy-conserving bouncing walls", "[device][shapes]") {
  std::unique_ptr<sph::Simulation> ref;
  const Contacts seen = compare_runs(device_scene("sphere_tank.json"), 200, &ref);
  const sph::Shape& tank = ref->setup().constants.shapes[0];
  REQUIRE(tank.type == sph::ShapeType::Sphere);
  REQUIRE(tank.keep_inside == 1);
  REQUIRE(tank.energy_conserving == 1);
  INFO("particle-steps with a hit " << seen.hits[0]);
  CHECK(seen.hits[0] > 0);
  compare_last_step(*ref);
}

TEST_CASE("device shapes: jets with recycling by age and by an absorbing plane", "[device][shapes]") {
  const sph::Scene scene = device_scene("jet.json");
  std::unique_ptr<sph::Simulation> ref;
  const Contacts seen = compare_runs(scene, 200, &ref);
  INFO("absorbing plane hits " << seen.hits[0] << ", absorbed " << seen.absorbed << ", aged out " << seen.aged_out
                               << ", alive " << ref->particles().size());
  CHECK(ref->setup().constants.shapes[0].absorb == 1);
  CHECK(seen.hits[0] > 0);
  CHECK(seen.absorbed > 0);
  CHECK(seen.aged_out > 0);
  compare_last_step(*ref);
}

// Above 100k particles, a few steps only (about 2 s on 2 shared cores, reference and device together).
TEST_CASE("device: the dam break above 100k particles", "[device][large]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=38"});
  std::unique_ptr<sph::Simulation> ref;
  compare_runs(scene, 5, &ref);
  INFO(ref->particles().size() << " particles");
  CHECK(ref->particles().size() > 100000);
  compare_last_step(*ref);
}
