// Surface tension in N/m (issue 15): cohesion between the particles of one fluid with Akinci et al.'s
// kernel, calibrated from sigma by the mean-field surface energy (src/common/calibration.h). A 0.1 m cube
// of water without gravity (scenes/drop_oscillation.json) pulls itself into a sphere of its own volume at two
// resolutions without gaining more kinetic energy than the surface energy it releases; the set-up counts
// that energy into the run's budget and refuses a fluid too soft for its sigma. What the model does not
// do (Rayleigh's oscillation, Laplace's pressure) is measured in docs/results.md; the continuum surface
// force does both (below: Laplace's pressure under DFSPH, and under WCSPH with the cubic spline kernel).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "common/cohesion_energy.h"
#include "common/guided_creation.h"
#include "common/kernels.h"
#include "common/metrics.h"
#include "physics_helpers.h"

using namespace sph_test;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = 3.14159265358979323846;

// int_0^1 q^k c(q) dq by Simpson's rule on the kernel as the solver evaluates it.
double kernel_moment(int k) {
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double q = double(i) / n;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * std::pow(q, k) * double(sph::akinci_cohesion_shape(float(q)));
  }
  return sum / (3.0 * n);
}

struct DropRun {
  double radius = 0.0;        // sqrt(5/3 <|x - x_c|^2>) at the end [m]: a uniform ball's radius
  double outermost = 0.0;     // the farthest particle from the centre at the end [m]
  double equivalent = 0.0;    // the radius of a ball of the fluid's volume M / rho0 [m]
  double ke_max = 0.0;        // the largest kinetic energy over the run [J]
  double released = 0.0;      // sigma (A_cube - A_sphere) [J]
  double initial_surface_energy = 0.0;  // sigma A_cube [J]
  double budget = 0.0;        // the run's energy budget [J]
  double spacing = 0.0;
  double inner_pressure = 0.0;  // mean pressure of the particles within equivalent / 2 of the centre [Pa]
};

// The mean of the particles' positions [m].
void mean_position(const sph::ParticleState& ps, double c[3]) {
  c[0] = c[1] = c[2] = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    c[0] += ps.pos[i].x / double(ps.size());
    c[1] += ps.pos[i].y / double(ps.size());
    c[2] += ps.pos[i].z / double(ps.size());
  }
}

DropRun run_drop(int across, double seconds, std::vector<std::string> sets = {}) {
  sets.push_back("resolution.particles_across=" + std::to_string(across));
  const sph::Scene scene = scene_file("drop_oscillation.json", sets);
  sph::Simulation sim(scene, cpu_factory(), seconds);
  DropRun out;
  out.spacing = sim.setup().spacing;
  out.budget = sim.energy_budget();
  const sph::ParticleState& start = sim.particles();
  const double mass = double(sim.setup().constants.fluids[0].mass) * double(start.size());
  const double rho0 = scene.fluids[0].rest_density, sigma = scene.fluids[0].surface_tension;
  out.equivalent = std::cbrt(3.0 * mass / (4.0 * kPi * rho0));
  const double side = std::cbrt(mass / rho0);  // the lattice cube's side, N^(1/3) d
  out.released = sigma * (6.0 * side * side - 4.0 * kPi * out.equivalent * out.equivalent);
  out.initial_surface_energy = sigma * 6.0 * side * side;
  while (sim.time() < seconds) {
    sim.advance();
    out.ke_max = std::max(out.ke_max, sph::measure(sim.setup().constants, sim.particles()).kinetic_energy);
  }
  const sph::ParticleState& ps = sim.particles();
  double c[3];
  mean_position(ps, c);
  double r2 = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double dx = ps.pos[i].x - c[0], dy = ps.pos[i].y - c[1], dz = ps.pos[i].z - c[2];
    r2 += (dx * dx + dy * dy + dz * dz) / double(ps.size());
    out.outermost = std::max(out.outermost, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  out.radius = std::sqrt(5.0 / 3.0 * r2);
  long inner = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double dx = ps.pos[i].x - c[0], dy = ps.pos[i].y - c[1], dz = ps.pos[i].z - c[2];
    if (dx * dx + dy * dy + dz * dz > 0.25 * out.equivalent * out.equivalent) continue;
    out.inner_pressure += ps.pressure[i];
    ++inner;
  }
  if (inner > 0) out.inner_pressure /= double(inner);
  return out;
}

}  // namespace

