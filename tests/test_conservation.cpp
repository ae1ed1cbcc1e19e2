// Pair forces are antisymmetric, so without gravity and walls the total momentum of the fluid is
// conserved to round-off: sum_a m_a a_a = 0 for one evaluation, and sum_a m_a v_a stays at its initial
// value over many steps.
#include <cmath>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "common/guided_creation.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

std::string cloud_scene(const std::string& pressure_force, const std::string& viscosity) {
  return R"({
    "name": "momentum",
    "fluids": [ { "rest_density": 1000, "speed_of_sound": 10, "viscosity": 0.05,
                  "artificial_viscosity": 0.1, "near_stiffness": 1.0, "surface_tension": 0.5, "xsph": 0.1 } ],
    "emitters": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.05 } ],
    "resolution": { "spacing": 0.01 },
    "sph": { "pressure_force": ")" + pressure_force + R"(", "viscosity": ")" + viscosity + R"(" },
    "time_step": { "mode": "fixed", "dt": 2e-4 },
    "gravity": [0, 0, 0]
  })";
}

// Jitters positions and gives random velocities so that every pair term is exercised unevenly.
sph::ParticleState disorder(sph::ParticleState ps, double spacing) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const float j = float(0.3 * spacing);
    ps.pos[i] += sph::Vec3{j * u(rng), j * u(rng), j * u(rng)};
    ps.vel[i] = sph::Vec3{0.5f * u(rng), 0.5f * u(rng), 0.5f * u(rng)};
  }
  return ps;
}

struct Totals {
  double momentum[3] = {0, 0, 0};
  double scale = 0.0;  // sum of |m q| over particles, the size against which round-off is judged
};

template <class Field>
Totals total(const sph::ParticleState& ps, const sph::SimConstants& c, Field field) {
  Totals t;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double m = c.fluids[ps.fluid[i]].mass;
    const sph::Vec3 q = field(ps, i);
    t.momentum[0] += m * q.x;
    t.momentum[1] += m * q.y;
    t.momentum[2] += m * q.z;
    t.scale += m * sph::length(q);
  }
  return t;
}

// From a disordered, randomly moving start of the setup's particles: the forces of one evaluation sum to zero
// up to float round-off of the pair sums, and over 200 steps of dt the momentum stays where it started (XSPH
// and every pair term are antisymmetric too).
void check_momentum_conserved(const sph::Setup& setup, float dt) {
  sph::CpuBackend cpu(setup.constants);
  cpu.upload(disorder(setup.particles, setup.spacing));
  cpu.initialise_forces();
  auto acc = [](const sph::ParticleState& ps, std::size_t i) { return ps.acc[i]; };
  auto vel = [](const sph::ParticleState& ps, std::size_t i) { return ps.vel[i]; };
  const Totals f = total(cpu.download(), setup.constants, acc);
  for (double component : f.momentum) CHECK(std::fabs(component) < 1e-5 * f.scale);
  const Totals p0 = total(cpu.download(), setup.constants, vel);
  for (int step = 0; step < 200; ++step) cpu.step(dt);
  const Totals p1 = total(cpu.download(), setup.constants, vel);
  for (int k = 0; k < 3; ++k) CHECK(std::fabs(p1.momentum[k] - p0.momentum[k]) < 1e-4 * p0.scale);
}

}  // namespace

TEST_CASE("symmetric pair forces conserve linear momentum", "[conservation]") {
  const auto [pressure_force, viscosity] = GENERATE(table<std::string, std::string>({{"monaghan", "mueller"},
                                                                                     {"monaghan", "artificial"},
                                                                                     {"mueller", "morris"},
                                                                                     {"mueller", "none"}}));
  const sph::Scene scene = sph::parse_scene(cloud_scene(pressure_force, viscosity), "momentum");
  const sph::Setup setup = sph::create_setup(scene, 1.0);
  INFO("pressure force " << pressure_force << ", viscosity " << viscosity << ", " << setup.particles.size() << " particles");
  check_momentum_conserved(setup, 2e-4f);
}

TEST_CASE("number-density pair forces conserve momentum between fluids of density ratio 10", "[conservation][multiphase]") {
  const std::string pressure_force = GENERATE(std::string("monaghan"), std::string("mueller"));
  // Two touching halves of a cloud, water and a fluid ten times lighter (equal Tait B), every pair term on.
  const std::string text = R"({
    "name": "momentum_two_fluids",
    "fluids": [ { "name": "heavy", "rest_density": 1000, "speed_of_sound": 10, "viscosity": 0.05, "artificial_viscosity": 0.1,
                  "near_stiffness": 1.0, "surface_tension": 0.5, "xsph": 0.1 },
                { "name": "light", "rest_density": 100, "speed_of_sound": 31.6, "viscosity": 0.01, "artificial_viscosity": 0.1,
                  "near_stiffness": 1.0, "surface_tension": 0.05, "xsph": 0.1 } ],
    "emitters": [ { "type": "box", "fluid": "heavy", "min": [-0.05, -0.05, -0.05], "max": [0, 0.05, 0.05] },
                  { "type": "box", "fluid": "light", "min": [0, -0.05, -0.05], "max": [0.05, 0.05, 0.05] } ],
    "resolution": { "spacing": 0.01 },
    "sph": { "pressure_force": ")" + pressure_force + R"(", "viscosity": "morris", "multiphase": "number_density" },
    "time_step": { "mode": "fixed", "dt": 1e-4 },
    "gravity": [0, 0, 0]
  })";
  const sph::Scene scene = sph::parse_scene(text, "momentum_two_fluids");
  const sph::Setup setup = sph::create_setup(scene, 1.0);
  REQUIRE(setup.constants.number_density == 1);
  check_momentum_conserved(setup, 1e-4f);
}
