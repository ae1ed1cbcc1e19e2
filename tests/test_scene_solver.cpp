// The pressure solver's scene keys (src/common/scene_loader.cpp, read_solver): "solver" and the blocks
// "dfsph" and "pbf", and guided creation's refusal of a time step the incompressible solvers cannot take
// (guided_creation.cpp, check_incompressible_step). Every bad value must give a SceneError naming the
// file, the key path and what is allowed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/guided_creation.h"
#include "common/params.h"
#include "common/scene.h"
#include "scene_text.h"

using Catch::Contains;
using sph::SceneError;
using namespace scene_text;

namespace {

// The scene with "solver": solver and one more top-level member (for example a solver block).
sph::Scene parse_solver(const std::string& solver, const std::string& block = "") {
  return parse_with_extra(R"("solver": ")" + solver + "\"" + (block.empty() ? "" : ", " + block));
}

void check_dfsph_equal(const sph::DfsphConstants& a, const sph::DfsphConstants& b) {
  CHECK(a.density_tolerance == b.density_tolerance);
  CHECK(a.divergence_tolerance == b.divergence_tolerance);
  CHECK(a.min_iterations == b.min_iterations);
  CHECK(a.max_iterations == b.max_iterations);
  CHECK(a.check_every == b.check_every);
  CHECK(a.divergence_solver == b.divergence_solver);
  CHECK(a.warm_start == b.warm_start);
  CHECK(a.warm_start_fraction == b.warm_start_fraction);
  CHECK(a.chebyshev == b.chebyshev);
}

void check_pbf_equal(const sph::PbfConstants& a, const sph::PbfConstants& b) {
  CHECK(a.iterations == b.iterations);
  CHECK(a.density_tolerance == b.density_tolerance);
  CHECK(a.relaxation == b.relaxation);
  CHECK(a.scorr_k == b.scorr_k);
  CHECK(a.scorr_n == b.scorr_n);
  CHECK(a.scorr_dq == b.scorr_dq);
  CHECK(a.clamp_expansion == b.clamp_expansion);
  CHECK(a.xsph_c == b.xsph_c);
  CHECK(a.vorticity_epsilon == b.vorticity_epsilon);
  CHECK(a.jacobi_weight == b.jacobi_weight);
  CHECK(a.chebyshev == b.chebyshev);
  CHECK(a.artificial_viscosity == b.artificial_viscosity);
  CHECK(a.coarse_grid == b.coarse_grid);
  CHECK(a.coarse_iterations == b.coarse_iterations);
}

// One bad value of a block key and the words its refusal must hold.
struct BadValue {
  const char* key;      // inside the block
  const char* value;    // JSON text
  const char* allowed;  // the allowed range or type, as the message prints it
};

}  // namespace

TEST_CASE("loader: scene solver defaults to WCSPH, and the blocks to the papers' settings", "[loader][solver]") {
  const sph::Scene s = parse(SceneText{});
  REQUIRE(s.solver == sph::Solver::Wcsph);
  check_dfsph_equal(s.dfsph, sph::dfsph_defaults());
  check_pbf_equal(s.pbf, sph::pbf_defaults());
  // [BK15] section 5: eta = 0.01% of rho0, eta_v = 0.1%; [MM13] section 4: n = 4, dq in [0.1, 0.3] h, and k = 0
  // with the one-sided constraint (params.h, pbf_defaults, says why not the paper's 0.1).
  CHECK(sph::dfsph_defaults().density_tolerance == Approx(1e-4));
  CHECK(sph::dfsph_defaults().divergence_tolerance == Approx(1e-3));
  CHECK(sph::dfsph_defaults().min_iterations <= sph::dfsph_defaults().max_iterations);
  CHECK(sph::pbf_defaults().clamp_expansion == 1);
  CHECK(sph::pbf_defaults().scorr_k == 0.0f);
  CHECK(sph::pbf_defaults().scorr_n == 4);
  CHECK(sph::pbf_defaults().scorr_dq >= 0.1f);
  CHECK(sph::pbf_defaults().scorr_dq <= 0.3f);

  // Choosing a solver without its block keeps the defaults.
  const sph::Scene d = parse_solver("dfsph");
  REQUIRE(d.solver == sph::Solver::Dfsph);
  check_dfsph_equal(d.dfsph, sph::dfsph_defaults());
  const sph::Scene p = parse_solver("pbf");
  REQUIRE(p.solver == sph::Solver::Pbf);
  check_pbf_equal(p.pbf, sph::pbf_defaults());
  REQUIRE(parse_solver("wcsph").solver == sph::Solver::Wcsph);
  // An empty block is its defaults too.
  check_dfsph_equal(parse_solver("dfsph", R"("dfsph": {})").dfsph, sph::dfsph_defaults());
  for (const sph::Solver m : {sph::Solver::Wcsph, sph::Solver::Dfsph, sph::Solver::Pbf})
    REQUIRE(parse_solver(sph::solver_name(m)).solver == m);
}

