// Several fluids of very different density (issue 15, Solenthaler & Pajarola 2008, thesis 3.4.3): two layers
// at rest, water under a fluid ten (and a thousand) times lighter, stay layered and at rest with the
// number-density form, and fly apart with the neighbours' masses summed (tested where it fails). The
// loader refuses the combinations that cannot hold such layers.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/metrics.h"
#include "physics_helpers.h"

using namespace sph_test;
using Catch::Matchers::Contains;

namespace {

// The interface as each fluid sees it: the 99th percentile of the lower fluid's heights and the 1st of the
// upper fluid's [m] (robust to a stray particle, sensitive to a layer that rises or sinks).
struct Interface {
  double lower_top = 0.0, upper_bottom = 0.0;
};

Interface interface_of(const sph::ParticleState& ps) {
  std::vector<double> lower, upper;
  for (std::size_t i = 0; i < ps.size(); ++i) (ps.fluid[i] == 0 ? lower : upper).push_back(ps.pos[i].y);
  std::sort(lower.begin(), lower.end());
  std::sort(upper.begin(), upper.end());
  return {lower[std::size_t(0.99 * double(lower.size() - 1))], upper[std::size_t(0.01 * double(upper.size() - 1))]};
}

struct LayerRun {
  Interface start, end;
  double v_max_late = 0.0;  // the largest speed over the second half of the run [m/s]
  double v_max = 0.0;       // over the whole run
  double v99_end = 0.0;     // the 99th percentile of the speeds at the end
  double spacing = 0.0;
};

LayerRun run_layers(const sph::Scene& scene, double seconds) {
  sph::Simulation sim(scene, cpu_factory(), seconds);
  LayerRun out;
  out.spacing = sim.setup().spacing;
  out.start = interface_of(sim.particles());
  while (sim.time() < seconds) {
    sim.advance();
    const double v = sph::measure(sim.setup().constants, sim.particles()).v_max;
    out.v_max = std::max(out.v_max, v);
    if (sim.time() > 0.5 * seconds) out.v_max_late = std::max(out.v_max_late, v);
  }
  out.end = interface_of(sim.particles());
  std::vector<double> speeds;
  for (const sph::Vec3& v : sim.particles().vel) speeds.push_back(sph::length(v));
  std::sort(speeds.begin(), speeds.end());
  out.v99_end = speeds[std::size_t(0.99 * double(speeds.size() - 1))];
  return out;
}

}  // namespace

TEST_CASE("two layers at density ratio 10 stay layered and at rest with the number-density form", "[multiphase]") {
  const sph::Scene scene = scene_file("two_layers.json");
  REQUIRE(scene.number_density);
  const LayerRun r = run_layers(scene, 0.5);
  INFO("water top " << r.start.lower_top << " -> " << r.end.lower_top << " m, oil bottom " << r.start.upper_bottom << " -> "
                    << r.end.upper_bottom << " m, spacing " << r.spacing << " m; largest speed " << r.v_max
                    << " m/s, after 0.25 s " << r.v_max_late << " m/s");
  CHECK(std::fabs(r.end.lower_top - r.start.lower_top) < r.spacing);
  CHECK(std::fabs(r.end.upper_bottom - r.start.upper_bottom) < r.spacing);
  CHECK(r.v_max_late < 0.1);
}

TEST_CASE("two layers at density ratio 10 stay layered under DFSPH in the number-density form", "[multiphase][dfsph]") {
  const sph::Scene scene = scene_file("two_layers.json", {"solver=dfsph"});
  const LayerRun r = run_layers(scene, 0.5);
  INFO("water top " << r.start.lower_top << " -> " << r.end.lower_top << " m, oil bottom " << r.start.upper_bottom << " -> "
                    << r.end.upper_bottom << " m; speeds at the end: 99th percentile " << r.v99_end << " m/s; largest over "
                    << "the run " << r.v_max << " m/s, after 0.25 s " << r.v_max_late << " m/s");
  CHECK(std::fabs(r.end.lower_top - r.start.lower_top) < r.spacing);
  CHECK(std::fabs(r.end.upper_bottom - r.start.upper_bottom) < r.spacing);
  // The 0.1 m/s for the fastest particle, as under WCSPH. Before the wall ghosts moved with their
  // particles in DFSPH's density rate (src/common/dfsph.h), a particle in a corner of the floor rattled at up
  // to 0.89 m/s here, and only the 99th percentile stayed below 0.1 m/s.
  CHECK(r.v_max_late < 0.1);
  CHECK(r.v99_end < 0.1);
}

