// Rigid bodies with two-way coupling (issue 13): Archimedes (a box of density 500 floats half submerged, one
// of 2000 sinks to the floor; under WCSPH and DFSPH), and the momentum the fluid and a free body exchange.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "physics_helpers.h"

using namespace sph_test;

TEST_CASE("rigid bodies: a box of density 500 floats half submerged, one of 2000 sinks to the floor", "[bodies]") {
  // scenes/floating_box.json at a coarser spacing (4.8 particles across the box's 0.06 m). The still-water
  // level comes from the fluid's volume: 0.15 m plus what the submerged part displaces over the free surface
  // (0.4 x 0.2 m less the box's 0.08 x 0.08 m), the surface a particle layer cannot resolve better than
  // half a spacing.
  const double height = 0.06, footprint = 0.08 * 0.08, surface = 0.4 * 0.2 - footprint;
  for (const double density : {500.0, 2000.0}) {
    const sph::Scene scene =
        scene_file("floating_box.json", {"bodies.0.density=" + std::to_string(density), "resolution.spacing=0.0125"});
    sph::Simulation sim(scene, cpu_factory(), 1.5);
    const double mean_centre = mean_body_height(sim, 1.0, 1.5);  // the last half second, past the first bobbing
    const sph::RigidBody& b = sim.backend().bodies().at(0);
    const double bottom = mean_centre - 0.5 * height;
    INFO("density " << density << ": box centre y " << mean_centre << " m (mean over 1 to 1.5 s), bottom " << bottom
                    << " m, contact with the walls " << b.contact << ", tilt w " << b.orientation[0]);
    if (density < 1000.0) {
      // Archimedes: depth d_s with rho_w d_s = rho_b H; the level rises by footprint d_s / surface.
      const double expected = density / 1000.0 * height;
      const double level = 0.15 + footprint * expected / surface;
      const double submerged = (level - bottom) / height;
      INFO("still-water level " << level << " m: submerged " << submerged << " of the height (Archimedes: " << density / 1000.0 << ")");
      CHECK(std::fabs(submerged - density / 1000.0) <= 0.05);  // within 5% of its height
      CHECK_FALSE(b.contact);
    } else {
      CHECK(b.contact);  // resting on the floor
      CHECK(std::fabs(bottom) <= 0.5 * sim.setup().spacing);
    }
  }
}

TEST_CASE("rigid bodies: under DFSPH a box of density 500 floats half submerged", "[bodies][dfsph]") {
  // As above under DFSPH. Where boundary particles pushed with kappa_i alone the box floated at 0.57 of its
  // height, and mirrored without the wall's hydrostatic pressure at 0.44 (src/common/dfsph.h).
  const double height = 0.06, footprint = 0.08 * 0.08, surface = 0.4 * 0.2 - footprint;
  const sph::Scene scene = scene_file("floating_box.json", {"solver=dfsph", "resolution.spacing=0.0125"});
  sph::Simulation sim(scene, cpu_factory(), 1.5);
  const double mean_centre = mean_body_height(sim, 1.0, 1.5);
  const double level = 0.15 + footprint * 0.5 * height / surface;
  const double submerged = (level - (mean_centre - 0.5 * height)) / height;
  INFO("box centre y " << mean_centre << " m (mean over 1 to 1.5 s), still-water level " << level << " m: submerged "
                       << submerged << " of the height (Archimedes: 0.5)");
  CHECK(std::fabs(submerged - 0.5) <= 0.05);
  CHECK_FALSE(sim.backend().bodies().at(0).contact);
}

TEST_CASE("rigid bodies: a free body and the fluid exchange momentum and conserve its sum", "[bodies]") {
  // A block of fluid at 0.5 m/s hits a free box at rest, no gravity, no walls; semi-implicit Euler for the
  // fluid, as the body's step, so that each step's exchange is exactly the reaction. Under DFSPH the body
  // gets the reaction to the total each solve applied, which equals the sum of its iterations up to
  // round-off.
  // With a surface tension and a contact angle, the adhesion to the body's particles (forces.h, boundary_pair)
  // must come back to the body as well (issue 15).
  const std::string solver = GENERATE(std::string("wcsph"), std::string("dfsph"), std::string("wcsph with adhesion"));
  INFO("solver " << solver);
  const bool adhesion = solver == "wcsph with adhesion";
  std::vector<std::string> sets = {"sph.walls=particles", "gravity=[0,0,0]", "integrator=semi_implicit_euler",
                                   "emitters.0.velocity=[0.5,0,0]", "resolution.particles_across=8",
                                   "solver=" + (adhesion ? std::string("wcsph") : solver)};
  if (adhesion) sets.insert(sets.end(), {"fluids.0.surface_tension=1", "fluids.0.contact_angle=30"});
  sph::Scene scene = scene_file("hydrostatic_tank.json", sets);
  scene.boundaries.clear();
  sph::BodySpec box;
  box.min = {0.06, 0.03, 0.01};
  box.max = {0.09, 0.07, 0.04};
  box.density = 800.0;
  scene.bodies.push_back(box);
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  const auto momentum = [&](double body[3], double& scale) {
    const sph::ParticleState& ps = sim.particles();
    const sph::SimConstants& c = sim.setup().constants;
    const sph::RigidBody& b = sim.backend().bodies().at(0);
    double total[3] = {0.0, 0.0, 0.0};
    scale = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const double m = c.fluids[ps.fluid[i]].mass;
      total[0] += m * ps.vel[i].x, total[1] += m * ps.vel[i].y, total[2] += m * ps.vel[i].z;
      scale += m * std::sqrt(double(sph::length2(ps.vel[i])));
    }
    for (int k = 0; k < 3; ++k) {
      body[k] = b.mass * b.velocity[std::size_t(k)];
      total[k] += body[k];
    }
    return std::vector<double>{total[0], total[1], total[2]};
  };
  double body0[3], body1[3], scale0 = 0.0, scale1 = 0.0;
  const std::vector<double> before = momentum(body0, scale0);
  while (sim.time() < 0.06) sim.advance();
  const std::vector<double> after = momentum(body1, scale1);
  const double gained = body1[0] - body0[0];
  const double drift = std::sqrt((after[0] - before[0]) * (after[0] - before[0]) + (after[1] - before[1]) * (after[1] - before[1]) +
                                 (after[2] - before[2]) * (after[2] - before[2]));
  INFO(sim.steps() << " steps: the body gained " << gained << " kg m/s along x (fluid's momentum " << before[0]
                   << "); total momentum changed by " << drift << " kg m/s");
  REQUIRE(gained > 0.05 * before[0]);  // the fluid did push the body
  CHECK(drift <= 1e-4 * gained + 1e-6 * scale0);
}

