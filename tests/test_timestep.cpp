// The viscous time-step limit (viscous_limit.h): derived from the largest eigenvalue of the discrete viscous
// operator, it keeps a very viscous cube in free fall rigid (issue 10, item 6), where the old rule
// dt <= 0.125 h^2 / nu put the fastest viscous mode past the explicit stability bound.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <random>

#include "common/time_step.h"
#include "common/viscous_limit.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

// A cube of 10^3 particles (0.1 m) of a fluid of viscosity mu, falling freely: no boundary. Negative
// pressure is clamped: with it kept, the lower lattice density at the free surface pulls the surface layer
// inwards (0.07 m/s at mu = 1000 Pa s, the same for every step size), a response of the model that would
// hide what these tests look at, the stability of the viscous update.
sph::Scene viscous_cube(double mu, const std::string& model) {
  const std::string json = R"({
    "name": "viscous_free_fall",
    "fluids": [ { "name": "honey", "rest_density": 1000, "speed_of_sound": 20, "viscosity": )" +
                           std::to_string(mu) + R"( } ],
    "emitters": [ { "type": "box", "fluid": "honey", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1] } ],
    "resolution": { "particles_across": 10, "neighbours": 32 },
    "sph": { "viscosity": ")" + model + R"(", "negative_pressure": "clamp" },
    "time_step": { "mode": "adaptive", "max": 1e-3 }
  })";
  return sph::parse_scene(json, "viscous_free_fall.json");
}

// The cube of viscous_cube with Monaghan's artificial viscosity alpha instead (c0 = 20 m/s, no laminar
// viscosity).
sph::Scene artificial_cube(double alpha) {
  const std::string json = R"({
    "name": "artificial_cube",
    "fluids": [ { "name": "water", "rest_density": 1000, "speed_of_sound": 20, "viscosity": 0, "artificial_viscosity": )" +
                           std::to_string(alpha) + R"( } ],
    "emitters": [ { "type": "box", "fluid": "water", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1] } ],
    "resolution": { "particles_across": 10, "neighbours": 32 },
    "sph": { "viscosity": "artificial", "negative_pressure": "clamp" },
    "time_step": { "mode": "adaptive", "max": 1e-3 }
  })";
  return sph::parse_scene(json, "artificial_cube.json");
}

// The fastest rate [1/s] at which the velocity-dependent forces of the set-up's initial state (the force code
// of forces.h, as a step runs it) damp a velocity field: power iteration v <- (acc(0) - acc(v)) / |.|, the
// rate the norm of that, on all three velocity components. Pressure and gravity do not depend on the
// velocity, so acc(v) = acc(0) - L v where the forces are linear (laminar viscosity); Monaghan's artificial
// viscosity acts on approaching pairs only, and the iteration then finds the field it damps fastest.
double measured_fastest_rate(const sph::Scene& scene) {
  sph::Setup setup = sph::create_setup(scene, 0.1);
  sph::ParticleState state = setup.particles;
  const std::size_t n = state.size();
  auto accelerations = [&](const std::vector<sph::Vec3>& v) {  // by particle id
    for (std::size_t i = 0; i < n; ++i) state.vel[i] = v[std::size_t(state.id[i])];
    sph::CpuBackend backend(setup.constants);
    backend.upload(state);
    backend.initialise_forces();
    const sph::ParticleState& out = backend.download();
    std::vector<sph::Vec3> a(n);
    for (std::size_t i = 0; i < n; ++i) a[std::size_t(out.id[i])] = out.acc[i];
    return a;
  };
  const std::vector<sph::Vec3> a0 = accelerations(std::vector<sph::Vec3>(n, sph::Vec3{0.0f, 0.0f, 0.0f}));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<sph::Vec3> v(n);
  for (sph::Vec3& x : v) x = sph::Vec3{uniform(rng), uniform(rng), uniform(rng)};
  double rate = 0.0;
  for (int iter = 0; iter < 150; ++iter) {
    double norm = 0.0;
    for (const sph::Vec3& x : v) norm += double(sph::length2(x));
    const float scale = float(1.0 / std::sqrt(norm));  // unit speed scale: 1 m/s, well inside single precision
    for (sph::Vec3& x : v) x = scale * x;
    const std::vector<sph::Vec3> a = accelerations(v);
    double norm_lv = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      v[i] = a0[i] - a[i];
      norm_lv += double(sph::length2(v[i]));
    }
    rate = std::sqrt(norm_lv);
  }
  return rate;
}

}  // namespace

