// Interface tension between two fluids (issue 15, "interface tension between fluids as an option"), the scene
// key interface_tension. Under the cohesion model it sets sigma_ab by a cohesion between the two fluids'
// particles, calibrated in the same mean-field picture as a fluid's own (src/common/calibration.h,
// cross_cohesion). Tested: the calibration's limits, the key's validation, the energy budget, and that a cube
// of one fluid inside another pulls into a ball of its volume with an interface tension and stays a cube
// without one; the pressure jump across that interface drifts (docs/results.md), and is not claimed. Under
// the continuum surface force (surface_tension_csf.h, csf_interface_share) the jump holds Laplace's law:
// tested below under DFSPH, with its limits (two fluids, no contact angle).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/guided_creation.h"
#include "common/surface_tension_csf.h"
#include "physics_helpers.h"

using namespace sph_test;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A 0.04 m cube of fluid "inner" in the middle of a closed 0.08 m box filled with fluid "outer", no gravity;
// neither fluid has a surface tension of its own. `interface` is the scene's interface_tension member.
std::string cube_in_fluid(const std::string& interface, double spacing = 0.005) {
  return R"({ "name": "cube_in_fluid",
    "fluids": [
      { "name": "outer", "rest_density": 1000, "speed_of_sound": 20, "viscosity": 0.5, "artificial_viscosity": 0.05 },
      { "name": "inner", "rest_density": 1000, "speed_of_sound": 20, "viscosity": 0.5, "artificial_viscosity": 0.05 } ],)" +
         interface + R"(
    "emitters": [
      { "type": "box", "fluid": "inner", "min": [0.02, 0.02, 0.02], "max": [0.06, 0.06, 0.06] },
      { "type": "box", "fluid": "outer", "min": [0, 0, 0], "max": [0.08, 0.08, 0.08] } ],
    "boundaries": [ { "type": "box", "min": [0, 0, 0], "max": [0.08, 0.08, 0.08] } ],
    "resolution": { "spacing": )" +
         std::to_string(spacing) + R"(, "neighbours": 32 },
    "time_step": { "mode": "adaptive", "dt": 1e-4, "max": 2e-3 },
    "gravity": [0, 0, 0] })";
}

sph::Scene parse(const std::string& text, const std::vector<std::string>& sets = {}) {
  return sph::parse_scene(text, "cube_in_fluid.json", sets);
}

const std::string kTension = R"( "interface_tension": [ { "fluids": ["outer", "inner"], "sigma": 4.7 } ],)";

struct Inner {
  double radius = 0.0;      // sqrt(5/3 <|x - x_c|^2>) of the inner fluid [m]
  double outermost = 0.0;   // its farthest particle from its centre [m]
  double equivalent = 0.0;  // the radius of the ball of its volume [m]
  double centre[3] = {0, 0, 0};  // its centre of mass [m]
};

Inner measure_inner(const sph::ParticleState& ps, double d) {
  double c[3] = {0, 0, 0};
  long n = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.fluid[i] == 1) c[0] += ps.pos[i].x, c[1] += ps.pos[i].y, c[2] += ps.pos[i].z, ++n;
  REQUIRE(n > 0);
  for (double& v : c) v /= double(n);
  Inner out;
  for (int k = 0; k < 3; ++k) out.centre[k] = c[k];
  double r2 = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.fluid[i] != 1) continue;
    const double dx = ps.pos[i].x - c[0], dy = ps.pos[i].y - c[1], dz = ps.pos[i].z - c[2];
    r2 += (dx * dx + dy * dy + dz * dz) / double(n);
    out.outermost = std::max(out.outermost, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  out.radius = std::sqrt(5.0 / 3.0 * r2);
  out.equivalent = std::cbrt(3.0 * double(n) * d * d * d / (4.0 * kPi));
  return out;
}

}  // namespace