TEST_CASE("cohesion kernel: the calibration's moments and the potential", "[surface_tension]") {
  // The exact moments guided_creation.cpp calibrates with, against the kernel the solver evaluates.
  CHECK(kernel_moment(3) == Approx(33.0 / 28672.0).epsilon(1e-4));
  CHECK(kernel_moment(4) == Approx(21.0 / 28160.0).epsilon(1e-4));
  // Continuous at q = 1/2, repulsive below q = 0.273, attractive above, zero at the support.
  CHECK(sph::akinci_cohesion_shape(0.5f) == Approx(sph::akinci_cohesion_shape(0.50001f)).margin(1e-6));
  CHECK(sph::akinci_cohesion_shape(0.26f) < 0.0f);
  CHECK(sph::akinci_cohesion_shape(0.29f) > 0.0f);
  CHECK(sph::akinci_cohesion_shape(1.0f) == 0.0f);
  // The potential shape is int_q^1 c: its derivative is -c (central differences).
  for (double q : {0.1, 0.3, 0.45, 0.55, 0.8, 0.95}) {
    const double e = 1e-5;
    const double slope = (sph::akinci_cohesion_potential_shape(q + e) - sph::akinci_cohesion_potential_shape(q - e)) / (2 * e);
    CHECK(slope == Approx(-double(sph::akinci_cohesion_shape(float(q)))).margin(1e-7));
  }
  CHECK(sph::akinci_cohesion_potential_shape(1.0) == 0.0);
  // sigma = (pi / 8) rho0^2 gamma int r^4 C dr: the constant gamma 32 / (pi h^3) times that integral.
  const double sigma = 0.0728, rho0 = 1000.0, h = 0.01;
  const double constant = sph::cohesion_from_surface_tension(sigma, rho0, h);
  const double gamma = constant * kPi * h * h * h / 32.0;
  CHECK(kPi / 8.0 * rho0 * rho0 * gamma * 32.0 / kPi * h * h * kernel_moment(4) == Approx(sigma).epsilon(1e-4));
}

TEST_CASE("surface tension pulls a cube of water into a sphere of its volume at two resolutions", "[surface_tension]") {
  for (int across : {10, 14}) {
    const DropRun r = run_drop(across, 0.4, {"solver=wcsph", "sph.surface_tension=cohesion"});
    INFO(across << " across: radius " << r.radius << " m, outermost particle " << r.outermost << " m, volume-equivalent "
                << r.equivalent << " m; kinetic energy at most " << r.ke_max << " J, surface energy released "
                << r.released << " J, initially " << r.initial_surface_energy << " J, budget " << r.budget << " J");
    CHECK(std::fabs(r.radius - r.equivalent) < 0.05 * r.equivalent);
    // A cube's corners lie at 1.40 times the radius; a sphere's outermost centres within half a spacing of it.
    CHECK(r.outermost < r.equivalent + 0.75 * r.spacing);
    // Energy: the kinetic energy stays below the initial surface energy sigma A_cube (issue 15). It does exceed
    // sigma times the area the cube loses (docs/results.md), and it does move the fluid.
    CHECK(r.ke_max < r.initial_surface_energy);
    CHECK(r.ke_max > 0.05 * r.released);
  }
}

TEST_CASE("under DFSPH the cohesion pulls a cube into a ball at two resolutions and leaves its corners at a third",
          "[surface_tension][dfsph]") {
  // The WCSPH test's checks above, at 0.5 s. Measured 2026-12-03 (the outermost particle against the ball's
  // radius plus 0.75 spacings): 0.0653 against 0.0695 m at 10 across, 0.0663 against 0.0674 m at 14.
  for (int across : {10, 14}) {
    const DropRun r = run_drop(across, 0.5, {"solver=dfsph", "sph.surface_tension=cohesion"});
    INFO(across << " across: radius " << r.radius << " m, outermost particle " << r.outermost << " m, volume-equivalent "
                << r.equivalent << " m; kinetic energy at most " << r.ke_max << " J, initially " << r.initial_surface_energy << " J");
    CHECK(std::fabs(r.radius - r.equivalent) < 0.05 * r.equivalent);
    CHECK(r.outermost < r.equivalent + 0.75 * r.spacing);
    CHECK(r.ke_max < r.initial_surface_energy);
  }
  // Where it fails: at 16 across the cube's corners stay out (0.0703 m at 0.5 s and 1.5 s, where the ball and
  // 0.75 spacings reach 0.0667 m; radius +1.1%): with one kernel the particles' lattice resists the slow
  // shear that rounds it, as it held Rayleigh-Taylor back (docs/results.md, "The cohesion under DFSPH"; with
  // Poly6 and Spiky 0.0667 m, under WCSPH 0.0637 m).
  const DropRun fine = run_drop(16, 0.5, {"solver=dfsph", "sph.surface_tension=cohesion"});
  INFO("16 across: outermost particle " << fine.outermost << " m, the ball's radius " << fine.equivalent << " m");
  CHECK(fine.outermost > fine.equivalent + 0.75 * fine.spacing);
  CHECK(std::fabs(fine.radius - fine.equivalent) < 0.05 * fine.equivalent);
}

TEST_CASE("under DFSPH the continuum surface force pulls a cube into a ball of its volume", "[surface_tension][dfsph]") {
  // Before the divergence solve dropped the kept pressure of particles without support (src/solvers/dfsph.h,
  // WarmStartFn), 192 of the cube's 600 face particles peeled off as a sheet and flew away (measured).
  const DropRun r = run_drop(12, 1.0, {"solver=dfsph", "sph.surface_tension=csf"});
  INFO("radius " << r.radius << " m, outermost particle " << r.outermost << " m, volume-equivalent " << r.equivalent
                 << " m; kinetic energy at most " << r.ke_max << " J, initially sigma A_cube = " << r.initial_surface_energy << " J");
  CHECK(std::fabs(r.radius - r.equivalent) < 0.05 * r.equivalent);
  CHECK(r.outermost < r.equivalent + 0.75 * r.spacing);
  CHECK(r.ke_max < r.initial_surface_energy);
}

