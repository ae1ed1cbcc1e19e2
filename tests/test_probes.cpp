// Water-height probes (metrics.h, probe_depth; scene key "probes"): the depth a gauge reads from a lattice
// of known depth, along any direction of gravity, and in the SPHERIC-2 scene before the dam breaks.
#include <array>
#include <cmath>

#include <catch2/catch.hpp>

#include "common/kernels.h"
#include "common/metrics.h"
#include "common/solid_penetration.h"
#include "physics_helpers.h"

using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

// A block of nx x ny x nz particles at spacing s from `lo` (cell centres), mass rho0 s^3, and constants with
// h = 2 s and gravity g.
struct Block {
  sph::SimConstants c{};
  sph::ParticleState ps;
};

Block lattice(int nx, int ny, int nz, double s, sph::Vec3 lo, sph::Vec3 gravity) {
  Block b;
  b.c.kernel = sph::make_kernel_coeffs(2.0 * s);
  b.c.gravity = gravity;
  b.c.num_fluids = 1;
  b.c.fluids[0].rest_density = 1000.0f;
  b.c.fluids[0].mass = float(1000.0 * s * s * s);
  int id = 0;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        const sph::Vec3 x{lo.x + float((i + 0.5) * s), lo.y + float((j + 0.5) * s), lo.z + float((k + 0.5) * s)};
        b.ps.append(sph::Spawn{x, sph::Vec3{0, 0, 0}, 0.0f, 1000.0f, 0, id++});
      }
  return b;
}

}  // namespace

TEST_CASE("a probe reads the depth of a resting layer wherever it stands, and 0 where it is dry", "[probes]") {
  const double s = 0.01;
  const Block b = lattice(20, 12, 20, s, sph::Vec3{0, 0, 0}, sph::Vec3{0, -9.81f, 0});  // 0.12 m deep
  // On a particle, between particles, anywhere: within 0.5% of the depth (lattice error of the disc sum).
  for (const auto& at : {std::array<double, 3>{0.105, 0.0, 0.105}, std::array<double, 3>{0.1, 0.0, 0.1},
                         std::array<double, 3>{0.0937, 0.0, 0.1121}})
    CHECK_THAT(sph::probe_depth(b.c, b.ps, at), WithinRel(0.12, 0.005));
  // Raised by 5 cm, it reads the water above itself (within one layer: the cut runs through a layer).
  CHECK_THAT(sph::probe_depth(b.c, b.ps, {0.1, 0.05, 0.1}), WithinAbs(0.07, s));
  // Beside the block, farther than the disc radius 1.5 h = 0.03 m: dry.
  CHECK(sph::probe_depth(b.c, b.ps, {0.24, 0.0, 0.1}) == 0.0);
  CHECK(sph::probe_depth(b.c, b.ps, {0.1, 0.13, 0.1}) == 0.0);  // above the water
}

TEST_CASE("a probe measures along gravity, whatever its direction, and reads 0 without gravity", "[probes]") {
  const double s = 0.01;
  // Gravity along +x: "up" is -x, so the layer 0.08 m thick rests against the wall x = 0.2.
  const Block b = lattice(8, 20, 20, s, sph::Vec3{0.12f, 0, 0}, sph::Vec3{9.81f, 0, 0});
  CHECK_THAT(sph::probe_depth(b.c, b.ps, {0.2, 0.1, 0.1}), WithinRel(0.08, 0.005));
  CHECK(sph::probe_depth(b.c, b.ps, {0.0, 0.1, 0.1}) == 0.0);  // "above" the layer: nothing above it
  Block none = b;
  none.c.gravity = sph::Vec3{0, 0, 0};
  CHECK(sph::probe_depth(none.c, none.ps, {0.2, 0.1, 0.1}) == 0.0);
}