TEST_CASE("interface tension: the cohesion between two fluids from Dupre's relation", "[surface_tension][interface]") {
  const double h = 0.01, rho = 1000.0;
  // sigma_ab = sigma_a + sigma_b: the fluids ignore each other (the default for pairs not listed).
  CHECK(sph::cross_cohesion(4.7, 0.03, 4.73, rho, 500.0, h) == Approx(0.0).margin(1e-9));
  // Two fluids of one kind with no interface between them (sigma_ab = 0) bind as the fluid binds itself.
  CHECK(sph::cross_cohesion(4.7, 4.7, 0.0, rho, rho, h) == Approx(sph::cohesion_from_surface_tension(4.7, rho, h)).epsilon(1e-12));
  // Below sigma_a + sigma_b they attract, above it they repel; linear in sigma_ab.
  CHECK(sph::cross_cohesion(4.7, 4.7, 1.0, rho, rho, h) > 0.0);
  CHECK(sph::cross_cohesion(0.0, 0.0, 4.7, rho, rho, h) == Approx(-0.5 * sph::cohesion_from_surface_tension(4.7, rho, h)).epsilon(1e-12));
  // The work of parting them goes as rho_a rho_b.
  CHECK(sph::cross_cohesion(1.0, 1.0, 0.5, rho, 100.0, h) == Approx(10.0 * sph::cross_cohesion(1.0, 1.0, 0.5, rho, rho, h)).epsilon(1e-12));
}

TEST_CASE("interface tension: the scene key is read by fluid name or index and checked", "[surface_tension][interface][scene]") {
  const sph::Scene by_name = parse(cube_in_fluid(kTension));
  REQUIRE(by_name.interface_tensions.size() == 1);
  CHECK(by_name.interface_tensions[0].a == 0);
  CHECK(by_name.interface_tensions[0].b == 1);
  CHECK(by_name.interface_tensions[0].sigma == 4.7);
  const sph::Scene by_index = parse(cube_in_fluid(R"( "interface_tension": [ { "fluids": [1, 0], "sigma": 0.03 } ],)"));
  CHECK(by_index.interface_tensions[0].a == 1);
  const sph::Setup setup = sph::create_setup(by_name, 1.0);
  CHECK(setup.constants.interface_cohesion_enabled == 1);
  CHECK(setup.constants.cross_cohesion[0][1] < 0.0f);  // neither fluid has a sigma: they repel
  CHECK(setup.constants.cross_cohesion[1][0] == setup.constants.cross_cohesion[0][1]);
  CHECK(setup.constants.cross_cohesion[0][0] == 0.0f);

  const auto fails = [](const std::string& member) { return parse(cube_in_fluid(member)); };
  CHECK_THROWS_WITH(fails(R"( "interface_tension": [ { "fluids": ["outer", "oil"], "sigma": 1 } ],)"),
                    Contains("interface_tension.0.fluids.1") && Contains("no fluid named \"oil\""));
  CHECK_THROWS_WITH(fails(R"( "interface_tension": [ { "fluids": ["outer", "outer"], "sigma": 1 } ],)"),
                    Contains("interface_tension.0.fluids") && Contains("two different fluids"));
  CHECK_THROWS_WITH(fails(R"( "interface_tension": [ { "fluids": [0, 1], "sigma": 1 }, { "fluids": [1, 0], "sigma": 2 } ],)"),
                    Contains("interface_tension.1.fluids") && Contains("twice"));
  CHECK_THROWS_WITH(fails(R"( "interface_tension": [ { "fluids": [0, 1] } ],)"), Contains("interface_tension.0.sigma"));
  CHECK_THROWS_WITH(fails(R"( "interface_tension": [ { "fluids": [0, 1], "sigma": -1 } ],)"), Contains("interface_tension.0.sigma"));
  CHECK_THROWS_WITH(fails(R"( "interface_tension": [ { "fluids": [0, 1, 1], "sigma": 1 } ],)"),
                    Contains("interface_tension.0.fluids") && Contains("two fluids"));
  CHECK_THROWS_WITH(fails(R"( "interface_tension": [ { "fluids": [0, 1], "sigma": 1, "tension": 2 } ],)"),
                    Contains("interface_tension.0") && Contains("tension"));
  CHECK_THROWS_WITH(fails(R"( "interface_tension": { "fluids": [0, 1], "sigma": 1 },)"), Contains("interface_tension"));
  // Too strong for the fluids' equations of state: refused with the least speed of sound (unchecked, 100 N/m
  // blew up at 7 ms).
  CHECK_THROWS_WITH(sph::create_setup(parse(cube_in_fluid(kTension), {"interface_tension.0.sigma=100"}), 1.0),
                    Contains("interface_tension.0.sigma") && Contains("speed_of_sound of at least"));
  CHECK_THROWS_WITH(sph::create_setup(parse(cube_in_fluid(kTension), {"solver=pbf"}), 1.0),
                    Contains("interface_tension") && Contains("pbf"));
}

