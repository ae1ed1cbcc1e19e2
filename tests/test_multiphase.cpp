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

namespace {

// two_layers under PBF's defaults for 0.5 s at density ratio 10 and, as the reference, with one rest density;
// run once for the two tests below.
struct PbfLayers {
  LayerRun ratio10, one;
};

const PbfLayers& pbf_layers() {
  static const PbfLayers runs{run_layers(scene_file("two_layers.json", {"solver=pbf"}), 0.5),
                              run_layers(scene_file("two_layers.json", {"solver=pbf", "fluids.1.rest_density=1000"}), 0.5)};
  return runs;
}

}  // namespace

TEST_CASE("two layers at density ratio 10 stay layered under PBF in the number-density form", "[multiphase][pbf]") {
  // PBF's constraint on the number density, its corrections weighted by inverse mass (src/common/pbf.h).
  const LayerRun& r = pbf_layers().ratio10;
  INFO("water top " << r.start.lower_top << " -> " << r.end.lower_top << " m, oil bottom " << r.start.upper_bottom << " -> "
                    << r.end.upper_bottom << " m");
  CHECK(std::fabs(r.end.lower_top - r.start.lower_top) < r.spacing);
  CHECK(std::fabs(r.end.upper_bottom - r.start.upper_bottom) < r.spacing);
}

TEST_CASE("under PBF the light fluid of two layers rattles at most twice as fast as one fluid does",
          "[multiphase][pbf][!shouldfail]") {
  // A known failure, kept as the check it was: PBF is never quiet at rest (every step's corrections become
  // speeds, v = Delta x / dt), and at the interface the light fluid takes m_w / (m_w + m_l) = 10/11 of a
  // shared correction instead of half, 1.8 times as much; so its speeds were checked against the same tank
  // with one rest density, within twice them. That held with the paper's plain Jacobi iteration and solid
  // wall ghosts (0.298 against 0.163 m/s at the 99th percentile). Since the wall ghosts count as fluid and the
  // iteration is weighted and Chebyshev-accelerated (issue 12) the one-fluid tank is quieter (0.097 m/s) and
  // the light fluid less so (0.232 m/s, 2.4 times; docs/results.md, "Several fluids under PBF"). With the
  // scene's artificial viscosity (pbf.artificial_viscosity) both come to rest (the next test).
  const LayerRun& r = pbf_layers().ratio10;
  const LayerRun& one = pbf_layers().one;
  INFO("speeds at the end: 99th percentile " << r.v99_end << " m/s (one rest density: " << one.v99_end
                                             << " m/s); largest after 0.25 s " << r.v_max_late
                                             << " m/s (one rest density: " << one.v_max_late << " m/s)");
  CHECK(r.v99_end < 2.0 * one.v99_end);
  CHECK(r.v_max_late < 2.0 * one.v_max_late);
}

TEST_CASE("under PBF with the scene's artificial viscosity two layers at density ratio 10 stay layered and at rest",
          "[multiphase][pbf]") {
  // The damping WCSPH and DFSPH give the scene (fluids.N.artificial_viscosity 0.2, c0 15 m/s), applied by PBF
  // with pbf.artificial_viscosity (src/solvers/pbf.h, apply_viscosity; sub-cycled: 2 updates a 1 ms step). The
  // issue's bounds, as under WCSPH and DFSPH above; with XSPH alone the light fluid still moved at 0.63 m/s
  // after 0.25 s (the known failure above).
  const LayerRun r = run_layers(scene_file("two_layers.json", {"solver=pbf", "pbf.artificial_viscosity=true"}), 0.5);
  INFO("water top " << r.start.lower_top << " -> " << r.end.lower_top << " m, oil bottom " << r.start.upper_bottom << " -> "
                    << r.end.upper_bottom << " m; speeds at the end: 99th percentile " << r.v99_end << " m/s; largest after "
                    << "0.25 s " << r.v_max_late << " m/s");
  CHECK(std::fabs(r.end.lower_top - r.start.lower_top) < r.spacing);
  CHECK(std::fabs(r.end.upper_bottom - r.start.upper_bottom) < r.spacing);
  CHECK(r.v_max_late < 0.1);
  CHECK(r.v99_end < 0.1);
}

