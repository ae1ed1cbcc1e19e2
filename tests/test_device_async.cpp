// The device back end's asynchronous step (issue 11, item 2) against the serial reference: what the step
// leaves for the host to read once (the diagnostics, the count of particles a recycling step kept) must
// be what the reference finds, and recycling must follow the constants it is given. Part of
// sph_device_tests (SPH_DEVICE_BACKEND names the back end under test, test_device_backend.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "app/backends.h"
#include "common/guided_creation.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

std::string backend_under_test() {
  const char* env = std::getenv("SPH_DEVICE_BACKEND");
  return env ? env : "host";
}

// n particles of fluid 0 on a jittered lattice in the dam break's column, at rest density, ages spread
// over [0, 1) s.
sph::ParticleState column(const sph::Setup& s, int32_t n) {
  sph::ParticleState ps;
  const float dx = float(s.spacing);
  for (int32_t i = 0; i < n; ++i) {
    sph::Spawn sp{};
    sp.pos = s.particles.pos[std::size_t(i)];
    sp.vel = sph::Vec3{0.01f * float(i % 7), 0.0f, -0.01f * float(i % 5)};
    sp.pos.x += 0.05f * dx * float(i % 3);
    sp.age = float(i % 100) / 100.0f;
    sp.density = s.constants.fluids[0].rest_density;
    sp.id = int32_t(i);
    ps.append(sp);
  }
  return ps;
}

std::vector<int32_t> sorted_ids(const sph::ParticleState& ps) {
  std::vector<int32_t> ids = ps.id;
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace

TEST_CASE("recycling follows the constants: none without a lifetime, the expired ones once one is set", "[device]") {
  const sph::Setup s = sph::create_setup(scene_file("dam_break.json", {"resolution.particles_across=10"}), 1.0);
  REQUIRE(s.particles.size() >= 500);
  const sph::ParticleState start = column(s, 500);
  sph::CpuBackend cpu(s.constants);
  auto dev = sph::backend_factory(backend_under_test())(s.constants);
  for (sph::Backend* b : {static_cast<sph::Backend*>(&cpu), dev.get()}) {
    b->upload(start);
    b->initialise_forces();
  }
  const float dt = 1e-4f;
  cpu.step(dt);
  dev->step(dt);
  CHECK(dev->size() == start.size());  // no lifetime, no absorbing shape: every particle stays

  // A lifetime of 0.5 s from now on: the particles older than that (about half) expire in the next step.
  sph::SimConstants aging = s.constants;
  aging.fluids[0].lifetime = 0.5f;
  cpu.set_constants(aging);
  dev->set_constants(aging);
  cpu.step(dt);
  dev->step(dt);
  CHECK(cpu.size() > start.size() / 3);
  CHECK(cpu.size() < 2 * start.size() / 3);
  REQUIRE(dev->size() == cpu.size());
  CHECK(sorted_ids(dev->download()) == sorted_ids(cpu.download()));
  for (float age : dev->download().age) CHECK(age <= 0.5f);

  // And none once the lifetime is taken away again.
  cpu.set_constants(s.constants);
  dev->set_constants(s.constants);
  const std::size_t kept = dev->size();
  for (int i = 0; i < 3; ++i) dev->step(dt);
  CHECK(dev->size() == kept);
}

TEST_CASE("diagnostics after a step and an emission are the reference's", "[device]") {
  const sph::Setup s = sph::create_setup(scene_file("dam_break.json", {"resolution.particles_across=10"}), 1.0);
  const sph::ParticleState start = column(s, 400);
  sph::CpuBackend cpu(s.constants);
  auto dev = sph::backend_factory(backend_under_test())(s.constants);
  for (sph::Backend* b : {static_cast<sph::Backend*>(&cpu), dev.get()}) {
    b->upload(start);
    b->initialise_forces();
    b->step(1e-4f);
    (void)b->diagnose();  // the step's diagnostics: an emission after them adds its own (on every build)
  }
  // A fast particle emitted after the step: it is the fastest, at the index it was appended at.
  sph::Spawn fast{};
  fast.pos = start.pos[0] + sph::Vec3{0.0f, 0.0f, 0.05f};
  fast.vel = sph::Vec3{3.0f, 0.0f, -4.0f};
  fast.density = s.constants.fluids[0].rest_density;
  fast.id = 1000;
  cpu.emit({fast});
  dev->emit({fast});
  const sph::Diagnostics r = cpu.diagnose(), d = dev->diagnose();
  REQUIRE(dev->size() == start.size() + 1);
  CHECK(r.max_speed == 5.0f);
  CHECK(d.max_speed == r.max_speed);
  REQUIRE(d.fastest == int32_t(start.size()));
  CHECK(dev->download().id[std::size_t(d.fastest)] == fast.id);
  CHECK(d.non_finite == -1);
  if (backend_under_test() == "host") CHECK(d.max_accel == r.max_accel);  // cuda's default build rounds differently

  // A particle with a NaN velocity, emitted next, is found (the least such index, as the reference's).
  sph::Spawn broken = fast;
  broken.vel.y = std::numeric_limits<float>::quiet_NaN();
  broken.id = 1001;
  cpu.emit({broken});
  dev->emit({broken});
  const sph::Diagnostics r2 = cpu.diagnose(), d2 = dev->diagnose();
  CHECK(r2.non_finite == int32_t(start.size()) + 1);
  CHECK(d2.non_finite == r2.non_finite);
}