TEST_CASE("the lattice viscous rate matches the fastest mode of the discrete operator", "[timestep]") {
  for (const std::string model : {"mueller", "morris"}) {
    const sph::Scene scene = viscous_cube(1000.0, model);
    const sph::Setup setup = sph::create_setup(scene, 0.1);
    const double lattice = setup.viscous_rate;
    const double measured = measured_fastest_rate(scene);
    const double nu = 1000.0 / 1000.0;
    const double old_dt = 0.125 * setup.h * setup.h / nu;  // the former rule dt <= 0.125 h^2 / nu
    const sph::StepChoice now = sph::choose_time_step(scene.time_step, setup.h, setup.max_speed_of_sound,
                                                      setup.viscous_rate, 0.0, 0.0);
    INFO(model << ": lattice lambda_max " << lattice << " 1/s, measured on the cube " << measured << " 1/s; old dt "
               << old_dt << " s (lambda dt " << measured * old_dt << "), new dt " << now.dt << " s (lambda dt "
               << measured * now.dt << ")");
    CHECK(now.limit == sph::StepLimit::Viscosity);
    // The cube's free surfaces (lower densities) make the operator stiffer than the infinite lattice, by
    // less than the margin the default safety factor 0.5 leaves.
    CHECK(measured > lattice);
    CHECK(measured < 1.5 * lattice);
    // The old rule put the fastest mode past the stability bound lambda dt < 2; the new one stays below it.
    CHECK(measured * old_dt > sph::kViscousStabilityBound);
    CHECK(measured * now.dt < 0.75 * sph::kViscousStabilityBound);
  }
}

TEST_CASE("the viscous rate scales as nu / d^2 and vanishes without Mueller or Morris viscosity", "[timestep]") {
  const sph::Setup a = sph::create_setup(viscous_cube(10.0, "mueller"), 0.1);
  const sph::Setup b = sph::create_setup(viscous_cube(20.0, "mueller"), 0.1);
  CHECK(b.viscous_rate == Approx(2.0 * a.viscous_rate).epsilon(1e-6));
  sph::Scene fine = viscous_cube(10.0, "mueller");
  fine.particles_across = 20;  // half the spacing: four times the rate
  CHECK(sph::create_setup(fine, 0.1).viscous_rate == Approx(4.0 * a.viscous_rate).epsilon(1e-3));
  CHECK(sph::create_setup(viscous_cube(10.0, "artificial"), 0.1).viscous_rate == 0.0);
  CHECK(sph::create_setup(viscous_cube(10.0, "none"), 0.1).viscous_rate == 0.0);
}

TEST_CASE("a cube at mu = 1000 Pa s falls freely as one rigid block", "[timestep]") {
  const std::string model = GENERATE(as<std::string>{}, "mueller", "morris");
  sph::Simulation sim(viscous_cube(1000.0, model), cpu_factory(), 0.05);
  const double g = 9.81;
  for (const double t_check : {0.02, 0.04}) {
    while (sim.time() < t_check) sim.advance();
    const sph::ParticleState& ps = sim.particles();
    const double t = sim.time();
    double worst = 0.0;  // largest deviation of a particle's velocity from free fall, -g t along y
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const sph::Vec3 v = ps.vel[i];
      const double dy = v.y + g * t;
      worst = std::max(worst, std::sqrt(double(v.x) * v.x + dy * dy + double(v.z) * v.z));
    }
    INFO(model << ": t = " << t << " s after " << sim.steps() << " steps (dt " << sim.last_dt() << " s): largest deviation "
                << worst << " m/s against g t = " << g * t << " m/s");
    CHECK(worst < 0.01 * g * t);
  }
}