TEST_CASE("under PBF the continuum surface force pulls a cube into a ball, with the scene's laminar viscosity",
          "[surface_tension][pbf]") {
  // drop_oscillation's 0.5 Pa s (Morris), which PBF applies since 2026-12-02 (src/solvers/pbf.h,
  // apply_viscosity), beside the paper's XSPH at c = 0.01, with the paper's plain iteration, as the set-up note
  // asks (the default's Chebyshev weights shed particles: the last test here).
  for (int across : {12, 16}) {
    const DropRun r = run_drop(across, 1.0, {"solver=pbf", "pbf.jacobi_weight=1", "pbf.chebyshev=0"});
    INFO(across << " across: radius " << r.radius << " m, outermost particle " << r.outermost << " m, volume-equivalent "
                << r.equivalent << " m; kinetic energy at most " << r.ke_max << " J, surface energy released " << r.released
                << " J, initially " << r.initial_surface_energy << " J, budget " << r.budget << " J");
    CHECK(std::fabs(r.radius - r.equivalent) < 0.05 * r.equivalent);
    CHECK(r.outermost < r.equivalent + 0.75 * r.spacing);
    CHECK(r.ke_max < r.released);  // damped: no more than the area it loses releases
    CHECK(r.budget > r.released);  // the budget counts the start's surface energy under PBF too (was 0)
  }
}

TEST_CASE("under PBF without a laminar viscosity, XSPH at c = 0.1 holds the drop and the paper's c = 0.01 does not",
          "[surface_tension][pbf]") {
  // XSPH as PBF's only viscosity (fluids.0.viscosity = 0): at c = 0.1 it damps the collapse.
  for (int across : {12, 16}) {
    const DropRun r = run_drop(across, 1.0, {"solver=pbf", "fluids.0.viscosity=0", "pbf.xsph=0.1", "pbf.jacobi_weight=1",
                                             "pbf.chebyshev=0"});
    INFO(across << " across: radius " << r.radius << " m, outermost particle " << r.outermost << " m, volume-equivalent "
                << r.equivalent << " m; kinetic energy at most " << r.ke_max << " J, released " << r.released << " J");
    CHECK(std::fabs(r.radius - r.equivalent) < 0.05 * r.equivalent);
    CHECK(r.outermost < r.equivalent + 0.75 * r.spacing);
    CHECK(r.ke_max < r.released);
  }
  // The method where it fails: c = 0.01 leaves the collapse almost undamped, PBF's corrections feed the
  // surface's motion and particles leave the drop (0.42 m from its centre at 0.6 s, docs/results.md). The
  // kinetic energy grows past what the lost area releases, and since the budget counts only that for a free
  // drop (cohesion_energy.h, least_surface_energy) the energy check stops the run (0.087 J at 0.38 s).
  CHECK_THROWS_WITH(run_drop(12, 0.6, {"solver=pbf", "fluids.0.viscosity=0"}),
                    Contains("kinetic energy") && Contains("surface tension"));
}

TEST_CASE("the set-up note names the damping and the iteration with which PBF's continuum surface force held a drop",
          "[surface_tension][pbf]") {
  auto noted = [](const std::vector<std::string>& sets) {
    const sph::Setup s = sph::create_setup(scene_file("drop_oscillation.json", sets), 1.0);
    return std::any_of(s.report.begin(), s.report.end(), [](const std::string& line) {
      return line.find("continuum surface force held a 0.1 m drop together") != std::string::npos;
    });
  };
  const std::string w1 = "pbf.jacobi_weight=1", ch0 = "pbf.chebyshev=0", novisc = "fluids.0.viscosity=0";
  CHECK(noted({"solver=pbf"}));                       // the Chebyshev weights (the last test)
  CHECK_FALSE(noted({"solver=pbf", w1, ch0}));        // the scene's 0.5 Pa s and c = 0.01 (the first test)
  CHECK(noted({"solver=pbf", w1, ch0, "pbf.xsph=0.1"}));  // both: 3 corner particles left a 12-across cube
  CHECK(noted({"solver=pbf", w1, ch0, "fluids.0.viscosity=0.1"}));  // less viscosity than was tested
  CHECK(noted({"solver=pbf", w1, ch0, novisc}));      // c = 0.01 alone (the last test)
  CHECK_FALSE(noted({"solver=pbf", w1, ch0, novisc, "pbf.xsph=0.1"}));
  CHECK(noted({"solver=pbf", novisc, "pbf.xsph=0.1"}));
  CHECK_FALSE(noted({"solver=dfsph"}));
}