TEST_CASE("loader: scene solver blocks read every key", "[loader][solver]") {
  SECTION("dfsph") {
    const sph::Scene s = parse_solver("dfsph", R"("dfsph": { "density_tolerance": 0.002, "divergence_tolerance": 0.05,
        "min_iterations": 3, "max_iterations": 40, "check_every": 5, "divergence_solver": false, "warm_start": false,
        "warm_start_fraction": 0.5, "chebyshev": 0 })");
    const sph::DfsphConstants& d = s.dfsph;
    CHECK(d.density_tolerance == Approx(0.002f));
    CHECK(d.divergence_tolerance == Approx(0.05f));
    CHECK(d.min_iterations == 3);
    CHECK(d.max_iterations == 40);
    CHECK(d.check_every == 5);
    CHECK(d.divergence_solver == 0);
    CHECK(d.warm_start == 0);
    CHECK(d.warm_start_fraction == 0.5f);
    CHECK(d.chebyshev == 0.0f);  // plain Jacobi
    // The upper ends of the ranges are allowed, and min_iterations may equal max_iterations.
    const sph::Scene e = parse_solver("dfsph", R"("dfsph": { "density_tolerance": 0.1, "divergence_tolerance": 1,
        "min_iterations": 10000, "max_iterations": 10000, "check_every": 100, "warm_start_fraction": 1 })");
    CHECK(e.dfsph.density_tolerance == Approx(0.1f));
    CHECK(e.dfsph.warm_start_fraction == 1.0f);
    CHECK(e.dfsph.min_iterations == 10000);
    CHECK(e.dfsph.check_every == 100);
  }
  SECTION("pbf") {
    const sph::Scene s = parse_solver("pbf", R"("pbf": { "iterations": 9, "density_tolerance": 0.005, "relaxation": 2.5,
        "scorr_k": 0.3, "scorr_n": 3, "scorr_dq": 0.25, "clamp_expansion": false, "xsph": 0.02,
        "vorticity_epsilon": 0.5, "jacobi_weight": 0.6, "chebyshev": 0.5, "artificial_viscosity": true,
        "coarse_grid": true, "coarse_iterations": 12 })");
    const sph::PbfConstants& b = s.pbf;
    CHECK(b.iterations == 9);
    CHECK(b.density_tolerance == Approx(0.005f));
    CHECK(b.relaxation == Approx(2.5f));
    CHECK(b.scorr_k == Approx(0.3f));
    CHECK(b.scorr_n == 3);
    CHECK(b.scorr_dq == Approx(0.25f));
    CHECK(b.clamp_expansion == 0);
    CHECK(b.xsph_c == Approx(0.02f));
    CHECK(b.vorticity_epsilon == Approx(0.5f));
    CHECK(b.jacobi_weight == Approx(0.6f));
    CHECK(b.chebyshev == Approx(0.5f));
    CHECK(b.artificial_viscosity == 1);
    CHECK(sph::pbf_defaults().artificial_viscosity == 0);  // XSPH alone unless asked
    CHECK(b.coarse_grid == 1);
    CHECK(b.coarse_iterations == 12);
    CHECK(sph::pbf_defaults().coarse_grid == 0);  // [MM13]'s iteration unless asked
    // The closed lower ends are allowed: no tolerance (always all iterations), no s_corr, no XSPH.
    const sph::Scene z = parse_solver("pbf", R"("pbf": { "density_tolerance": 0, "relaxation": 0.001, "scorr_k": 0,
        "xsph": 0, "vorticity_epsilon": 0, "jacobi_weight": 1, "chebyshev": 0 })");
    CHECK(z.pbf.density_tolerance == 0.0f);
    CHECK(z.pbf.scorr_k == 0.0f);
    CHECK(z.pbf.jacobi_weight == 1.0f);  // the paper's plain Jacobi iteration
    CHECK(z.pbf.chebyshev == 0.0f);
  }
  SECTION("through --set, as sph_run --set solver=... does") {
    const sph::Scene s = parse(SceneText{}, {"solver=pbf", "pbf.iterations=7", "pbf.clamp_expansion=false"});
    REQUIRE(s.solver == sph::Solver::Pbf);
    CHECK(s.pbf.iterations == 7);
    CHECK(s.pbf.clamp_expansion == 0);
    CHECK(s.pbf.scorr_k == sph::pbf_defaults().scorr_k);
    const sph::Scene d = parse(SceneText{}, {"solver=dfsph", "dfsph.max_iterations=1", "dfsph.min_iterations=1"});
    CHECK(d.dfsph.max_iterations == 1);
    CHECK(d.dfsph.min_iterations == 1);
  }
}