TEST_CASE("two layers at density ratio 10 stay layered under PBF in the number-density form", "[multiphase][pbf]") {
  // PBF's constraint on the number density, its corrections weighted by inverse mass (src/common/pbf.h). PBF
  // is never quiet at rest: every step's corrections become speeds (v = Delta x / dt), and the same tank with
  // one rest density keeps about 0.2 m/s at its 99th percentile (measured). So the speeds are checked against
  // that run: the light fluid, which takes the larger share of each correction, may rattle more, but not
  // flow.
  const LayerRun r = run_layers(scene_file("two_layers.json", {"solver=pbf"}), 0.5);
  const LayerRun one = run_layers(scene_file("two_layers.json", {"solver=pbf", "fluids.1.rest_density=1000"}), 0.5);
  INFO("water top " << r.start.lower_top << " -> " << r.end.lower_top << " m, oil bottom " << r.start.upper_bottom << " -> "
                    << r.end.upper_bottom << " m; speeds at the end: 99th percentile " << r.v99_end << " m/s (one rest "
                    << "density: " << one.v99_end << " m/s); largest after 0.25 s " << r.v_max_late << " m/s (one rest density: "
                    << one.v_max_late << " m/s)");
  CHECK(std::fabs(r.end.lower_top - r.start.lower_top) < r.spacing);
  CHECK(std::fabs(r.end.upper_bottom - r.start.upper_bottom) < r.spacing);
  CHECK(r.v99_end < 2.0 * one.v99_end);
  CHECK(r.v_max_late < 2.0 * one.v_max_late);
}

TEST_CASE("under PBF two layers at density ratio 10 are thrown about when the neighbours' masses are summed",
          "[multiphase][pbf]") {
  sph::Scene scene = scene_file("two_layers.json", {"solver=pbf"});
  scene.number_density = false;  // past the loader, which refuses this combination
  const LayerRun r = run_layers(scene, 0.1);
  INFO("largest speed " << r.v_max << " m/s; oil bottom " << r.start.upper_bottom << " -> " << r.end.upper_bottom << " m");
  CHECK(r.v_max > 1.0);
}

TEST_CASE("two layers at density ratio 10 are thrown about when the neighbours' masses are summed", "[multiphase]") {
  sph::Scene scene = scene_file("two_layers.json");
  scene.number_density = false;  // past the loader, which refuses this combination (next test)
  const LayerRun r = run_layers(scene, 0.1);
  INFO("largest speed " << r.v_max << " m/s");
  CHECK(r.v_max > 0.5);  // five times the number-density form's bound
}

TEST_CASE("layers at density ratio 1000 hold for 0.05 s when the light fluid's stiffness matches", "[multiphase]") {
  // Air-like over water: the light fluid's c0 raised so that Tait's B is a tenth of water's (the limit).
  const sph::Scene scene = scene_file("two_layers.json", {"fluids.1.rest_density=1", "fluids.1.speed_of_sound=150"});
  const LayerRun r = run_layers(scene, 0.05);
  INFO("water top " << r.start.lower_top << " -> " << r.end.lower_top << " m, light bottom " << r.start.upper_bottom
                    << " -> " << r.end.upper_bottom << " m; largest speed " << r.v_max << " m/s");
  CHECK(std::fabs(r.end.lower_top - r.start.lower_top) < r.spacing);
  CHECK(std::fabs(r.end.upper_bottom - r.start.upper_bottom) < r.spacing);
  CHECK(r.v_max < 0.1);
}

TEST_CASE("density ratios a formulation cannot hold are refused with the key and the limit", "[multiphase][scene]") {
  CHECK_THROWS_WITH(scene_file("two_layers.json", {"sph.multiphase=mass_density"}),
                    Contains("sph.multiphase") && Contains("1.25") && Contains("number_density"));
  CHECK_THROWS_WITH(scene_file("two_layers.json", {"fluids.1.rest_density=1"}),
                    Contains("fluids.1.speed_of_sound") && Contains("at least 150"));
  CHECK_THROWS_WITH(scene_file("two_layers.json", {"solver=pbf", "sph.multiphase=mass_density"}),
                    Contains("sph.multiphase") && Contains("1.25"));
  CHECK_NOTHROW(scene_file("two_layers.json", {"solver=pbf", "fluids.1.rest_density=1"}));  // no equation of state
  CHECK_NOTHROW(scene_file("two_layers.json", {"solver=dfsph", "fluids.1.rest_density=1"}));  // no equation of state
  CHECK_THROWS_WITH(scene_file("two_layers.json", {"sph.multiphase=volume"}),
                    Contains("sph.multiphase") && Contains("number_density") && Contains("mass_density"));
  // Equal rest densities: either form, nothing refused.
  CHECK_NOTHROW(scene_file("two_layers.json", {"sph.multiphase=mass_density", "fluids.1.rest_density=1000"}));
}