TEST_CASE("dam_break_obstacle: before the dam breaks H4 reads the column's depth, H1 to H3 and box_front are dry", "[probes][scenes]") {
  sph::Scene scene = sph_test::scene_file("dam_break_obstacle.json", {"resolution.spacing=0.05"});
  REQUIRE(scene.probes.size() == 5);  // H1 to H4, box_front
  sph::Simulation sim(scene, sph_test::cpu_factory(), 0.01);
  const sph::SimConstants& c = sim.setup().constants;
  // The column fills 11 layers of 0.05 m: 0.55 m.
  CHECK_THAT(sph::probe_depth(c, sim.particles(), scene.probes[3].position), WithinRel(0.55, 0.01));
  for (const int i : {0, 1, 2, 4}) CHECK(sph::probe_depth(c, sim.particles(), scene.probes[std::size_t(i)].position) == 0.0);
}

TEST_CASE("the leak check measures how deep fluid is inside obstacles, containers and bodies", "[probes][leaks]") {
  // solid_penetration.h, which sph_run's deepest_in_solid column and the cli_leak_* tests rely on: particles
  // put where the depth is known.
  const auto state = [](std::initializer_list<sph::Vec3> points) {
    sph::ParticleState ps;
    int id = 0;
    for (const sph::Vec3& x : points) ps.append(sph::Spawn{x, sph::Vec3{0, 0, 0}, 0.0f, 1000.0f, 0, id++});
    return ps;
  };
  SECTION("a box obstacle and the container (dam_break_obstacle)") {
    sph::Scene scene = sph_test::scene_file("dam_break_obstacle.json", {"resolution.spacing=0.05"});
    sph::Simulation sim(scene, sph_test::cpu_factory(), 0.01);
    const sph::SimConstants& c = sim.setup().constants;
    // 3 cm below the box's top face (its sides are 8 cm away), 2 cm outside the tank's near wall, free fluid.
    const sph::ParticleState ps = state({{0.744f, 0.131f, 0.5f}, {-0.02f, 0.3f, 0.5f}, {1.5f, 0.3f, 0.5f}});
    const sph::Penetration p = sph::solid_penetration(c, sim.setup().meshes, sim.backend().bodies(), ps, 0.01);
    CHECK_THAT(p.deepest, WithinAbs(0.03, 1e-6));
    CHECK(p.count == 2);
    CHECK(sph::solid_penetration(c, {}, {}, state({{1.5f, 0.3f, 0.5f}}), 0.0).deepest == 0.0);
  }
  SECTION("a rigid body at its current pose (floating_box) and a mesh (mesh_obstacle's cup)") {
    sph::Simulation sim(sph_test::scene_file("floating_box.json"), sph_test::cpu_factory(), 0.01);
    const sph::RigidBody& body = sim.backend().bodies().at(0);  // 0.08 x 0.06 x 0.08 m, centre (0.2, 0.19, 0.1)
    const sph::Vec3 centre{float(body.centre[0]), float(body.centre[1]), float(body.centre[2])};
    const sph::Penetration p = sph::solid_penetration(sim.setup().constants, {}, sim.backend().bodies(),
                                                      state({centre + sph::Vec3{0.0f, 0.02f, 0.0f}}), 0.005);
    CHECK_THAT(p.deepest, WithinAbs(0.01, 1e-6));  // 1 cm below its top face
    CHECK(p.count == 1);

    sph::Simulation cup(sph_test::scene_file("mesh_obstacle.json", {"resolution.particles_across=8"}), sph_test::cpu_factory(), 0.01);
    // The cup (radius 0.08 m about (0.42, z = 0.1), walls 0.024 m thick): the middle of its wall, 0.012 m deep.
    const sph::Penetration q = sph::solid_penetration(cup.setup().constants, cup.setup().meshes, {},
                                                      state({{0.42f + 0.068f, 0.08f, 0.1f}}), 0.005);
    CHECK_THAT(q.deepest, WithinAbs(0.012, 0.002));  // a polygonal cylinder: within its facets' sag
    CHECK(q.count == 1);
  }
}