TEST_CASE("under PBF the set-up names the damping and the iterations that several fluids need",
          "[multiphase][pbf][scene]") {
  auto notes = [](const std::vector<std::string>& sets) {
    const sph::Setup s = sph::create_setup(scene_file("two_layers.json", sets), 1.0);
    std::string all;
    for (const std::string& line : s.report) all += line + "\n";
    return all;
  };
  const std::string plain = notes({"solver=pbf"});
  CHECK_THAT(plain, Contains("pbf.artificial_viscosity = true") && Contains("do not come to rest"));
  CHECK_THAT(plain, Contains("pbf.iterations >= 10") && Contains("a light drop rising"));
  CHECK_THAT(notes({"solver=pbf", "pbf.artificial_viscosity=true", "pbf.iterations=10"}),
             !Contains("do not come to rest") && !Contains("pbf.iterations >= 10"));
  CHECK_THAT(notes({"solver=pbf", "fluids.1.rest_density=1000"}), !Contains("do not come to rest"));
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

namespace {

// The check for layers 1000 times apart: over 0.05 s the interface within a spacing and every
// particle, start included, below 0.1 m/s.
void check_ratio_1000(const sph::Scene& scene) {
  const LayerRun r = run_layers(scene, 0.05);
  INFO("water top " << r.start.lower_top << " -> " << r.end.lower_top << " m, light bottom " << r.start.upper_bottom
                    << " -> " << r.end.upper_bottom << " m; largest speed " << r.v_max << " m/s");
  CHECK(std::fabs(r.end.lower_top - r.start.lower_top) < r.spacing);
  CHECK(std::fabs(r.end.upper_bottom - r.start.upper_bottom) < r.spacing);
  CHECK(r.v_max < 0.1);
}

}  // namespace

TEST_CASE("layers at density ratio 1000 hold for 0.05 s when the light fluid's stiffness matches", "[multiphase]") {
  // Air-like over water: the light fluid's c0 raised so that Tait's B is a tenth of water's (the limit).
  const sph::Scene scene = scene_file("two_layers.json", {"fluids.1.rest_density=1", "fluids.1.speed_of_sound=150"});
  check_ratio_1000(scene);
}

TEST_CASE("under DFSPH layers at density ratio 1000 hold and stay below 0.1 m/s for 0.05 s", "[multiphase][dfsph]") {
  // DFSPH has no equation of state, so no stiffness to match: the air-like fluid as it is. The fastest
  // particle over the whole run, start included (v_max, as the issue asks within 0.05 s): 0.031 m/s (measured
  // 2026-12-02). Until then its masses were calibrated with Poly6's lattice sum while it sums the cubic
  // spline: both layers started 0.78% below rest density, the column fell freely until it had closed that (up
  // to 18 ms at its top), and the fastest particle reached 0.152 m/s (docs/results.md, "DFSPH's mass from
  // the cubic spline").
  const sph::Scene scene = scene_file("two_layers.json", {"solver=dfsph", "fluids.1.rest_density=1"});
  check_ratio_1000(scene);
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
// by 0.1%), read where a is 2.5 a0 (k a = 0.2, still linear).
struct RayleighTaylor {
  double a0 = 0.0, a_end = 0.0, t_read = 0.0, t_end = 0.0;
  double rate = 0.0;  // measured n [1/s]; 0 where a never reached 2.5 a0 within t_max
  bool blew_up = false;
  double theory = 0.0;  // sqrt(A g k) [1/s]
};

RayleighTaylor rayleigh_taylor(std::vector<std::string> sets, double t_max = 0.3) {
  const double width = 0.1;
  for (const char* s : {"boundaries.0.max=[0.1,0.2,0.01]", "emitters.0.max=[0.075,0.1,0.01]", "emitters.1.max=[0.1,0.2,0.01]",
                        "emitters.2.max=[0.1,0.1,0.01]"})
    sets.push_back(s);
  const sph::Scene scene = scene_file("rayleigh_taylor.json", sets);
  REQUIRE(scene.fluids[1].rest_density == 500.0);
  sph::Simulation sim(scene, cpu_factory(), t_max);
  RayleighTaylor r;
  r.a0 = rt_amplitude(sim.particles(), width);
  const double atwood = (1000.0 - 500.0) / 1500.0, k = 3.14159265358979 / width, g = 9.81;
  r.theory = std::sqrt(atwood * g * k);
  try {
    while (sim.time() < t_max && r.rate == 0.0) {
      sim.advance();
      r.a_end = rt_amplitude(sim.particles(), width);
      if (r.a_end >= 2.5 * r.a0) {
        r.t_read = sim.time();
        r.rate = std::acosh(r.a_end / r.a0) / r.t_read;
      }
    }
  } catch (const sph::BlowUp&) {
    r.blew_up = true;
  }
  r.t_end = sim.time();
  return r;
}

// The growth rate within 20% of linear theory.
void check_rayleigh_taylor(const std::vector<std::string>& sets) {
  const RayleighTaylor r = rayleigh_taylor(sets);
  INFO("amplitude " << r.a0 << " m at the start, 2.5 times that at " << r.t_read << " s: growth rate " << r.rate
                    << " 1/s; linear theory sqrt(A g k) = " << r.theory << " 1/s (depth 0.01 m)");
  REQUIRE_FALSE(r.blew_up);
  REQUIRE(r.rate > 0.0);
  CHECK(std::fabs(r.rate - r.theory) < 0.2 * r.theory);
}

}  // namespace

TEST_CASE("Rayleigh-Taylor: the interface grows at the rate of linear theory", "[multiphase]") { check_rayleigh_taylor({}); }

TEST_CASE("Rayleigh-Taylor under PBF: the interface grows at the rate of linear theory with 10 iterations",
          "[multiphase][pbf]") {
  // The number-density constraint with mass-weighted corrections (src/common/pbf.h) carries the buoyancy
  // (measured -16% against linear theory with the scene's 0.01 Pa s, which PBF applies since 2026-12-02;
  // -6.5% without it: docs/results.md, "PBF takes the scene's viscosity").
  check_rayleigh_taylor({"solver=pbf", "pbf.iterations=10"});
  // The method where it fails: the default 4 iterations. With the weighted, Chebyshev-accelerated iteration
  // the interface grows at about half the rate of theory (2.45 a0 at 0.3 s, where theory is at 2.5 a0 by
  // 0.155 s; measured); the paper's plain Jacobi iteration grew within 6% of it (docs/results.md, "Several
  // fluids under PBF"). A set-up note asks for 10 iterations where rest densities differ.
  const RayleighTaylor r = rayleigh_taylor({"solver=pbf"});
  INFO("4 iterations: growth rate " << r.rate << " 1/s (0: 2.5 a0 not reached by " << r.t_end << " s, amplitude then "
                                    << r.a_end << " m from " << r.a0 << " m); theory " << r.theory << " 1/s");
  CHECK_FALSE(r.blew_up);
  CHECK(std::fabs(r.rate - r.theory) > 0.2 * r.theory);
}

TEST_CASE("Rayleigh-Taylor under DFSPH: the interface grows at the rate of linear theory with Poly6 and Spiky",
          "[multiphase][dfsph]") {
  // The scene gives sph.kernel = "poly6_spiky", which DFSPH then takes (src/common/dfsph.h; measured -9%:
  // 2.5 a0 at about 0.17 s, docs/results.md, "DFSPH's kernel").
  check_rayleigh_taylor({"solver=dfsph"});
}

TEST_CASE("Rayleigh-Taylor under DFSPH with the cubic spline stalls below linear theory's rate", "[multiphase][dfsph]") {
  // The method where it fails: with [BK15]'s one kernel the particles' lattice resists the slow shear and the
  // interface stops near 1.6 a0 (measured), where theory passes 2.5 a0 at 0.155 s. A rate within 20% of
  // theory would reach 2.5 a0 by 0.194 s, so not reaching it by 0.2 s is a miss of more than 20%.
  const RayleighTaylor r = rayleigh_taylor({"solver=dfsph", "sph.kernel=cubic_spline"}, 0.2);
  INFO("cubic spline: amplitude " << r.a_end / r.a0 << " a0 at " << r.t_end << " s (theory cosh(n t) = "
                                  << std::cosh(r.theory * r.t_end) << ")");
  CHECK_FALSE(r.blew_up);
  CHECK(r.rate == 0.0);
  CHECK(r.a_end > 1.3 * r.a0);  // it grows at first (1.63 a0 measured), then stalls
}

TEST_CASE("DFSPH takes sph.kernel when the scene gives it, calibrates its masses with it and says when it stalls",
          "[multiphase][dfsph][scene]") {
  const auto setup = [](const std::string& file, const std::vector<std::string>& sets, bool& stall_noted) {
    const sph::Setup s = sph::create_setup(scene_file(file, sets), 0.1);
    stall_noted = std::any_of(s.report.begin(), s.report.end(), [](const std::string& line) {
      return line.find("stalls") != std::string::npos && line.find("sph.kernel = \"poly6_spiky\"") != std::string::npos;
    });
    return s;
  };
  bool noted = false;
  // rayleigh_taylor gives the pair: DFSPH's masses then follow Poly6's lattice sum (1.0069 at h = 1.97 d).
  sph::Setup s = setup("rayleigh_taylor.json", {"solver=dfsph"}, noted);
  CHECK(s.constants.dfsph_poly6_spiky == 1);
  CHECK_FALSE(sph::density_cubic_spline(s.constants));
  CHECK(s.lattice_density == Approx(1.0069).margin(5e-4));
  CHECK_FALSE(noted);
  // The cubic spline, asked or by default (two_layers gives no kernel), with the note where densities differ.
  s = setup("rayleigh_taylor.json", {"solver=dfsph", "sph.kernel=cubic_spline"}, noted);
  CHECK(s.constants.dfsph_poly6_spiky == 0);
  CHECK(s.lattice_density == Approx(0.9991).margin(5e-4));
  CHECK(noted);
  s = setup("two_layers.json", {"solver=dfsph"}, noted);
  CHECK(s.constants.dfsph_poly6_spiky == 0);
  CHECK(sph::density_cubic_spline(s.constants));
  CHECK(noted);
  s = setup("two_layers.json", {"solver=dfsph", "fluids.1.rest_density=1000"}, noted);
  CHECK_FALSE(noted);  // one rest density: nothing to stall
  // WCSPH and PBF never set it.
  s = setup("rayleigh_taylor.json", {}, noted);
  CHECK(s.constants.dfsph_poly6_spiky == 0);
  s = setup("rayleigh_taylor.json", {"solver=pbf"}, noted);
  CHECK(s.constants.dfsph_poly6_spiky == 0);
  CHECK_FALSE(noted);
}