namespace {

// The interface's displacement in rayleigh_taylor: half the difference between the heavy fluid's lowest
// reach (2nd percentile of its heights) next to the walls and in the middle [m].
double rt_amplitude(const sph::ParticleState& ps, double width) {
  std::vector<double> centre, edge;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.fluid[i] != 0) continue;
    const double x = ps.pos[i].x;
    if (std::fabs(x - 0.5 * width) < 0.1 * width) centre.push_back(ps.pos[i].y);
    if (x < 0.1 * width || x > 0.9 * width) edge.push_back(ps.pos[i].y);
  }
  auto low = [](std::vector<double>& v) {
    std::sort(v.begin(), v.end());
    return v[std::size_t(0.02 * double(v.size() - 1))];
  };
  return 0.5 * (low(edge) - low(centre));
}

// rayleigh_taylor four layers deep (0.01 m): water over a fluid half as dense (Atwood 1/3), a notch of two
// spacings seeding the mode of wavelength 2 W between slip walls, k = pi / W; the solver's keys in `sets`.
// Linear theory from rest: a(t) = a0 cosh(n t), n^2 = A g k (inviscid; the fluids' mu of 0.01 Pa s changes n
// by 0.1%), read where a is 2.5 a0 (k a = 0.2, still linear); the growth rate must be within 20% of it.
void check_rayleigh_taylor(std::vector<std::string> sets) {
  const double width = 0.1, depth = 0.01;
  for (const char* s : {"boundaries.0.max=[0.1,0.2,0.01]", "emitters.0.max=[0.075,0.1,0.01]", "emitters.1.max=[0.1,0.2,0.01]",
                        "emitters.2.max=[0.1,0.1,0.01]"})
    sets.push_back(s);
  const sph::Scene scene = scene_file("rayleigh_taylor.json", sets);
  REQUIRE(scene.fluids[1].rest_density == 500.0);
  sph::Simulation sim(scene, cpu_factory(), 0.3);
  const double a0 = rt_amplitude(sim.particles(), width);
  const double atwood = (1000.0 - 500.0) / 1500.0, k = 3.14159265358979 / width, g = 9.81;
  const double n_theory = std::sqrt(atwood * g * k);
  double n_measured = 0.0, t_read = 0.0;
  while (sim.time() < 0.3 && n_measured == 0.0) {
    sim.advance();
    const double a = rt_amplitude(sim.particles(), width);
    if (a >= 2.5 * a0) {
      t_read = sim.time();
      n_measured = std::acosh(a / a0) / t_read;
    }
  }
  INFO("amplitude " << a0 << " m at the start, 2.5 times that at " << t_read << " s: growth rate " << n_measured
                    << " 1/s; linear theory sqrt(A g k) = " << n_theory << " 1/s (depth " << depth << " m)");
  REQUIRE(n_measured > 0.0);
  CHECK(std::fabs(n_measured - n_theory) < 0.2 * n_theory);
}

}  // namespace

TEST_CASE("Rayleigh-Taylor: the interface grows at the rate of linear theory", "[multiphase]") { check_rayleigh_taylor({}); }

TEST_CASE("Rayleigh-Taylor under PBF: the interface grows at the rate of linear theory with 10 iterations",
          "[multiphase][pbf]") {
  // The number-density constraint with mass-weighted corrections (src/common/pbf.h) carries the buoyancy
  // (measured +2.2% against linear theory).
  check_rayleigh_taylor({"solver=pbf", "pbf.iterations=10"});
  // The method where it fails: with the default 4 iterations the heavy layer is not held up, sinks into the
  // light one faster than it can fall, and the energy check stops the run (at 0.073 s, measured).
  const sph::Scene scene = scene_file("rayleigh_taylor.json", {"solver=pbf", "boundaries.0.max=[0.1,0.2,0.01]",
                                                                "emitters.0.max=[0.075,0.1,0.01]", "emitters.1.max=[0.1,0.2,0.01]",
                                                                "emitters.2.max=[0.1,0.1,0.01]"});
  sph::Simulation sim(scene, cpu_factory(), 0.3);
  CHECK_THROWS_AS([&] { while (sim.time() < 0.3) sim.advance(); }(), sph::BlowUp);
}