TEST_CASE("loader: scene solver values out of range are refused with the key path and the range", "[loader][solver]") {
  SECTION("dfsph") {
    const std::vector<BadValue> bad = {
        {"density_tolerance", "0", "allowed (0, 0.1]"},     {"density_tolerance", "-0.0001", "allowed (0, 0.1]"},
        {"density_tolerance", "0.5", "allowed (0, 0.1]"},   {"divergence_tolerance", "0", "allowed (0, 1]"},
        {"divergence_tolerance", "-1", "allowed (0, 1]"},   {"divergence_tolerance", "2", "allowed (0, 1]"},
        {"min_iterations", "0", "allowed [1, 10000]"},      {"max_iterations", "0", "allowed [1, 10000]"},
        {"max_iterations", "-5", "allowed [1, 10000]"},     {"max_iterations", "10001", "allowed [1, 10000]"},
        {"check_every", "0", "allowed [1, 100]"},           {"check_every", "101", "allowed [1, 100]"},
        {"max_iterations", "2.5", "expected a whole number"}, {"density_tolerance", "\"small\"", "expected a number"},
        {"divergence_solver", "1", "expected true or false"}, {"warm_start", "\"yes\"", "expected true or false"},
        {"chebyshev", "1", "allowed [0, 0.99]"},            {"chebyshev", "-0.1", "allowed [0, 0.99]"},
        {"warm_start_fraction", "0", "allowed (0, 1]"},     {"warm_start_fraction", "1.5", "allowed (0, 1]"},
    };
    for (const BadValue& b : bad) {
      INFO("dfsph." << b.key << " = " << b.value);
      REQUIRE_THROWS_WITH(parse_solver("dfsph", std::string(R"("dfsph": { ")") + b.key + "\": " + b.value + " }"),
                          Contains("test.json") && Contains(std::string("dfsph.") + b.key) && Contains(b.allowed));
    }
  }
  SECTION("pbf") {
    const std::vector<BadValue> bad = {
        {"iterations", "0", "allowed [1, 1000]"},           {"iterations", "1001", "allowed [1, 1000]"},
        {"density_tolerance", "-0.01", "allowed [0, 0.1]"}, {"density_tolerance", "0.2", "allowed [0, 0.1]"},
        {"relaxation", "0", "allowed (0, 100]"},            {"relaxation", "1000", "allowed (0, 100]"},
        {"scorr_k", "-0.1", "allowed [0, 10]"},             {"scorr_k", "11", "allowed [0, 10]"},
        {"scorr_n", "0", "allowed [1, 16]"},                {"scorr_n", "17", "allowed [1, 16]"},
        {"scorr_n", "4.5", "expected a whole number"},      {"scorr_dq", "0", "allowed (0, 1)"},
        {"scorr_dq", "1", "allowed (0, 1)"},                {"scorr_dq", "1.5", "allowed (0, 1)"},
        {"scorr_dq", "-0.2", "allowed (0, 1)"},             {"scorr_dq", "1e7", "allowed (0, 1)"},
        {"scorr_dq", "0.999999999", "allowed (0, 1)"},      {"xsph", "-0.1", "allowed [0, 1]"},
        {"xsph", "1.5", "allowed [0, 1]"},                  {"vorticity_epsilon", "-1", "allowed [0, 1000]"},
        {"vorticity_epsilon", "1e4", "allowed [0, 1000]"},  {"clamp_expansion", "0", "expected true or false"},
        {"artificial_viscosity", "\"yes\"", "expected true or false"},
        {"coarse_grid", "1", "expected true or false"},     {"coarse_iterations", "0", "allowed [1, 1000]"},
        {"coarse_iterations", "1001", "allowed [1, 1000]"}, {"coarse_iterations", "2.5", "expected a whole number"},
        {"jacobi_weight", "0", "allowed (0, 1]"},           {"jacobi_weight", "1.2", "allowed (0, 1]"},
        {"jacobi_weight", "-0.5", "allowed (0, 1]"},        {"chebyshev", "1", "allowed [0, 0.99]"},
        {"chebyshev", "-0.1", "allowed [0, 0.99]"},         {"chebyshev", "\"fast\"", "expected a number"},
    };
    for (const BadValue& b : bad) {
      INFO("pbf." << b.key << " = " << b.value);
      REQUIRE_THROWS_WITH(parse_solver("pbf", std::string(R"("pbf": { ")") + b.key + "\": " + b.value + " }"),
                          Contains("test.json") && Contains(std::string("pbf.") + b.key) && Contains(b.allowed));
    }
  }
  SECTION("non-finite values through --set") {
    REQUIRE_THROWS_WITH(parse(SceneText{}, {"solver=dfsph", "dfsph.density_tolerance=nan"}),
                        Contains("dfsph.density_tolerance") && Contains("not a finite number"));
    REQUIRE_THROWS_WITH(parse(SceneText{}, {"solver=pbf", "pbf.relaxation=inf"}),
                        Contains("pbf.relaxation") && Contains("not a finite number"));
  }
}

