// Viscoelastic fluids (issue 15): springs between close particles of a fluid made at the start (Clavet et al.
// 2005, thesis eq. 2.26; src/common/springs.h). A jelly cube dropped on the floor rebounds and keeps its shape
// while a water cube of the same viscosity beside it splashes (scenes/viscoelastic.json); with plasticity
// the springs yield and the jelly slumps; the spring forces conserve momentum; and springs where they cannot
// be kept are refused by name.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/springs.h"
#include "physics_helpers.h"

using namespace sph_test;
using Catch::Matchers::Contains;

namespace {

struct FallRun {
  double start[2] = {0, 0};    // centre-of-mass height of each fluid at the start [m]
  double lowest[2] = {1e9, 1e9};  // its first minimum after the fall [m]
  double rebound[2] = {0, 0};  // how far it rose after that minimum [m]
  double width_end[2] = {0, 0};  // its extent along x at the end [m]
  double top_end[2] = {0, 0};    // its 98th percentile height at the end [m]
};

FallRun run_fall(const std::vector<std::string>& overrides, double seconds) {
  sph::Simulation sim(scene_file("viscoelastic.json", overrides), cpu_factory(), seconds);
  FallRun out;
  auto centre = [&](int f) {
    const sph::ParticleState& ps = sim.particles();
    double y = 0.0;
    long n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.fluid[i] == f) {
        y += ps.pos[i].y;
        ++n;
      }
    return y / double(n);
  };
  bool fell[2] = {false, false};
  for (int f = 0; f < 2; ++f) out.start[f] = centre(f);
  while (sim.time() < seconds) {
    sim.advance();
    for (int f = 0; f < 2; ++f) {
      const double y = centre(f);
      if (!fell[f]) {
        if (y < out.lowest[f]) out.lowest[f] = y;
        else if (y > out.lowest[f] + 1e-4) fell[f] = true;  // past its first minimum
      }
      if (fell[f]) out.rebound[f] = std::max(out.rebound[f], y - out.lowest[f]);
    }
  }
  const sph::ParticleState& ps = sim.particles();
  for (int f = 0; f < 2; ++f) {
    std::vector<double> x, y;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.fluid[i] == f) {
        x.push_back(ps.pos[i].x);
        y.push_back(ps.pos[i].y);
      }
    std::sort(y.begin(), y.end());
    out.width_end[f] = *std::max_element(x.begin(), x.end()) - *std::min_element(x.begin(), x.end());
    out.top_end[f] = y[std::size_t(0.98 * double(y.size() - 1))];
  }
  return out;
}

}  // namespace

namespace {

// The fall of scenes/viscoelastic.json under the solver `sets` choose: the jelly bounces (measured 0.62 of its
// fall under WCSPH), the water's centre rises a little as it splashes up the walls, the jelly keeps its
// shape (a 0.054 m lattice cube) and the water spreads across the tank.
void check_jelly_and_water(const std::vector<std::string>& sets) {
  const FallRun r = run_fall(sets, 0.4);
  const double fall_jelly = r.start[0] - r.lowest[0], fall_water = r.start[1] - r.lowest[1];
  INFO("jelly: centre " << r.start[0] << " -> " << r.lowest[0] << " m, rebound " << r.rebound[0] << " m, width at the end "
                        << r.width_end[0] << " m; water: centre " << r.start[1] << " -> " << r.lowest[1] << " m, rebound "
                        << r.rebound[1] << " m, width " << r.width_end[1] << " m");
  CHECK(r.rebound[0] > 0.25 * fall_jelly);
  CHECK(r.rebound[1] < 0.15 * fall_water);
  CHECK(r.width_end[0] < 1.25 * 0.054);
  CHECK(r.width_end[1] > 3.0 * 0.054);
}

}  // namespace

TEST_CASE("a jelly cube rebounds from the floor where a water cube of the same viscosity splashes", "[viscoelastic]") {
  check_jelly_and_water({});
}

TEST_CASE("under DFSPH the jelly rebounds too, at its step's spring limit", "[viscoelastic][dfsph]") {
  // DFSPH advances the springs explicitly, at a step below 2 / omega_max (time_step.h, springs.h: spring_rate).
  check_jelly_and_water({"solver=dfsph"});
}

TEST_CASE("under PBF the jelly rebounds too, its springs an external force at the spring limit", "[viscoelastic][pbf]") {
  // PBF adds the springs to gravity before its prediction (solvers/pbf.h), at the same step limit as DFSPH.
  check_jelly_and_water({"solver=pbf"});
}