TEST_CASE("under PBF with the default Chebyshev-accelerated iteration a cube held by the continuum surface force "
          "sheds particles", "[surface_tension][pbf]") {
  // The method where it fails: the weights that quiet a resting column (docs/results.md, issue 12) drive the
  // clumps the collapsing surface forms apart, and particles leave the drop with XSPH at 0.1 for its viscosity
  // (14 across: 7 particles beyond the drop at 0.6 s, the farthest 0.32 m from its centre; the plain iteration
  // lost 1). With the scene's laminar viscosity instead it is marginal: `sph_run` at 16 across, frames every
  // 0.05 s, lost 4 particles by 0.3 s, while this test's run of the same drop without frames (whose times
  // shorten some steps) lost none; so that case is not asserted here.
  const DropRun r = run_drop(14, 0.6, {"solver=pbf", "fluids.0.viscosity=0", "pbf.xsph=0.1"});
  INFO("XSPH at 0.1: outermost particle " << r.outermost << " m, volume-equivalent " << r.equivalent << " m");
  CHECK(r.outermost > 2.0 * r.equivalent);
}

namespace {

// Particles of a 20-across cube (scenes/drop_oscillation.json, DFSPH, continuum surface force) farther than two
// spacings beyond the ball of its volume after `seconds`: those its surface let go.
long shed_particles(bool curvature_limit, double seconds) {
  sph::Scene scene = scene_file("drop_oscillation.json", {"resolution.particles_across=20"});
  scene.csf_curvature_limit = curvature_limit;  // not a scene key (surface_tension_csf.h, csf_limited_curvature)
  sph::Simulation sim(scene, cpu_factory(), seconds);
  while (sim.time() < seconds) sim.advance();
  const sph::ParticleState& ps = sim.particles();
  const double mass = double(sim.setup().constants.fluids[0].mass) * double(ps.size());
  const double equivalent = std::cbrt(3.0 * mass / (4.0 * kPi * scene.fluids[0].rest_density));
  double c[3];
  mean_position(ps, c);
  const double reach = equivalent + 2.0 * sim.setup().spacing;
  long shed = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double dx = ps.pos[i].x - c[0], dy = ps.pos[i].y - c[1], dz = ps.pos[i].z - c[2];
    if (dx * dx + dy * dy + dz * dz > reach * reach) ++shed;
  }
  return shed;
}

}  // namespace

TEST_CASE("the continuum surface force's curvature limit keeps a finer cube's surface particles on it",
          "[surface_tension][dfsph]") {
  // A face particle whose own curvature read the wrong sign was pushed out of its face and, with too few
  // neighbours left for an estimate, flew off (surface_tension_csf.h, csf_limited_curvature). Measured
  // 2026-12-01 at 0.3 s: none with the limit, 69 of 8,000 without it.
  const long with_limit = shed_particles(true, 0.3), without = shed_particles(false, 0.3);
  INFO("particles shed by 0.3 s: " << with_limit << " with the curvature limit, " << without << " without");
  CHECK(with_limit <= 8);  // 0.1% of the cube
  CHECK(without > 40);     // 0.5%
}

TEST_CASE("a resting drop's inner pressure follows Laplace's law under DFSPH with the continuum surface force",
          "[surface_tension][dfsph]") {
  // Issue 15: within 15% of 2 sigma / R, R the radius of the ball of the fluid's volume; at two resolutions
  // (R = 3.8 h and 5.1 h). DFSPH's pressure is rho kappa of its density solve (the field the frames write).
  // Measured 2026-11-30: +2.2% and +6.8% after 1 s. Under DFSPH a drop of R = 2.9 h (the 0.075 m cube at
  // this spacing) is 31% high (docs/results.md).
  const double sigma = 4.7;
  for (int across : {12, 16}) {
    const DropRun r = run_drop(across, 1.0, {"solver=dfsph", "sph.surface_tension=csf"});
    const double laplace = 2.0 * sigma / r.equivalent;
    INFO(across << " across: pressure within R / 2 " << r.inner_pressure << " Pa, 2 sigma / R = " << laplace
                << " Pa (R = " << r.equivalent << " m), ratio " << r.inner_pressure / laplace);
    CHECK(std::fabs(r.inner_pressure / laplace - 1.0) <= 0.15);
  }
}