TEST_CASE("loader: scene solver iteration bounds must be consistent", "[loader][solver]") {
  // The message names both keys and both values: the user who lowers max_iterations alone meets the
  // default min_iterations (2), which the file does not show.
  REQUIRE_THROWS_WITH(parse_solver("dfsph", R"("dfsph": { "min_iterations": 50, "max_iterations": 10 })"),
                      Contains("test.json") && Contains("dfsph.min_iterations") && Contains("dfsph.max_iterations") &&
                          Contains("50") && Contains("10"));
  REQUIRE_THROWS_WITH(parse_solver("dfsph", R"("dfsph": { "max_iterations": 1 })"),
                      Contains("dfsph.min_iterations") && Contains("dfsph.max_iterations") && Contains("1") &&
                          Contains(std::to_string(sph::dfsph_defaults().min_iterations)));
  REQUIRE_NOTHROW(parse_solver("dfsph", R"("dfsph": { "min_iterations": 1, "max_iterations": 1 })"));
}

TEST_CASE("loader: scene solver names and blocks are checked", "[loader][solver]") {
  SECTION("an unknown solver name lists the three") {
    REQUIRE_THROWS_WITH(parse_solver("sph"), Contains("test.json") && Contains("solver") && Contains("\"sph\"") &&
                                                 Contains("\"wcsph\"") && Contains("\"dfsph\"") && Contains("\"pbf\""));
    REQUIRE_THROWS_WITH(parse_solver("DFSPH"), Contains("\"DFSPH\"") && Contains("\"dfsph\""));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("solver": 2)"), Contains("solver") && Contains("expected a string"));
    REQUIRE_THROWS_WITH(parse(SceneText{}, {"solver=iisph"}), Contains("\"iisph\"") && Contains("\"pbf\""));
  }
  SECTION("an unknown key in a block lists the allowed keys") {
    REQUIRE_THROWS_WITH(parse_solver("dfsph", R"("dfsph": { "max_iteration": 5 })"),
                        Contains("test.json") && Contains("dfsph.max_iteration") && Contains("unknown key") &&
                            Contains("density_tolerance") && Contains("divergence_tolerance") && Contains("min_iterations") &&
                            Contains("max_iterations") && Contains("check_every") && Contains("divergence_solver") &&
                            Contains("warm_start") && Contains("warm_start_fraction") && Contains("chebyshev"));
    REQUIRE_THROWS_WITH(parse_solver("pbf", R"("pbf": { "epsilon": 0.1 })"),
                        Contains("test.json") && Contains("pbf.epsilon") && Contains("unknown key") &&
                            Contains("iterations") && Contains("relaxation") && Contains("scorr_k") && Contains("scorr_n") &&
                            Contains("scorr_dq") && Contains("clamp_expansion") && Contains("xsph") &&
                            Contains("vorticity_epsilon") && Contains("jacobi_weight") && Contains("chebyshev"));
    // A solver key at the top level, outside its block, is an unknown key there.
    REQUIRE_THROWS_WITH(parse_with_extra(R"("solver": "pbf", "iterations": 4)"),
                        Contains("iterations") && Contains("unknown key") && Contains("pbf"));
  }
  SECTION("a block that is not an object") {
    REQUIRE_THROWS_WITH(parse_solver("dfsph", R"("dfsph": 5)"), Contains("dfsph") && Contains("expected a JSON object"));
    REQUIRE_THROWS_WITH(parse_solver("pbf", R"("pbf": [4])"), Contains("pbf") && Contains("expected a JSON object"));
  }
  SECTION("a block for another solver than the chosen one names both") {
    REQUIRE_THROWS_WITH(parse_solver("pbf", R"("dfsph": { "max_iterations": 50 })"),
                        Contains("test.json") && Contains("dfsph") && Contains("solver is \"pbf\""));
    REQUIRE_THROWS_WITH(parse_solver("dfsph", R"("pbf": { "iterations": 4 })"),
                        Contains("test.json") && Contains("pbf") && Contains("solver is \"dfsph\""));
    // WCSPH, chosen or by default, has no block.
    REQUIRE_THROWS_WITH(parse_solver("wcsph", R"("dfsph": {})"), Contains("dfsph") && Contains("solver is \"wcsph\""));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("pbf": { "iterations": 4 })"), Contains("pbf") && Contains("solver is \"wcsph\""));
    // Both blocks: the one that does not belong is named.
    REQUIRE_THROWS_WITH(parse_solver("dfsph", R"("dfsph": {}, "pbf": {})"), Contains("pbf") && Contains("solver is \"dfsph\""));
    // Through --set, the block for another solver is refused the same way.
    REQUIRE_THROWS_WITH(parse(SceneText{}, {"solver=pbf", "dfsph.max_iterations=50"}),
                        Contains("dfsph") && Contains("solver is \"pbf\""));
  }
}