TEST_CASE("interface tension pulls a cube of one fluid inside another into a ball, and without it the cube stays",
          "[surface_tension][interface]") {
  const double d = 0.005, sigma = 4.7, side = 0.04;
  sph::Simulation with(parse(cube_in_fluid(kTension)), cpu_factory(), 0.4);
  sph::Simulation without(parse(cube_in_fluid("")), cpu_factory(), 0.4);
  // The budget counts the interface's energy: at most sigma_ab A of the cube, and most of it (the lattice binds
  // the cohesion at 0.75 of the continuum's, cohesion_energy.h).
  INFO("energy budget " << with.energy_budget() << " J with the interface tension, " << without.energy_budget()
                        << " J without; sigma A = " << sigma * 6.0 * side * side << " J");
  CHECK(with.energy_budget() - without.energy_budget() < sigma * 6.0 * side * side);
  CHECK(with.energy_budget() - without.energy_budget() > 0.5 * sigma * 6.0 * side * side);
  while (with.time() < 0.4) with.advance();
  while (without.time() < 0.4) without.advance();
  const Inner ball = measure_inner(with.particles(), d), cube = measure_inner(without.particles(), d);
  INFO("with sigma_ab = 4.7 N/m: radius " << ball.radius << " m, outermost " << ball.outermost << " m; without: "
       << cube.radius << " m, " << cube.outermost << " m; the ball of the volume " << ball.equivalent << " m");
  CHECK(std::fabs(ball.radius - ball.equivalent) < 0.05 * ball.equivalent);
  CHECK(ball.outermost < ball.equivalent + 0.25 * d);  // the centres half a spacing inside the surface
  // A cube's corners lie at 1.40 times the ball's radius (centres: 0.0303 m here).
  CHECK(cube.outermost > 1.2 * cube.equivalent);
}

TEST_CASE("interface tension under the continuum surface force: set-up and its limits", "[surface_tension][interface][csf]") {
  const sph::Setup setup = sph::create_setup(parse(cube_in_fluid(kTension), {"sph.surface_tension=csf"}), 1.0);
  const sph::SimConstants& c = setup.constants;
  CHECK(c.csf_enabled == 1);
  CHECK(c.csf_interface_enabled == 1);
  CHECK(c.interface_cohesion_enabled == 0);  // the tension acts through the colours, not a cohesion
  CHECK(c.cross_cohesion[0][1] < 0.0f);      // kept for the energy budget: parting them costs sigma_ab
  const double chi = sph::csf_band_integral(setup.spacing, setup.h, setup.lattice_density);
  CHECK(c.fluids[0].csf_interface_sigma == Approx(4.7 / chi).epsilon(1e-6));
  CHECK(c.fluids[1].csf_interface_sigma == Approx(4.7 / chi).epsilon(1e-6));
  CHECK(c.fluids[0].csf_sigma == 0.0f);  // neither fluid has a free surface's tension of its own
  // The colour of "the other fluid" is every fluid but a particle's own: with a third fluid refused.
  const std::string three = R"({ "name": "three",
    "fluids": [ { "name": "a" }, { "name": "b" }, { "name": "c" } ],
    "interface_tension": [ { "fluids": ["a", "b"], "sigma": 1 } ],
    "emitters": [ { "type": "box", "fluid": "a", "min": [0, 0, 0], "max": [0.02, 0.02, 0.02] } ],
    "boundaries": [ { "type": "box", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1] } ],
    "resolution": { "spacing": 0.01 }, "sph": { "surface_tension": "csf" } })";
  CHECK_THROWS_WITH(sph::create_setup(parse(three), 1.0),
                    Contains("interface_tension") && Contains("two fluids") && Contains("cohesion"));
  // A contact angle's images and the interface's share are not run together.
  CHECK_THROWS_WITH(sph::create_setup(parse(cube_in_fluid(kTension), {"sph.surface_tension=csf", "sph.walls=mirror",
                                                                       "fluids.0.surface_tension=1",
                                                                       "fluids.0.contact_angle=90"}),
                                      1.0),
                    Contains("interface_tension") && Contains("fluids.0.contact_angle"));
}