TEST_CASE("a free drop under the continuum surface force keeps its momentum", "[surface_tension][conservation]") {
  // drop_oscillation (no wall, no gravity): each step's net surface force is taken off the particles that feel
  // it (surface_forces.h). Without it the drop's mean velocity reached 2.8 mm/s after 1 s under DFSPH (0.6 m/s
  // at 300 N/m); the bound is 1/30 of that. The pressure force and the viscosities are pair forces.
  for (const char* solver : {"dfsph", "wcsph"}) {
    sph::Simulation sim(scene_file("drop_oscillation.json", {std::string("solver=") + solver}), cpu_factory(), 1.0);
    REQUIRE(sim.setup().constants.csf_momentum == 1);
    double drift = 0.0;
    while (sim.time() < 1.0) {
      sim.advance();
      if (sim.steps() % 20 != 0) continue;
      const sph::ParticleState& ps = sim.particles();
      double v[3] = {0.0, 0.0, 0.0};
      for (std::size_t i = 0; i < ps.size(); ++i) v[0] += ps.vel[i].x, v[1] += ps.vel[i].y, v[2] += ps.vel[i].z;
      drift = std::max(drift, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / double(ps.size()));
    }
    INFO(solver << ": the largest mean velocity over 1 s " << drift << " m/s");
    CHECK(drift < 1e-4);
  }
  // Not applied where a wall takes momentum (a drop in a box) or under PBF (the set-up leaves the flag off).
  CHECK(sph::create_setup(scene_file("drop_oscillation.json", {"solver=pbf"}), 1.0).constants.csf_momentum == 0);
  CHECK(sph::create_setup(scene_file("contact_angle.json", {"resolution.particles_across=5"}), 1.0).constants.csf_momentum == 0);
}

TEST_CASE("a ball of water laid out at rest holds Laplace's pressure with small spurious currents", "[surface_tension]") {
  // The static drop of the issue: a ball of radius 0.062 m (15 spacings across, 1,749 particles), sigma
  // 4.7 N/m, no gravity, the continuum surface force. Measured 2026-12-03 (pressure within R / 2 over
  // 2 sigma / R at 0.5 and 1 s; the fastest particle after 0.5 s): DFSPH 0.985 and 1.103, 0.024 m/s; WCSPH
  // 1.049 and 1.066, 0.018 m/s. The spurious currents' capillary number mu v / sigma stays below 0.005 (v
  // below 0.05 m/s at mu = 0.5 Pa s).
  const std::string text = R"({ "name": "ball",
    "fluids": [ { "name": "water", "rest_density": 1000, "speed_of_sound": 20, "viscosity": 0.5,
                  "artificial_viscosity": 0.05, "surface_tension": 4.7 } ],
    "emitters": [ { "type": "sphere", "fluid": "water", "center": [0, 0, 0], "radius": 0.062 } ],
    "resolution": { "spacing": 0.00833333, "neighbours": 32 }, "sph": { "surface_tension": "csf" },
    "time_step": { "mode": "adaptive", "dt": 1e-4, "max": 2e-3 }, "gravity": [0, 0, 0] })";
  const double sigma = 4.7, pi = 3.14159265358979323846;
  for (const char* solver : {"dfsph", "wcsph"}) {
    sph::Simulation sim(sph::parse_scene(text, "ball.json", {std::string("solver=") + solver}), cpu_factory(), 1.0);
    const double volume = double(sim.particles().size()) * sim.setup().constants.fluids[0].mass / 1000.0;
    const double radius = std::cbrt(3.0 * volume / (4.0 * pi));
    double v_late = 0.0;
    for (const double until : {0.5, 1.0}) {
      while (sim.time() < until) {
        sim.advance();
        if (sim.time() > 0.5) v_late = std::max(v_late, double(sim.backend().diagnose().max_speed));
      }
      const sph::ParticleState& ps = sim.particles();
      double c[3];
      mean_position(ps, c);
      double p = 0.0;
      long n = 0;
      for (std::size_t i = 0; i < ps.size(); ++i) {
        const double dx = ps.pos[i].x - c[0], dy = ps.pos[i].y - c[1], dz = ps.pos[i].z - c[2];
        if (dx * dx + dy * dy + dz * dz < 0.25 * radius * radius) p += ps.pressure[i], ++n;
      }
      REQUIRE(n > 0);
      INFO(solver << " at " << sim.time() << " s: pressure within R / 2 " << p / double(n) << " Pa, 2 sigma / R = "
                  << 2.0 * sigma / radius << " Pa (R = " << radius << " m)");
      CHECK(std::fabs(p / double(n) / (2.0 * sigma / radius) - 1.0) <= 0.15);
    }
    INFO(solver << ": fastest particle after 0.5 s " << v_late << " m/s");
    CHECK(v_late < 0.05);
  }
}

TEST_CASE("under WCSPH a drop's inner pressure follows Laplace's law with one kernel for density and pressure",
          "[surface_tension]") {
  // The cubic spline for the summed density and for the pressure gradient [BT07], which WCSPH's continuum
  // surface force takes when the scene names no sph.kernel (calibration.h, wcsph_cubic_spline). Measured
  // 2026-11-30 (docs/results.md): +5.1% at 12 across, +6.2% at 16 after 1 s; with the curvature's limit
  // (2026-12-01) +3.2% and +5.0%.
  const double sigma = 4.7;
  for (int across : {12, 16}) {
    const DropRun r = run_drop(across, 1.0, {"solver=wcsph", "sph.surface_tension=csf"});
    const double laplace = 2.0 * sigma / r.equivalent;
    INFO(across << " across: pressure within R / 2 " << r.inner_pressure << " Pa, 2 sigma / R = " << laplace
                << " Pa (R = " << r.equivalent << " m), ratio " << r.inner_pressure / laplace);
    CHECK(std::fabs(r.inner_pressure / laplace - 1.0) <= 0.15);
  }
  // The method where it fails: with the default pair, Poly6's density and Spiky's gradient, the Tait pressure
  // holds the same ball 29% above Laplace's (32% with the curvature's limit). The summed density of the
  // particles just inside the surface band and the pressure force on them weigh the missing neighbours
  // differently, and the bulk needs more pressure to hold the band out (docs/results.md).
  const DropRun w = run_drop(12, 1.0, {"solver=wcsph", "sph.surface_tension=csf", "sph.kernel=poly6_spiky"});
  INFO("WCSPH, Poly6 and Spiky, 12 across: " << w.inner_pressure << " Pa against " << 2.0 * sigma / w.equivalent << " Pa");
  CHECK(w.inner_pressure > 1.15 * 2.0 * sigma / w.equivalent);
}