TEST_CASE("setup: scene solver DFSPH and PBF refuse a step above sqrt(d / |g|)", "[loader][solver]") {
  // A 5 cm cube at 5 mm spacing: the bound is sqrt(0.005 / 9.81) = 22.6 ms.
  SceneText t;
  t.emitters = R"([{ "type": "box", "fluid": "water", "min": [0, 0, 0], "max": [0.05, 0.05, 0.05] }])";
  t.resolution = R"({ "spacing": 0.005 })";
  const double bound = std::sqrt(0.005 / 9.81);
  auto scene = [&](const std::string& solver, const std::string& time_step, const std::string& gravity = "[0, -9.81, 0]") {
    SceneText u = t;
    u.extra = R"("solver": ")" + solver + R"(", "time_step": )" + time_step + R"(, "gravity": )" + gravity + ", ";
    return parse(u);
  };

  SECTION("adaptive: time_step.max") {
    for (const char* solver : {"dfsph", "pbf"}) {
      INFO("solver " << solver);
      const sph::Scene s = scene(solver, R"({ "mode": "adaptive", "max": 1 })");
      REQUIRE_THROWS_AS(sph::create_setup(s, 1.0), SceneError);
      REQUIRE_THROWS_WITH(sph::create_setup(s, 1.0), Contains("test.json") && Contains("time_step.max") &&
                                                          Contains("sqrt(d / |g|)") && Contains(solver) &&
                                                          Contains("0.0225"));
      // Just below the bound is accepted, just above refused.
      REQUIRE_NOTHROW(sph::create_setup(scene(solver, R"({ "mode": "adaptive", "max": 0.0225 })"), 1.0));
      REQUIRE_THROWS_WITH(sph::create_setup(scene(solver, R"({ "mode": "adaptive", "max": 0.0227 })"), 1.0),
                          Contains("time_step.max"));
    }
    REQUIRE(bound > 0.0225);
    REQUIRE(bound < 0.0227);
  }
  SECTION("fixed: time_step.dt") {
    for (const char* solver : {"dfsph", "pbf"}) {
      INFO("solver " << solver);
      const sph::Scene s = scene(solver, R"({ "mode": "fixed", "dt": 0.05 })");
      REQUIRE_THROWS_WITH(sph::create_setup(s, 1.0), Contains("test.json") && Contains("time_step.dt") &&
                                                          Contains("sqrt(d / |g|)") && !Contains("time_step.max"));
      // PBF's dam-break target step, 4 ms, is well within the bound at this spacing.
      REQUIRE_NOTHROW(sph::create_setup(scene(solver, R"({ "mode": "fixed", "dt": 0.004 })"), 1.0));
    }
  }
  SECTION("the bound shrinks with the spacing") {
    // At 2.5 mm the bound is 16 ms: the 20 ms accepted at 5 mm is refused.
    SceneText u = t;
    u.resolution = R"({ "spacing": 0.0025 })";
    u.extra = R"("solver": "dfsph", "time_step": { "mode": "fixed", "dt": 0.02 }, )";
    REQUIRE_THROWS_WITH(sph::create_setup(parse(u), 1.0), Contains("time_step.dt") && Contains("0.0025"));
    REQUIRE_NOTHROW(sph::create_setup(scene("dfsph", R"({ "mode": "fixed", "dt": 0.02 })"), 1.0));
  }
  SECTION("no bound without gravity, and none for WCSPH (its own CFL step applies)") {
    REQUIRE_NOTHROW(sph::create_setup(scene("dfsph", R"({ "mode": "adaptive", "max": 1 })", "[0, 0, 0]"), 1.0));
    REQUIRE_NOTHROW(sph::create_setup(scene("wcsph", R"({ "mode": "adaptive", "max": 1 })"), 1.0));
  }
}

