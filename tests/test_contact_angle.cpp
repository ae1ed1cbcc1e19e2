// The contact angle under the continuum surface force (issue 15: a fluid-wall term with sigma in N/m; the
// wall condition of Brackbill, Kothe & Zemach 1992 through images of the fluid sheared along the walls,
// src/common/surface_tension_csf.h). scenes/contact_angle.json: three equal cubes without gravity on the
// floor, at 60, 90 and 120 degrees, each relaxing to a spherical cap. What is tested: the cap's angle against
// the asked one, that the drops stay whole, and the angles the condition is refused at (below 60 degrees a
// spreading film sheds particles, measured; docs/results.md, "Contact angle").
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "physics_helpers.h"

using namespace sph_test;
using Catch::Matchers::Contains;

namespace {

struct Cap {
  long body = 0;       // particles with at least 6 of their fluid within 2 d: the drop, without what it shed
  long total = 0;
  double angle = 0.0;  // [degrees] of the spherical cap of the body's volume and height
};

// Fluid f's drop on the floor y = 0: the cap of volume N d^3 (the cube's, N its particles in the body) and
// height top + d / 2.
Cap measure_cap(const sph::ParticleState& ps, int f, double d) {
  std::vector<sph::Vec3> x;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.fluid[i] == f) x.push_back(ps.pos[i]);
  Cap cap;
  cap.total = long(x.size());
  double top = 0.0;
  for (const sph::Vec3& a : x) {
    int near = 0;
    for (const sph::Vec3& b : x) near += double(sph::length2(a - b)) < 4.0 * d * d ? 1 : 0;
    if (near < 7) continue;  // itself and 6 others
    ++cap.body;
    top = std::max(top, double(a.y));
  }
  cap.angle = spherical_cap_angle(double(cap.body) * d * d * d, top + 0.5 * d);
  return cap;
}

}  // namespace

TEST_CASE("drops relax to the contact angles asked under the continuum surface force", "[surface_tension][contact_angle]") {
  const sph::Scene scene = scene_file("contact_angle.json");
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  const double d = sim.setup().spacing;
  const double asked[3] = {60.0, 90.0, 120.0};
  // The mean over 0.5 to 1 s: the caps still ring by a few degrees (measured means 56.4, 86.7 and 123.5).
  double mean[3] = {0.0, 0.0, 0.0};
  long fewest_in_body[3] = {1 << 30, 1 << 30, 1 << 30};
  int samples = 0;
  for (double t = 0.5; t <= 1.0 + 1e-9; t += 0.1) {
    while (sim.time() < t - 1e-9) sim.advance();
    ++samples;
    for (int f = 0; f < 3; ++f) {
      const Cap cap = measure_cap(sim.particles(), f, d);
      mean[f] += cap.angle;
      fewest_in_body[f] = std::min(fewest_in_body[f], cap.body);
      REQUIRE(cap.total == 1000);
    }
  }
  for (int f = 0; f < 3; ++f) {
    mean[f] /= samples;
    INFO("asked " << asked[f] << " degrees: cap angle " << mean[f] << " (mean of " << samples << " frames), "
                  << fewest_in_body[f] << " of 1000 particles in the drop");
    // A model blind to the angle would leave all three alike (the cube reads 122 degrees; a plain mirror
    // wall gives 90): 8 degrees tells 60, 90 and 120 apart.
    CHECK(std::fabs(mean[f] - asked[f]) < 8.0);
    // Measured: 60 degrees shed 28 particles as it spread (2.8%), 90 and 120 none; since the curvature's limit
    // (surface_tension_csf.h, csf_limited_curvature, 2026-12-01) none of the three sheds one.
    CHECK(fewest_in_body[f] >= 980);
  }
  CHECK(mean[0] < mean[1]);
  CHECK(mean[1] < mean[2]);
}

TEST_CASE("a contact angle under the continuum surface force is refused where it was not measured to hold",
          "[surface_tension][contact_angle][scene]") {
  const auto setup = [](const std::vector<std::string>& sets) { return sph::create_setup(scene_file("contact_angle.json", sets), 1.0); };
  CHECK_NOTHROW(setup({"resolution.particles_across=5"}));
  CHECK_NOTHROW(setup({"resolution.particles_across=5", "sph.walls=particles"}));
  CHECK_THROWS_WITH(setup({"resolution.particles_across=5", "fluids.0.contact_angle=45"}),
                    Contains("fluids.0.contact_angle") && Contains("[60, 120]") && Contains("cohesion"));
  CHECK_THROWS_WITH(setup({"resolution.particles_across=5", "fluids.2.contact_angle=135"}),
                    Contains("fluids.2.contact_angle") && Contains("[60, 120]"));
  // Penalty walls pack particles closer to the wall than the images assume: drops flew apart (measured).
  CHECK_THROWS_WITH(setup({"resolution.particles_across=5", "sph.walls=penalty"}),
                    Contains("fluids.0.contact_angle") && Contains("mirror") && Contains("penalty"));
  // An angle just outside the range is printed as given, not rounded into it.
  CHECK_THROWS_WITH(setup({"resolution.particles_across=5", "fluids.1.contact_angle=120.0001"}), Contains("120.0001"));
  // Without a wall the condition has nothing to act at (an absorbing plane is no wall).
  CHECK_THROWS_WITH(setup({"resolution.particles_across=5", "boundaries=[]"}), Contains("fluids.0.contact_angle") && Contains("walls"));
  CHECK_THROWS_WITH(setup({"resolution.particles_across=5", "solver=pbf"}), Contains("fluids.0.contact_angle") && Contains("pbf"));
}