TEST_CASE("under WCSPH the continuum surface force takes the cubic spline unless sph.kernel is given, and says so",
          "[surface_tension][scene]") {
  struct Choice {
    bool cubic_spline = false;
    std::string laplace_note;  // the set-up line that names Laplace's pressure, if any
  };
  auto choice = [](const std::vector<std::string>& sets) {
    const sph::Setup s = sph::create_setup(scene_file("drop_oscillation.json", sets), 1.0);
    Choice c;
    c.cubic_spline = s.constants.cubic_spline != 0;
    for (const std::string& line : s.report)
      if (line.find("Laplace") != std::string::npos && line.find("under WCSPH") != std::string::npos) c.laplace_note = line;
    return c;
  };
  const Choice taken = choice({"solver=wcsph"});
  CHECK(taken.cubic_spline);
  CHECK_THAT(taken.laplace_note, Contains("takes the cubic spline") && Contains("poly6_spiky"));
  const Choice pair = choice({"solver=wcsph", "sph.kernel=poly6_spiky"});
  CHECK_FALSE(pair.cubic_spline);
  CHECK_THAT(pair.laplace_note, Contains("15 to 32% above") && Contains("cubic_spline"));
  const Choice given = choice({"solver=wcsph", "sph.kernel=cubic_spline"});
  CHECK(given.cubic_spline);
  CHECK(given.laplace_note.empty());
  // The cohesion, and a fluid without a surface tension, keep WCSPH's default pair; DFSPH says nothing of it.
  CHECK_FALSE(choice({"solver=wcsph", "sph.surface_tension=cohesion"}).cubic_spline);
  CHECK_FALSE(choice({"solver=wcsph", "fluids.0.surface_tension=0"}).cubic_spline);
  CHECK(choice({"solver=wcsph", "sph.surface_tension=cohesion"}).laplace_note.empty());
  CHECK(choice({"solver=dfsph"}).laplace_note.empty());
}

TEST_CASE("without gravity the set-up says what the cohesion does to a drop and names the continuum surface force",
          "[surface_tension][scene]") {
  auto noted = [](const std::string& scene, const std::vector<std::string>& sets) {
    const sph::Setup s = sph::create_setup(scene_file(scene, sets), 1.0);
    return std::any_of(s.report.begin(), s.report.end(), [](const std::string& line) {
      return line.find("settles like an elastic solid") != std::string::npos && line.find("\"csf\"") != std::string::npos;
    });
  };
  CHECK(noted("drop_oscillation.json", {"sph.surface_tension=cohesion"}));
  CHECK(noted("drop_oscillation.json", {"sph.surface_tension=cohesion", "solver=wcsph"}));
  CHECK_FALSE(noted("drop_oscillation.json", {}));                    // the scene's continuum surface force
  CHECK_FALSE(noted("wetting.json", {"resolution.particles_across=6"}));  // the cohesion under gravity: drops on walls
}

TEST_CASE("the energy budget counts the surface energy of the start", "[surface_tension][energy]") {
  // The excess cohesive energy of a lattice cube scales with its area: 8^3 and 16^3 particles.
  sph::Scene scene = scene_file("drop_oscillation.json", {"resolution.particles_across=8", "solver=wcsph",
                                                          "sph.surface_tension=cohesion"});  // d = 0.0125 m
  scene.particles_across = 0;
  scene.spacing = 0.0125;
  const sph::Setup small = sph::create_setup(scene, 1.0);
  scene.emitters[0].min = {-0.1, -0.1, -0.1};
  scene.emitters[0].max = {0.1, 0.1, 0.1};
  const sph::Setup large = sph::create_setup(scene, 1.0);
  REQUIRE(large.particles.size() == 8 * small.particles.size());
  auto total = [](const sph::Setup& s) {
    double e = 0.0;
    const std::vector<double> x = sph::cohesion_excess_energy(s.constants, s.particles, s.spacing);
    for (double v : x) e += v * double(s.constants.fluids[0].mass);
    return e;
  };
  const double e_small = total(small), e_large = total(large);
  INFO("excess cohesive energy: " << e_small << " J on 8^3, " << e_large << " J on 16^3; sigma A = "
                                  << 4.7 * 6 * 0.01 << " J on the smaller cube");
  CHECK(e_large / e_small == Approx(4.0).epsilon(0.15));
  // Interior particles have none: at most the 6 faces' worth of particles (4 layers within h each) have any.
  const std::vector<double> x = sph::cohesion_excess_energy(large.constants, large.particles, large.spacing);
  const long with_excess = long(std::count_if(x.begin(), x.end(), [](double v) { return v > 1e-9; }));
  CHECK(with_excess < 6 * 16 * 16 * 2);
  CHECK(with_excess > 6 * 14 * 14);
}