TEST_CASE("the springs' frequency bound holds on a block of the lattice's network and is tight", "[viscoelastic]") {
  // The stiffness matrix of a 7^3 lattice block with the springs of spring_law (free ends, one mass): its
  // largest eigenvalue omega_max^2 by power iteration, against spring_rate, the infinite lattice's bound.
  const double d = 0.01, h = 1.97 * d, modulus = 2e4, mass = 1000.0 * d * d * d;
  const sph::SpringLaw law = sph::spring_law(modulus, d, h);
  const double rate = sph::spring_rate(law.stiffness / mass, law.exponent, d, h);
  const int n = 7;
  std::vector<std::array<double, 3>> x;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) x.push_back({i * d, j * d, k * d});
  struct Bond { std::size_t a, b; double k; std::array<double, 3> e; };
  std::vector<Bond> bonds;
  for (std::size_t a = 0; a < x.size(); ++a)
    for (std::size_t b = a + 1; b < x.size(); ++b) {
      std::array<double, 3> e{x[b][0] - x[a][0], x[b][1] - x[a][1], x[b][2] - x[a][2]};
      const double r = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      if (!(r < h)) continue;
      for (double& v : e) v /= r;
      bonds.push_back({a, b, law.stiffness * std::pow(d / r, law.exponent) / mass, e});
    }
  std::vector<double> v(3 * x.size()), w(3 * x.size());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& c : v) c = u(rng);
  double lambda = 0.0;
  for (int it = 0; it < 400; ++it) {
    std::fill(w.begin(), w.end(), 0.0);
    for (const Bond& bd : bonds) {  // (K / m) v: each bond k e e^T (v_a - v_b) on a, the opposite on b
      double s = 0.0;
      for (int c = 0; c < 3; ++c) s += bd.e[c] * (v[3 * bd.a + c] - v[3 * bd.b + c]);
      for (int c = 0; c < 3; ++c) {
        w[3 * bd.a + c] += bd.k * s * bd.e[c];
        w[3 * bd.b + c] -= bd.k * s * bd.e[c];
      }
    }
    double norm = 0.0, vw = 0.0, vv = 0.0;
    for (std::size_t c = 0; c < w.size(); ++c) norm += w[c] * w[c], vw += v[c] * w[c], vv += v[c] * v[c];
    lambda = vw / vv;
    norm = std::sqrt(norm);
    for (std::size_t c = 0; c < w.size(); ++c) v[c] = w[c] / norm;
  }
  INFO("omega_max " << std::sqrt(lambda) << " 1/s, bound " << rate << " 1/s");
  CHECK(std::sqrt(lambda) <= rate);
  CHECK(std::sqrt(lambda) > 0.9 * rate);  // measured 0.96: the block's surface has fewer bonds
}

TEST_CASE("springs that yield let the jelly slump", "[viscoelastic]") {
  // A softer jelly (3 kPa: its weight strains it by about 20%), elastic and with springs that yield beyond 2%.
  const FallRun elastic = run_fall({"fluids.0.spring_modulus=3000", "fluids.0.spring_yield=0.02"}, 0.6);
  const FallRun plastic = run_fall({"fluids.0.spring_modulus=3000", "fluids.0.spring_yield=0.02",
                                    "fluids.0.spring_plasticity=20"}, 0.6);
  INFO("jelly's top at 0.6 s: elastic " << elastic.top_end[0] << " m, plastic " << plastic.top_end[0] << " m; widths "
                                        << elastic.width_end[0] << " and " << plastic.width_end[0] << " m");
  CHECK(plastic.top_end[0] < elastic.top_end[0] - 0.005);
  CHECK(plastic.width_end[0] > elastic.width_end[0]);
}