TEST_CASE("interface tension under the continuum surface force: refused where both fluids meet the gas",
          "[surface_tension][interface][csf]") {
  // Two 4.8 cm cubes side by side without gravity, sigma 4.7 N/m each and between them: the two drops should
  // hold together at Neumann's angles (120 degrees each); under this force they flew apart (their centres
  // from 0.068 to 0.155 m apart in 1 s, docs/results.md), so set-up refuses them.
  const std::string doublet = R"({ "name": "doublet",
    "fluids": [ { "name": "a", "surface_tension": 4.7 }, { "name": "b", "surface_tension": 4.7 } ],
    "interface_tension": [ { "fluids": ["a", "b"], "sigma": 4.7 } ],
    "emitters": [ { "type": "box", "fluid": "a", "min": [-0.048, -0.024, -0.024], "max": [0, 0.024, 0.024] },
                  { "type": "box", "fluid": "b", "min": [0, -0.024, -0.024], "max": [0.048, 0.024, 0.024] } ],
    "resolution": { "spacing": 0.004 }, "solver": "dfsph", "sph": { "surface_tension": "csf" }, "gravity": [0, 0, 0] })";
  CHECK_THROWS_WITH(sph::create_setup(parse(doublet), 1.0),
                    Contains("interface_tension.0") && Contains("both do at the start") && Contains("cohesion"));
  // The same under the cohesion model is taken, and so are one drop inside another and two fluids filling a box.
  CHECK_NOTHROW(sph::create_setup(parse(doublet, {"sph.surface_tension=cohesion"}), 1.0));
  CHECK_NOTHROW(sph::create_setup(scene_file("compound_drop.json", {"resolution.spacing=0.008"}), 1.0));
  CHECK_NOTHROW(sph::create_setup(parse(cube_in_fluid(kTension), {"sph.surface_tension=csf"}), 1.0));
}