TEST_CASE("a free drop's energy budget is what its lost area can release, and a drop that gains more stops",
          "[surface_tension][energy]") {
  // Continuum surface force, no solid about the fluid: the budget counts sigma times the start's area (the
  // lattice cube's, 6 (12 d)^2) less the ball's area of its volume, below which no shape goes.
  const double sigma = 4.7, pi = 3.14159265358979323846;
  sph::Simulation free(scene_file("drop_oscillation.json", {"resolution.particles_across=12"}), cpu_factory(), 1.0);
  const double volume = double(free.particles().size()) * free.setup().constants.fluids[0].mass / 1000.0;
  const double side = 12.0 * free.setup().spacing;
  const double released = sigma * (6.0 * side * side - 4.0 * pi * std::pow(3.0 * volume / (4.0 * pi), 2.0 / 3.0));
  INFO("budget " << free.energy_budget() << " J, sigma (A_cube - A_ball) = " << released << " J");
  CHECK(free.energy_budget() == Approx(released).epsilon(0.01));
  // In a container the fluid may spread on a wall (a half ball on a plate has 0.79 of a ball's free area):
  // no such bound, and the budget keeps the start's whole surface energy (the cohesion's estimate of it).
  std::ifstream in(std::string(SPH_SOURCE_DIR) + "/scenes/drop_oscillation.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string::size_type at = text.find("\"gravity\"");
  REQUIRE(at != std::string::npos);
  text.insert(at, R"("boundaries": [ { "type": "box", "min": [-0.2, -0.2, -0.2], "max": [0.2, 0.2, 0.2] } ], )");
  sph::Simulation boxed(sph::parse_scene(text, "drop_in_a_box.json", {"resolution.particles_across=12"}), cpu_factory(), 1.0);
  CHECK(boxed.energy_budget() > 2.0 * released);
  // A cube whose surface tension outruns its damping: at 1000 N/m (Ohnesorge number 0.0055 at the spacing)
  // it gained 16 J within 10 steps, where it can release 11.7 J, and flew apart; before, the budget's margin
  // (it counted all of sigma A_cube, 44 J) let the run end with exit 0 and every particle outside the domain.
  CHECK_THROWS_WITH(run_drop(12, 0.1, {"fluids.0.surface_tension=1000"}),
                    Contains("kinetic energy") && Contains("surface tension") && Contains("Ohnesorge"));
}

TEST_CASE("a fluid too soft for its surface tension is refused with the least speed of sound", "[surface_tension][scene]") {
  CHECK_THROWS_WITH(sph::create_setup(scene_file("drop_oscillation.json", {"fluids.0.speed_of_sound=5", "solver=wcsph",
                                                                        "sph.surface_tension=cohesion"}),
                                      1.0),
                    Contains("fluids.0.speed_of_sound") && Contains("at least") && Contains("surface_tension"));
  CHECK_THROWS_WITH(scene_file("drop_oscillation.json", {"fluids.0.surface_tension=-1"}), Contains("fluids.0.surface_tension"));
}

namespace {

// The l = 2 deformation <x^2> - (<y^2> + <z^2>) / 2 [m^2] of the particles within 1.5 R of the centre of mass
// of those within 2 R of the start's centre (a particle flung off does not count), sampled every step.
struct Ringing {
  std::vector<double> t, q2;
  double radius = 0.0;  // volume-equivalent [m]
};

Ringing ring(const std::string& model, double seconds, int across = 12, const std::string& solver = "wcsph",
             const std::string& kernel = "poly6_spiky") {
  // A box of the cube's volume, 0.11 x 0.1 x 0.091 m, longer along x: it rings in the l = 2 mode (amplitude ~10%).
  std::vector<std::string> sets = {"sph.surface_tension=" + model, "emitters.0.min=[-0.055,-0.05,-0.04545]",
                                   "emitters.0.max=[0.055,0.05,0.04545]",
                                   "resolution.particles_across=" + std::to_string(across), "solver=" + solver};
  if (solver == "wcsph") sets.push_back("sph.kernel=" + kernel);
  if (solver == "pbf") sets.insert(sets.end(), {"pbf.jacobi_weight=1", "pbf.chebyshev=0"});  // as the set-up note asks
  const sph::Scene scene = scene_file("drop_oscillation.json", sets);
  sph::Simulation sim(scene, cpu_factory(), seconds);
  Ringing out;
  const double mass = double(sim.setup().constants.fluids[0].mass) * double(sim.particles().size());
  out.radius = std::cbrt(3.0 * mass / (4.0 * kPi * scene.fluids[0].rest_density));
  while (sim.time() < seconds) {
    sim.advance();
    const sph::ParticleState& ps = sim.particles();
    double c[3] = {0, 0, 0}, n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (sph::length(ps.pos[i]) < 2.0 * out.radius) {
        c[0] += ps.pos[i].x, c[1] += ps.pos[i].y, c[2] += ps.pos[i].z, n += 1;
      }
    double m[3] = {0, 0, 0}, k = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const double x = ps.pos[i].x - c[0] / n, y = ps.pos[i].y - c[1] / n, z = ps.pos[i].z - c[2] / n;
      if (x * x + y * y + z * z > 2.25 * out.radius * out.radius) continue;
      m[0] += x * x, m[1] += y * y, m[2] += z * z, k += 1;
    }
    out.t.push_back(sim.time());
    out.q2.push_back((m[0] - 0.5 * (m[1] + m[2])) / k);
  }
  return out;
}

}  // namespace