TEST_CASE("rigid bodies: a prescribed paddle follows its oscillation and does work on the water", "[bodies]") {
  // scenes/wave_maker.json, coarse: the paddle's centre is start + A sin(2 pi t / T) at every step, whatever
  // the fluid does, and over its first strokes it pushes the water (the fluid's force against its velocity:
  // positive work done on the fluid).
  const sph::Scene scene = scene_file("wave_maker.json", {"resolution.spacing=0.02"});
  sph::Simulation sim(scene, cpu_factory(), 0.4);
  const double a = 0.02, period = 0.8, start = 0.05, pi = 3.14159265358979323846;
  double work = 0.0, worst = 0.0;
  while (sim.time() < 0.4) {
    sim.advance();
    const sph::RigidBody& b = sim.backend().bodies().at(0);
    worst = std::max(worst, std::fabs(b.centre[0] - (start + a * std::sin(2.0 * pi * b.time / period))));
    work -= (b.force[0] * b.velocity[0] + b.force[1] * b.velocity[1] + b.force[2] * b.velocity[2]) * sim.last_dt();
    REQUIRE(std::fabs(b.time - sim.time()) <= 1e-9);
  }
  INFO("largest deviation from the prescribed centre " << worst << " m; work done on the water " << work << " J");
  CHECK(worst <= 1e-12);
  CHECK(work > 0.0);
}

TEST_CASE("rigid bodies: a prescribed flap turns about its hinge as asked and does work on the water", "[bodies]") {
  // scenes/wave_maker.json with the paddle hinged instead: raised 2 cm off the floor, turning by
  // 5 sin(2 pi t / 0.8 s) degrees about the z axis through (0.05, 0.02, 0.05). Its orientation is that turn and
  // its centre the turned arm from the hinge at every step; its velocity is the rate of its centre. Over a whole period
  // it does work on the water (the waves it makes).
  const sph::Scene scene = scene_file(
      "wave_maker.json", {"resolution.spacing=0.02", "bodies.0.min=[0.03,0.02,0.0]",
                          R"(bodies.0.oscillation={"angle": 5, "axis": [0, 0, 1], "pivot": [0.05, 0.02, 0.05], "period": 0.8})"});
  sph::Simulation sim(scene, cpu_factory(), 0.8);
  const double pi = 3.14159265358979323846, amplitude = 5.0 * pi / 180.0, period = 0.8;
  double work = 0.0, worst_angle = 0.0, worst_arm = 0.0, worst_rate = 0.0;
  std::array<double, 3> last = sim.backend().bodies().at(0).centre;
  while (sim.time() < 0.8) {  // a whole period: the hydrostatic push returns what it took
    sim.advance();
    const sph::RigidBody& b = sim.backend().bodies().at(0);
    const double theta = amplitude * std::sin(2.0 * pi * b.time / period);
    // Orientation: a turn about z by theta, quaternion (cos theta/2, 0, 0, sin theta/2).
    worst_angle = std::max(worst_angle, std::fabs(2.0 * std::atan2(b.orientation[3], b.orientation[0]) - theta));
    // Centre: the arm from the hinge to the start centre (0, 0.14, 0) turned by theta.
    const double ax = -0.14 * std::sin(theta), ay = 0.14 * std::cos(theta);
    worst_arm = std::max(worst_arm, std::hypot(b.centre[0] - (0.05 + ax), b.centre[1] - (0.02 + ay)));
    // The mean velocity over the step against the centre's change (second order in dt).
    const double mid_rate = (b.centre[0] - last[0]) / sim.last_dt();
    worst_rate = std::max(worst_rate, std::fabs(mid_rate - b.velocity[0]) / (amplitude * 0.14 * 2.0 * pi / period));
    last = b.centre;
    work -= (b.force[0] * b.velocity[0] + b.force[1] * b.velocity[1] + b.force[2] * b.velocity[2] +
             b.torque[0] * b.omega[0] + b.torque[1] * b.omega[1] + b.torque[2] * b.omega[2]) * sim.last_dt();
  }
  INFO("angle error " << worst_angle << " rad, centre error " << worst_arm << " m, velocity against the centre's rate "
                      << worst_rate << " of the peak speed; work done on the water " << work << " J");
  CHECK(worst_angle <= 1e-12);
  CHECK(worst_arm <= 1e-12);
  CHECK(worst_rate <= 0.01);
  CHECK(work > 0.0);
}