namespace {

// scenes/interface_drop.json under DFSPH with a 0.052 m cube (13 layers, R = 4.1 h) of a fluid without a surface
// tension of its own in a closed box of another, sigma_ab = 4.7 N/m, no gravity, the box's x extent `box_x`:
// the jump across the interface at 0.25 and 0.5 s within 15% of 2 sigma_ab / R, holding (drift below 0.03),
// and a ball with its centres inside.
void check_dfsph_interface_jump(double box_x) {
  const double sigma = 4.7, d = 0.004;
  const sph::Scene scene = scene_file("interface_drop.json", {"sph.surface_tension=csf", "solver=dfsph",
                                                              "emitters.0.min=[0.025,0.025,0.025]",
                                                              "emitters.0.max=[0.075,0.075,0.075]",
                                                              "boundaries.0.max=[" + std::to_string(box_x) + ",0.1,0.1]"});
  sph::Simulation sim(scene, cpu_factory(), 0.5);
  const double h = sim.setup().h;
  std::vector<double> ratios;
  for (const double until : {0.25, 0.5}) {
    while (sim.time() < until) sim.advance();
    const sph::ParticleState& ps = sim.particles();
    const Inner ball = measure_inner(ps, d);
    const double* c = ball.centre;
    // Inside: the inner fluid within R / 2 of its centre; outside: the outer fluid 1.5 h beyond the interface
    // and h from the walls.
    double p_in = 0.0, p_out = 0.0;
    long n_in = 0, n_out = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const double x = ps.pos[i].x, y = ps.pos[i].y, z = ps.pos[i].z;
      const double r = std::sqrt((x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]) + (z - c[2]) * (z - c[2]));
      const double wall = std::min({x, y, z, box_x - x, 0.1 - y, 0.1 - z});
      if (ps.fluid[i] == 1 && r < 0.5 * ball.equivalent) p_in += ps.pressure[i], ++n_in;
      if (ps.fluid[i] == 0 && r > ball.equivalent + 1.5 * h && wall > h) p_out += ps.pressure[i], ++n_out;
    }
    REQUIRE(n_in > 0);
    REQUIRE(n_out > 0);
    const double ratio = (p_in / double(n_in) - p_out / double(n_out)) / (2.0 * sigma / ball.equivalent);
    INFO("box " << box_x << " m along x, t = " << sim.time() << " s: inside " << p_in / double(n_in)
                << " Pa, outside " << p_out / double(n_out) << " Pa, jump / (2 sigma_ab / R) = " << ratio
                << " (R = " << ball.equivalent << " m = " << ball.equivalent / h << " h); outermost inner particle "
                << ball.outermost << " m");
    CHECK(std::fabs(ratio - 1.0) <= 0.15);
    CHECK(ball.outermost < ball.equivalent);  // a ball with its centres inside, none carried into the outer fluid
    ratios.push_back(ratio);
  }
  CHECK(std::fabs(ratios[1] - ratios[0]) < 0.03);  // it holds: the cohesion's jump drifted by 0.1 in this time
}

}  // namespace

TEST_CASE("under DFSPH the continuum surface force's interface tension holds Laplace's pressure jump",
          "[surface_tension][interface][csf][dfsph]") {
  // The box 0.8 mm longer than the fluid along x, room for 0.8% of its volume: about how far a settled,
  // disordered fluid's cubic-spline density exceeds the start lattice's, which sets the mass (the next test). Measured 2026-12-02:
  // 1.12 and 1.11 times 2 sigma_ab / R at 0.25 and 0.5 s, the outer fluid at 63 to 67 Pa; the interface
  // force on each half of the ball 1.02 to 1.04 times 2 pi sigma_ab R, the pull Laplace's jump balances. With
  // sigma_ab / 2 on each side's own colour the jump was 0.58 and falling, the inner fluid spreading into the
  // outer (the concave side's force, surface_tension_csf.h).
  check_dfsph_interface_jump(0.1008);
}

TEST_CASE("under DFSPH the interface drop in a box filled to its walls holds Laplace's pressure jump",
          "[surface_tension][interface][csf][dfsph][!shouldfail]") {
  // A known failure (docs/results.md, "DFSPH's mass from the cubic spline"). The mass is rho0 d^3 over the
  // cubic spline's sum on the start's lattice; as the fluid settles into a disordered packing the same number
  // of particles reads 0.8% above rho0, and with no room to expand the whole box takes a pressure (331 Pa
  // outside the ball at 0.25 s, 179 Pa at 0.5 s; measured 2026-12-02). The jump across the interface then
  // reads 1.07 and 1.19 times 2 sigma_ab / R, drifting with that pressure, though the interface force on
  // each half of the ball is 0.88 to 0.93 times 2 pi sigma_ab R: the pressure force's error on the
  // interface's irregular packing grows with the pressure it carries.
  check_dfsph_interface_jump(0.1);
}