TEST_CASE("loader: PBF's coarse grid is refused where it cannot work, and its size reported", "[loader][solver]") {
  // Its walls are the analytic shapes (pbf_coarse.h, shape_excludes): boundary particles would be air to it.
  REQUIRE_THROWS_WITH(parse(SceneText{}, {"solver=pbf", "pbf.coarse_grid=true", "sph.walls=particles"}),
                      Contains("test.json") && Contains("pbf.coarse_grid") && Contains("boundary particles") &&
                          Contains("mirror"));
  REQUIRE_NOTHROW(parse(SceneText{}, {"solver=pbf", "sph.walls=particles"}));
  // Between fluids of different rest density it stirred the interface (docs/results.md): refused, naming both.
  SceneText two;
  two.fluids = R"([{ "name": "water", "rest_density": 1000, "speed_of_sound": 20 },
                   { "name": "oil", "rest_density": 800, "speed_of_sound": 20 }])";
  REQUIRE_THROWS_WITH(parse(two, {"solver=pbf", "pbf.coarse_grid=true"}),
                      Contains("test.json") && Contains("pbf.coarse_grid") && Contains("\"water\"") && Contains("\"oil\"") &&
                          Contains("800"));
  REQUIRE_NOTHROW(parse(two, {"solver=pbf"}));
  // Dense over the domain: a 30 x 30 m container at h = 2.5 cm takes 1,220 x 1,220 x 14 cells.
  SceneText wide;
  wide.boundaries = R"([{ "type": "box", "min": [0, 0, 0], "max": [30, 30, 0.3] }])";
  REQUIRE_THROWS_WITH(sph::create_setup(parse(wide, {"solver=pbf", "pbf.coarse_grid=true"}), 1.0),
                      Contains("test.json") && Contains("pbf.coarse_grid") && Contains("cells") &&
                          Contains("coarse_grid false"));
  REQUIRE_NOTHROW(sph::create_setup(parse(wide, {"solver=pbf"}), 1.0));
  const sph::Setup s = sph::create_setup(parse(SceneText{}, {"solver=pbf", "pbf.coarse_grid=true"}), 1.0);
  const bool reported = std::any_of(s.report.begin(), s.report.end(),
                                    [](const std::string& line) { return line.find("coarse grid") != std::string::npos; });
  CHECK(reported);
}