namespace {

// The times of the minima of q2 < 0 (the box squeezed along x), each the lowest within 0.1 s (a minimum of the
// ringing, not of the step-to-step noise).
std::vector<double> squeeze_minima(const Ringing& r) {
  std::vector<double> minima;
  for (std::size_t i = 1; i + 1 < r.q2.size(); ++i) {
    if (!(r.q2[i] < 0.0 && r.q2[i] < r.q2[i - 1] && r.q2[i] <= r.q2[i + 1])) continue;
    bool lowest = true;
    for (std::size_t j = 0; j < r.q2.size(); ++j)
      if (std::fabs(r.t[j] - r.t[i]) < 0.1 && r.q2[j] < r.q2[i]) lowest = false;
    if (lowest && (minima.empty() || r.t[i] - minima.back() > 0.1)) minima.push_back(r.t[i]);
  }
  return minima;
}

}  // namespace

TEST_CASE("the continuum surface force rings at Rayleigh's period, the cohesion does not ring", "[surface_tension]") {
  const double sigma = 4.7, rho0 = 1000.0;
  // Continuum surface force: the box turns into one squeezed along x (q2 < 0) and back. Its l = 2 period,
  // between the first two minima of q2, within issue 15's 10% of Rayleigh's 2 pi / sqrt(8 sigma / (rho0 R^3)),
  // at two resolutions under WCSPH and under DFSPH, once more under WCSPH with its cubic spline kernel, and at
  // one under PBF (with the scene's laminar viscosity, which PBF applies since 2026-12-02, and the paper's plain
  // iteration). Without the surface's offset from the particles (csf_surface_curvature) it was 12% short
  // (measured). At 16 across the lattice makes the box 19 x 18 x 16 particles, nearly as long along y as along
  // x, and under DFSPH q2's first minimum comes early (0.19 s): the first two minima are 16% short of
  // Rayleigh's period, the half periods after them within 1% (docs/results.md, "Rayleigh's period under DFSPH
  // at two resolutions").
  struct Case {
    int across;
    std::string solver, kernel;
  };
  for (const Case& run : std::vector<Case>{{12, "wcsph", "poly6_spiky"}, {14, "wcsph", "poly6_spiky"},
                                           {12, "wcsph", "cubic_spline"}, {12, "dfsph", ""}, {14, "dfsph", ""},
                                           {12, "pbf", ""}}) {
    const int across = run.across;
    const std::string solver = run.solver + (run.kernel.empty() ? "" : " (" + run.kernel + ")");
    const Ringing csf = ring("csf", 0.8, across, run.solver, run.kernel);
    const double rayleigh = 2.0 * kPi / std::sqrt(8.0 * sigma / (rho0 * std::pow(csf.radius, 3)));
    const std::vector<double> minima = squeeze_minima(csf);
    const double least = *std::min_element(csf.q2.begin(), csf.q2.end());
    INFO(solver << ", " << across << " across: csf deformation from " << csf.q2.front() << " down to " << least << " m^2; minima at "
                << (minima.empty() ? -1.0 : minima[0]) << " and " << (minima.size() > 1 ? minima[1] : -1.0)
                << " s; Rayleigh's l = 2 period " << rayleigh << " s (R = " << csf.radius << " m)");
    CHECK(least < -0.3 * csf.q2.front());  // squeezed the other way by at least 30% of the start's elongation
    REQUIRE(minima.size() >= 2);           // and back again, and over once more
    CHECK(std::fabs((minima[1] - minima[0]) / rayleigh - 1.0) <= 0.10);
  }
  // Cohesion: the box never turns into one squeezed along x: it settles like an elastic solid.
  const Ringing cohesion = ring("cohesion", 0.5);
  const double lowest = *std::min_element(cohesion.q2.begin(), cohesion.q2.end());
  INFO("cohesion: the deformation's least value " << lowest << " m^2 (start " << cohesion.q2.front() << ")");
  CHECK(lowest > 0.0);
}