TEST_CASE("spring forces conserve momentum", "[viscoelastic][conservation]") {
  sph::Scene scene = scene_file("viscoelastic.json", {"gravity=[0,0,0]", "fluids.0.artificial_viscosity=0",
                                                      "fluids.0.viscosity=0", "fluids.1.artificial_viscosity=0",
                                                      "fluids.1.viscosity=0"});
  scene.boundaries.clear();
  const sph::Setup setup = sph::create_setup(scene, 1.0);
  REQUIRE(setup.springs.capacity > 0);
  sph::CpuBackend cpu(setup.constants);
  cpu.set_springs(setup.springs);
  sph::ParticleState ps = setup.particles;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t i = 0; i < ps.size(); ++i) ps.vel[i] = sph::Vec3{0.3f * u(rng), 0.3f * u(rng), 0.3f * u(rng)};
  cpu.upload(ps);
  cpu.initialise_forces();
  auto momentum = [&](double& scale) {
    const sph::ParticleState& s = cpu.download();
    double p[3] = {0, 0, 0};
    scale = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double m = setup.constants.fluids[s.fluid[i]].mass;
      p[0] += m * s.vel[i].x;
      p[1] += m * s.vel[i].y;
      p[2] += m * s.vel[i].z;
      scale += m * sph::length(s.vel[i]);
    }
    return std::vector<double>{p[0], p[1], p[2]};
  };
  double scale0 = 0.0, scale1 = 0.0;
  const std::vector<double> p0 = momentum(scale0);
  for (int step = 0; step < 300; ++step) cpu.step(2e-4f);
  const std::vector<double> p1 = momentum(scale1);
  // With plasticity 0 no rest length may change, however the springs are strained (compared after the run).
  const sph::SpringNetwork after = cpu.download_springs();
  double stretched = 0.0;
  for (std::size_t k = 0; k < after.rest.size(); ++k)
    if (after.partner[k] >= 0) stretched = std::max(stretched, double(std::fabs(after.rest[k] - setup.springs.rest[k])));
  INFO("momentum " << p0[0] << ", " << p0[1] << ", " << p0[2] << " -> " << p1[0] << ", " << p1[1] << ", " << p1[2]);
  for (int k = 0; k < 3; ++k) CHECK(std::fabs(p1[k] - p0[k]) < 1e-4 * scale0);
  CHECK(stretched == 0.0);  // plasticity 0: rest lengths never change
}

TEST_CASE("springs where they cannot be kept are refused by name", "[viscoelastic][scene]") {
  CHECK_THROWS_WITH(sph::create_setup(scene_file("viscoelastic.json", {"fluids.0.spring_modulus=2e5"}), 1.0),
                    Contains("fluids.0.spring_modulus") && Contains("at most 100000"));
  // DFSPH's step has a limit of the springs' own: the stiffer jelly is taken there.
  const sph::Setup stiff = sph::create_setup(scene_file("viscoelastic.json", {"solver=dfsph", "fluids.0.spring_modulus=2e5"}), 1.0);
  CHECK(stiff.spring_rate > 0.0);
  // A fixed step, or a least step, above the springs' limit would override it: refused with the bound.
  CHECK_THROWS_WITH(sph::create_setup(scene_file("viscoelastic.json", {"solver=dfsph", "time_step.mode=fixed",
                                                                      "time_step.dt=0.001"}), 1.0),
                    Contains("time_step.dt") && Contains("springs") && Contains("adaptive"));
  CHECK_THROWS_WITH(sph::create_setup(scene_file("viscoelastic.json", {"solver=dfsph", "time_step.min=0.001"}), 1.0),
                    Contains("time_step.min") && Contains("springs"));
  // Where the springs hold the adaptive step, the set-up says how far (and, under PBF, that the scene's
  // artificial and laminar viscosities are not applied).
  const sph::Setup pbf = sph::create_setup(scene_file("viscoelastic.json", {"solver=pbf"}), 1.0);
  const auto reports = [&](const char* text) {
    return std::any_of(pbf.report.begin(), pbf.report.end(),
                       [&](const std::string& line) { return line.find(text) != std::string::npos; });
  };
  CHECK(reports("hold the step at or below"));
  CHECK(reports("fluids.0.artificial_viscosity"));
  // PBF keeps the same limit: its frame-sized steps are refused with springs.
  CHECK_THROWS_WITH(sph::create_setup(scene_file("viscoelastic.json", {"solver=pbf", "time_step.mode=fixed",
                                                                      "time_step.dt=0.004"}), 1.0),
                    Contains("time_step.dt") && Contains("springs") && Contains("pbf"));
  CHECK_THROWS_WITH(scene_file("viscoelastic.json", {"fluids.0.spring_modulus=-1"}), Contains("fluids.0.spring_modulus"));
  CHECK_THROWS_WITH(scene_file("viscoelastic.json", {"fluids.0.spring_yield=-0.1"}), Contains("fluids.0.spring_yield"));
  // Too few neighbours for bonds off the axes: no shear to calibrate, refused by name.
  CHECK_THROWS_WITH(sph::create_setup(scene_file("viscoelastic.json", {"resolution.neighbours=8"}), 1.0),
                    Contains("fluids.0.spring_modulus") && Contains("sqrt(2)"));
}