TEST_CASE("the incompressible solvers' step is [BK15]'s CFL step, capped, without a sound-speed limit", "[timestep]") {
  // Seed 000 eq. 3: dt = C_v d / v_max (C_v = 0.4 by default), capped at time_step.max, and the cap when
  // nothing moves; the explicit viscous limit as for WCSPH.
  sph::TimeStepSpec t;
  t.max = 0.01;
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 2.0).dt == Approx(0.002).epsilon(1e-12));
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 2.0).limit == sph::StepLimit::Velocity);
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 0.1).dt == 0.01);
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 0.0).limit == sph::StepLimit::Maximum);
  t.cfl_velocity = 0.2;
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 4.0).dt == Approx(0.0005).epsilon(1e-12));
  const double rate = 1000.0;  // 1/s: the viscous limit cfl_viscosity 2 / rate = 1 ms decides
  CHECK(sph::choose_incompressible_step(t, 0.01, rate, 0.1).dt == Approx(t.cfl_viscosity * 2.0 / rate));
  CHECK(sph::choose_incompressible_step(t, 0.01, rate, 0.1).limit == sph::StepLimit::Viscosity);
  // DFSPH's acceleration limit C_a sqrt(h / a_max) (the non-pressure forces): 600 m/s^2 at h = 0.0079 m gives
  // 0.25 * 3.63 ms; without a_max (PBF, or none given) it is not applied.
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 0.1, 0.0079, 600.0).dt ==
        Approx(t.cfl_acceleration * std::sqrt(0.0079 / 600.0)).epsilon(1e-12));
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 0.1, 0.0079, 600.0).limit == sph::StepLimit::Acceleration);
  CHECK(sph::choose_incompressible_step(t, 0.01, 0.0, 0.1, 0.0079, 1.0).limit == sph::StepLimit::Maximum);
  t.mode = sph::TimeStepMode::Fixed;
  t.dt = 0.004;
  CHECK(sph::choose_incompressible_step(t, 0.01, rate, 100.0).dt == 0.004);
}


TEST_CASE("the artificial viscosity's lattice rate bounds the fastest mode of its operator", "[timestep]") {
  // artificial_viscous_rate takes every pair as approaching (a linear operator, the largest eigenvalue of
  // its 3 x 3 symbol); the real term damps approaching pairs only. The bound must hold, and not by a margin
  // so wide that DFSPH sub-cycles needlessly. Measured on the cube: 0.73 of the bound (2026-11-30).
  const sph::Scene scene = artificial_cube(0.2);
  const sph::Setup setup = sph::create_setup(scene, 0.1);
  const double bound = double(setup.constants.artificial_rate);
  const double measured = measured_fastest_rate(scene);
  INFO("lattice bound " << bound << " 1/s, measured on the cube " << measured << " 1/s");
  CHECK(measured <= bound);
  CHECK(measured >= 0.5 * bound);
  // It scales as alpha c0 / d: twice alpha, twice the rate; half the spacing, twice the rate.
  CHECK(sph::create_setup(artificial_cube(0.4), 0.1).constants.artificial_rate == Approx(2.0 * bound).epsilon(1e-5));
  sph::Scene fine = artificial_cube(0.2);
  fine.particles_across = 20;
  CHECK(sph::create_setup(fine, 0.1).constants.artificial_rate == Approx(2.0 * bound).epsilon(1e-3));
  CHECK(sph::create_setup(artificial_cube(0.0), 0.1).constants.artificial_rate == 0.0f);
  // WCSPH's sound-speed step stays below the bound: 0.4 h / c0 against 2 / lambda_max.
  CHECK(scene.time_step.cfl_sound * setup.h / setup.max_speed_of_sound < sph::kViscousStabilityBound / bound);
}

TEST_CASE("DFSPH's sub-steps keep every explicit viscous update within the stability bound", "[timestep]") {
  // n = ceil(rate dt / 2), at least 1: rate dt / n <= 2, and n - 1 sub-steps would exceed it.
  for (const double rate : {0.0, 100.0, 1589.9, 1e5}) {
    for (const double dt : {1e-4, 1e-3, 2.63e-3, 0.01}) {
      const int32_t n = sph::viscous_substeps(rate, dt);
      INFO("rate " << rate << " 1/s, dt " << dt << " s: " << n << " sub-steps");
      REQUIRE(n >= 1);
      CHECK(rate * dt / n <= sph::kViscousStabilityBound * (1.0 + 1e-12));
      if (n > 1) CHECK(rate * dt / (n - 1) > sph::kViscousStabilityBound);
    }
  }
}
