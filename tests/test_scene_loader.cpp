// Scene loading (src/common/scene_loader.cpp) and guided creation's refusals (guided_creation.cpp).
// The shipped scenes must load; every kind of bad input must give a SceneError whose message names the
// file and the key and says what is allowed, never a crash, a silent default or a huge allocation.
// The pressure solver's keys ("solver", "dfsph", "pbf") are tested in test_scene_solver.cpp.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "common/guided_creation.h"
#include "common/particle_state.h"
#include "common/scene.h"
#include "scene_text.h"

namespace fs = std::filesystem;
using Catch::Contains;
using sph::SceneError;

using namespace scene_text;

TEST_CASE("loader: the base test scene is valid", "[loader]") {
  const sph::Scene s = parse(SceneText{});
  REQUIRE(s.source == "test.json");
  REQUIRE(s.fluids.size() == 1);
  REQUIRE(s.emitters.size() == 1);
  REQUIRE(s.boundaries.size() == 1);
  REQUIRE(s.particles_across == 8);
  REQUIRE(s.spacing == 0.0);
  // Defaults in code (scene.h) are filled in.
  REQUIRE(s.integrator == sph::Integrator::ModifiedVelocityVerlet);
  REQUIRE(s.neighbours == 32.0);
  REQUIRE(s.gravity[1] == Approx(-9.81));
  REQUIRE(s.boundaries[0].shape.type == sph::ShapeType::Box);
  REQUIRE(s.boundaries[0].shape.keep_inside == 1);
  // "comment" is accepted anywhere as documentation.
  REQUIRE_NOTHROW(parse_with_extra(R"("comment": "a note")"));
}

TEST_CASE("loader: every shipped scene loads and sets up", "[loader]") {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(scenes_dir()))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  REQUIRE(files.size() >= 3);
  for (const fs::path& f : files) {
    INFO("scene file " << f.string());
    sph::Scene s;
    REQUIRE_NOTHROW(s = sph::load_scene(f.string()));
    REQUIRE(s.source == f.string());
    REQUIRE_FALSE(s.fluids.empty());
    REQUIRE_FALSE(s.emitters.empty());
    REQUIRE((s.particles_across > 0) != (s.spacing > 0.0));
    REQUIRE(s.run_time > 0.0);
    sph::Setup setup;
    REQUIRE_NOTHROW(setup = sph::create_setup(s, s.run_time));
    REQUIRE(setup.particles.size() + setup.jets.size() > 0);
    REQUIRE(double(setup.particles.size()) <= s.max_particles);
    REQUIRE(setup.h > setup.spacing);
  }
}

TEST_CASE("loader: shipped scenes carry the values their descriptions promise", "[loader]") {
  const sph::Scene dam = sph::load_scene(scenes_dir() + "/dam_break.json");
  REQUIRE(dam.name == "dam_break");
  REQUIRE(dam.fluids.at(0).name == "water");
  REQUIRE(dam.fluids.at(0).artificial_viscosity == Approx(0.05));
  REQUIRE(dam.viscosity == sph::ViscosityModel::Artificial);
  REQUIRE(dam.clamp_negative_pressure);
  REQUIRE(dam.emitters.at(0).max[0] == Approx(0.05715));
  REQUIRE(dam.emitters.at(0).max[1] == Approx(2 * 0.05715));
  REQUIRE(dam.boundaries.size() == 1);
  REQUIRE(dam.time_step.mode == sph::TimeStepMode::Adaptive);

  // Thesis 5.2: 16^3 = 4096 particles, n_avg 27, dt 1 ms, no gravity, no boundary.
  const sph::Scene cube = sph::load_scene(scenes_dir() + "/thesis_perf_cube.json");
  REQUIRE(cube.particles_across == 16);
  REQUIRE(cube.neighbours == 27.0);
  REQUIRE(cube.boundaries.empty());
  REQUIRE(cube.gravity == sph::Vec3d{0.0, 0.0, 0.0});
  REQUIRE(cube.time_step.mode == sph::TimeStepMode::Fixed);
  REQUIRE(cube.time_step.dt == Approx(1e-3));
  REQUIRE(cube.fluids.at(0).speed_of_sound == Approx(10.0));
  REQUIRE(cube.fluids.at(0).viscosity == Approx(10.0));
  REQUIRE(cube.pressure_form == sph::PressureForm::Mueller);
  const sph::Setup setup = sph::create_setup(cube, cube.run_time);
  REQUIRE(setup.particles.size() == 4096);
}

TEST_CASE("loader: malformed JSON is a SceneError naming the file", "[loader]") {
  REQUIRE_THROWS_AS(sph::parse_scene(R"({ "name": )", "bad.json"), SceneError);
  REQUIRE_THROWS_WITH(sph::parse_scene(R"({ "name": )", "bad.json"),
                      Contains("bad.json") && Contains("not valid JSON"));
  // Trailing comma, single quotes, NaN literal: all invalid JSON.
  REQUIRE_THROWS_WITH(sph::parse_scene(R"({ "name": "x", })", "bad.json"), Contains("not valid JSON"));
  REQUIRE_THROWS_WITH(sph::parse_scene(R"({ 'name': 'x' })", "bad.json"), Contains("not valid JSON"));
  REQUIRE_THROWS_WITH(sph::parse_scene(R"({ "gravity": [0, NaN, 0] })", "bad.json"), Contains("not valid JSON"));
  REQUIRE_THROWS_WITH(sph::parse_scene("", "empty.json"), Contains("empty.json") && Contains("not valid JSON"));
  // A file on disk.
  const std::string path = data_dir() + "/malformed.json";
  REQUIRE_THROWS_WITH(sph::load_scene(path), Contains(path) && Contains("not valid JSON"));
  // Valid JSON that is not an object.
  REQUIRE_THROWS_WITH(sph::parse_scene("[1, 2, 3]", "array.json"), Contains("array.json") && Contains("expected a JSON object"));
}

TEST_CASE("loader: numbers too large for a double are a SceneError, not a stray JSON exception", "[loader]") {
  // nlohmann::json reports 1e400 as out_of_range (error 406), not as a parse_error.
  SceneText t;
  t.fluids = R"([{ "name": "water", "speed_of_sound": 1e400 }])";
  CHECK_THROWS_AS(parse(t), SceneError);
  CHECK_THROWS_WITH(parse(t), Contains("test.json"));
  // The same number given through --set.
  CHECK_THROWS_WITH(parse(SceneText{}, {"fluids.0.speed_of_sound=1e400"}),
                      Contains("test.json") && Contains("fluids.0.speed_of_sound"));
}

TEST_CASE("loader: a missing scene file is a SceneError naming the path", "[loader]") {
  const std::string path = data_dir() + "/no_such_scene.json";
  REQUIRE_THROWS_AS(sph::load_scene(path), SceneError);
  REQUIRE_THROWS_WITH(sph::load_scene(path), Contains(path) && Contains("cannot open"));
  // A directory is not a scene file either.
  REQUIRE_THROWS_AS(sph::load_scene(data_dir()), SceneError);
}

TEST_CASE("loader: unknown keys are refused and the allowed keys listed", "[loader]") {
  SECTION("top level") {
    REQUIRE_THROWS_WITH(parse_with_extra(R"("gravityy": [0, 0, 0])"),
                        Contains("test.json") && Contains("gravityy") && Contains("unknown key") &&
                            Contains("allowed") && Contains("gravity") && Contains("time_step") && Contains("fluids"));
    const std::string path = data_dir() + "/unknown_key.json";
    REQUIRE_THROWS_WITH(sph::load_scene(path), Contains(path) && Contains("unknown key") && Contains("integrator"));
  }
  SECTION("in a fluid") {
    REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "name": "water", "viscosty": 0.1 })"),
                        Contains("fluids.0.viscosty") && Contains("unknown key") && Contains("viscosity") &&
                            Contains("rest_density"));
  }
  SECTION("in an emitter") {
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "min": [0,0,0], "max": [1,1,1], "radius": 2 })"),
                        Contains("emitters.0.radius") && Contains("unknown key") && Contains("velocity"));
  }
  SECTION("in a boundary") {
    REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "plane", "point": [0,0,0], "normal": [0,1,0], "bouncy": 1 })"),
                        Contains("boundaries.0.bouncy") && Contains("bounce") && Contains("slip"));
  }
  SECTION("in resolution, sph, time_step, run, limits, domain") {
    REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": 8, "neighbors": 30 })"),
                        Contains("resolution.neighbors") && Contains("neighbours"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("sph": { "eos": "tait" })"),
                        Contains("sph.eos") && Contains("equation_of_state"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("time_step": { "dt_max": 0.01 })"),
                        Contains("time_step.dt_max") && Contains("max") && Contains("cfl_sound"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("run": { "steps": 10 })"), Contains("run.steps") && Contains("frames_every"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("limits": { "max_particle": 10 })"),
                        Contains("limits.max_particle") && Contains("max_particles"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("domain": { "min": [0,0,0], "max": [1,1,1], "periodic": true })"),
                        Contains("domain.periodic") && Contains("unknown key"));
  }
  SECTION("keys of a different shape type") {
    // "radius" belongs to spheres, not boxes.
    REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "box", "min": [0,0,0], "max": [1,1,1], "radius": 1 })"),
                        Contains("boundaries.0.radius") && Contains("open_top"));
  }
}

TEST_CASE("loader: unknown names are refused and the allowed names listed", "[loader]") {
  REQUIRE_THROWS_WITH(parse_with_extra(R"("integrator": "rk4")"),
                      Contains("test.json") && Contains("integrator") && Contains("\"rk4\"") &&
                          Contains("explicit_euler") && Contains("semi_implicit_euler") && Contains("velocity_verlet") &&
                          Contains("modified_velocity_verlet") && Contains("leapfrog"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("sph": { "viscosity": "xsph" })"),
                      Contains("sph.viscosity") && Contains("none") && Contains("mueller") && Contains("morris") &&
                          Contains("artificial"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("sph": { "density": "sum" })"), Contains("sph.density") && Contains("continuity"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("sph": { "equation_of_state": "cole" })"),
                      Contains("sph.equation_of_state") && Contains("tait") && Contains("ideal"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("sph": { "pressure_force": "symmetric" })"),
                      Contains("sph.pressure_force") && Contains("monaghan"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("sph": { "negative_pressure": "zero" })"),
                      Contains("sph.negative_pressure") && Contains("keep") && Contains("clamp"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("time_step": { "mode": "auto" })"),
                      Contains("time_step.mode") && Contains("fixed") && Contains("adaptive"));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "cone", "min": [0,0,0], "max": [1,1,1] })"),
                      Contains("emitters.0.type") && Contains("box") && Contains("sphere") && Contains("jet"));
  REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "cylinder" })"),
                      Contains("boundaries.0.type") && Contains("plane") && Contains("quadric"));
  REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": 8, "mass": "lattice" })"),
                      Contains("resolution.mass") && Contains("rest_density") && Contains("volume"));
  // Names are case sensitive.
  REQUIRE_THROWS_WITH(parse_with_extra(R"("integrator": "Leapfrog")"), Contains("leapfrog"));
}

TEST_CASE("loader: wrong JSON types are refused with the expected type", "[loader]") {
  REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "rest_density": "1000" })"),
                      Contains("fluids.0.rest_density") && Contains("expected a number") && Contains("string"));
  REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "viscosity": null })"),
                      Contains("fluids.0.viscosity") && Contains("expected a number"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("gravity": [0, -9.81])"), Contains("gravity") && Contains("array of 3 numbers"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("gravity": [0, "down", 0])"), Contains("gravity") && Contains("array of 3 numbers"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("gravity": -9.81)"), Contains("gravity") && Contains("array of 3 numbers"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("integrator": 3)"), Contains("integrator") && Contains("expected a string"));
  REQUIRE_THROWS_WITH(parse_with_extra(R"("description": ["a", "b"])"), Contains("description") && Contains("expected a string"));
  REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "box", "min": [0,0,0], "max": [1,1,1], "open_top": "yes" })"),
                      Contains("boundaries.0.open_top") && Contains("true or false"));
  REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": 10.5 })"),
                      Contains("resolution.particles_across") && Contains("whole number"));
  REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": "10" })"),
                      Contains("resolution.particles_across") && Contains("whole number"));
  REQUIRE_THROWS_WITH(parse_with_resolution("20"), Contains("resolution") && Contains("expected a JSON object"));
  SceneText t;
  t.fluids = R"({ "name": "water" })";
  REQUIRE_THROWS_WITH(parse(t), Contains("fluids") && Contains("list"));
  t = SceneText{};
  t.fluids = "[]";
  REQUIRE_THROWS_WITH(parse(t), Contains("fluids") && Contains("non-empty"));
  t = SceneText{};
  t.emitters = "[]";
  REQUIRE_THROWS_WITH(parse(t), Contains("emitters") && Contains("non-empty"));
  t = SceneText{};
  t.emitters = R"(["box"])";
  REQUIRE_THROWS_WITH(parse(t), Contains("emitters.0") && Contains("expected a JSON object"));
  t = SceneText{};
  t.boundaries = R"({ "type": "box" })";
  REQUIRE_THROWS_WITH(parse(t), Contains("boundaries") && Contains("list"));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "fluid": true, "min": [0,0,0], "max": [1,1,1] })"),
                      Contains("emitters.0.fluid") && Contains("fluid name or an integer index"));
}

TEST_CASE("loader: required members are named when missing", "[loader]") {
  REQUIRE_THROWS_WITH(sph::parse_scene(R"({ "name": "x" })", "test.json"), Contains("fluids") && Contains("is required"));
  REQUIRE_THROWS_WITH(sph::parse_scene(R"({ "fluids": [{}], "emitters": [{ "type": "box", "min": [0,0,0], "max": [1,1,1] }] })",
                                       "test.json"),
                      Contains("resolution") && Contains("is required"));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "min": [0,0,0], "max": [1,1,1] })"),
                      Contains("emitters.0.type") && Contains("is required"));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "min": [0,0,0] })"),
                      Contains("emitters.0.max") && Contains("is required"));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "sphere", "center": [0,0,0] })"),
                      Contains("emitters.0.radius") && Contains("is required"));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "jet", "position": [0,0,0], "radius": 0.01 })"),
                      Contains("emitters.0.speed") && Contains("is required"));
  REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "plane", "point": [0,0,0] })"),
                      Contains("boundaries.0.normal") && Contains("is required"));
  REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "quadric" })"),
                      Contains("boundaries.0.matrix") && Contains("is required"));
}

TEST_CASE("loader: zero, negative, non-finite and absurd sizes are refused with the allowed range", "[loader]") {
  SECTION("sphere radius") {
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "sphere", "center": [0,0,0], "radius": -0.1 })"),
                        Contains("emitters.0.radius") && Contains("out of range") && Contains("allowed"));
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "sphere", "center": [0,0,0], "radius": 0 })"),
                        Contains("emitters.0.radius") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "sphere", "center": [0,0,0], "radius": -1 })"),
                        Contains("boundaries.0.radius") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "sphere", "center": [0,0,0], "radius": 1e12 })"),
                        Contains("emitters.0.radius") && Contains("out of range"));
  }
  SECTION("boxes with max <= min") {
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "min": [0,0,0], "max": [1,0,1] })"),
                        Contains("emitters.0.max") && Contains("larger than min"));
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "min": [0,0,0], "max": [1,1,-1] })"),
                        Contains("emitters.0.max") && Contains("larger than min"));
    REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "box", "min": [0,1,0], "max": [1,0.5,1] })"),
                        Contains("boundaries.0.max") && Contains("larger than min"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("domain": { "min": [0,0,0], "max": [0,0,0] })"),
                        Contains("domain.max") && Contains("larger than min"));
  }
  SECTION("fluid properties") {
    REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "speed_of_sound": 0 })"),
                        Contains("fluids.0.speed_of_sound") && Contains("out of range") && Contains("(0, "));
    REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "rest_density": -1000 })"),
                        Contains("fluids.0.rest_density") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "rest_density": 1e9 })"),
                        Contains("fluids.0.rest_density") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "viscosity": -0.001 })"),
                        Contains("fluids.0.viscosity") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_fluid(R"({ "xsph": 2 })"), Contains("fluids.0.xsph") && Contains("[0, 1]"));
  }
  SECTION("resolution") {
    REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "spacing": -1 })"),
                        Contains("resolution.spacing") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "spacing": 0 })"),
                        Contains("resolution.spacing") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": 1 })"),
                        Contains("resolution.particles_across") && Contains("out of range") && Contains("[2, 100000]"));
    REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": 1000000000 })"),
                        Contains("resolution.particles_across") && Contains("out of range") && Contains("[2, 100000]"));
    REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": -5 })"),
                        Contains("resolution.particles_across") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": 8, "neighbours": 1 })"),
                        Contains("resolution.neighbours") && Contains("out of range"));
  }
  SECTION("time step, run, limits, geometry") {
    REQUIRE_THROWS_WITH(parse_with_extra(R"("time_step": { "dt": 0 })"), Contains("time_step.dt") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("time_step": { "dt": -0.001 })"), Contains("time_step.dt") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("time_step": { "dt": 100 })"), Contains("time_step.dt") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("time_step": { "min": 0.01, "max": 0.001 })"),
                        Contains("time_step.min") && Contains("time_step.max"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("run": { "time": 0 })"), Contains("run.time") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("limits": { "max_particles": 0 })"),
                        Contains("limits.max_particles") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_extra(R"("gravity": [0, -1e5, 0])"), Contains("gravity") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "min": [0,0,0], "max": [1e7,1,1] })"),
                        Contains("emitters.0.max") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "box", "min": [0,0,0], "max": [1,1,1], "bounce": 1.5 })"),
                        Contains("boundaries.0.bounce") && Contains("[0, 1]"));
    REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "box", "min": [0,0,0], "max": [1,1,1], "slip": -0.5 })"),
                        Contains("boundaries.0.slip") && Contains("[0, 1]"));
    REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "plane", "point": [0,0,0], "normal": [0,0,0] })"),
                        Contains("boundaries.0.normal") && Contains("zero vector"));
    REQUIRE_THROWS_WITH(
        parse_with_emitter(R"({ "type": "jet", "position": [0,0,0], "direction": [0,0,0], "radius": 0.01, "speed": 1 })"),
        Contains("emitters.0.direction") && Contains("zero vector"));
    REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "jet", "position": [0,0,0], "radius": 0.01, "speed": 1,
                                               "start": 2, "stop": 1 })"),
                        Contains("emitters.0.stop") && Contains("later than start"));
  }
  SECTION("NaN-like and overflowing values given through --set are not finite numbers") {
    SceneText t;
    for (const char* v : {"NaN", "inf", "-Infinity", "1e400", "-1e400"})
      REQUIRE_THROWS_WITH(parse(t, {std::string("fluids.0.viscosity=") + v}),
                          Contains("fluids.0.viscosity") && Contains(std::string(v) + " is not a finite number"));
  }
  SECTION("numbers that JSON does not read are read as numbers through --set") {
    SceneText t;
    REQUIRE(parse(t, {"fluids.0.viscosity=.5"}).fluids[0].viscosity == Approx(0.5));
    REQUIRE(parse(t, {"fluids.0.viscosity=+2"}).fluids[0].viscosity == Approx(2.0));
  }
}

TEST_CASE("loader: resolution needs exactly one of particles_across and spacing", "[loader]") {
  REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "particles_across": 8, "spacing": 0.01 })"),
                      Contains("resolution") && Contains("exactly one of particles_across and spacing"));
  REQUIRE_THROWS_WITH(parse_with_resolution(R"({ "neighbours": 30 })"),
                      Contains("resolution") && Contains("exactly one of particles_across and spacing"));
  const sph::Scene s = parse_with_resolution(R"({ "spacing": 0.01, "neighbours": 30 })");
  REQUIRE(s.spacing == Approx(0.01));
  REQUIRE(s.particles_across == 0);
  REQUIRE(s.neighbours == Approx(30.0));
}

TEST_CASE("loader: emitters must reference an existing fluid", "[loader]") {
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "fluid": "oil", "min": [0,0,0], "max": [1,1,1] })"),
                      Contains("test.json") && Contains("emitters.0.fluid") && Contains("no fluid named \"oil\""));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "fluid": 1, "min": [0,0,0], "max": [1,1,1] })"),
                      Contains("emitters.0.fluid") && Contains("does not name a fluid"));
  REQUIRE_THROWS_WITH(parse_with_emitter(R"({ "type": "box", "fluid": -1, "min": [0,0,0], "max": [1,1,1] })"),
                      Contains("emitters.0.fluid") && Contains("does not name a fluid"));
  // By name and by index, with two fluids.
  SceneText t;
  t.fluids = R"([{ "name": "water" }, { "name": "oil", "rest_density": 900 }])";
  t.emitters = R"([{ "type": "box", "fluid": "oil", "min": [0,0,0], "max": [0.1,0.1,0.1] },
                   { "type": "box", "fluid": 0, "min": [0.2,0,0], "max": [0.3,0.1,0.1] }])";
  const sph::Scene s = parse(t);
  REQUIRE(s.emitters.at(0).fluid == 1);
  REQUIRE(s.emitters.at(1).fluid == 0);
}

TEST_CASE("loader: quadric boundaries must be symmetric 4x4 matrices", "[loader]") {
  const std::string sphere = R"([[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,-0.01]])";
  const sph::Scene s = parse_with_boundary(R"({ "type": "quadric", "matrix": )" + sphere + " }");
  REQUIRE(s.boundaries.at(0).shape.type == sph::ShapeType::Quadric);
  REQUIRE(s.boundaries.at(0).shape.q[15] == Approx(-0.01));
  REQUIRE_THROWS_WITH(
      parse_with_boundary(R"({ "type": "quadric", "matrix": [[1,0,0,0.5],[0,1,0,0],[0,0,1,0],[0,0,0,-0.01]] })"),
      Contains("boundaries.0.matrix") && Contains("symmetric"));
  REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "quadric", "matrix": [[1,0,0],[0,1,0],[0,0,1]] })"),
                      Contains("boundaries.0.matrix") && Contains("4 rows of 4"));
  REQUIRE_THROWS_WITH(parse_with_boundary(R"({ "type": "quadric", "matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,"x"]] })"),
                      Contains("boundaries.0.matrix") && Contains("numbers"));
}

TEST_CASE("loader: --set overrides change values before validation", "[loader]") {
  const SceneText t;
  SECTION("numbers, names, nested paths") {
    const sph::Scene s = parse(t, {"fluids.0.viscosity=0.5", "integrator=leapfrog", "resolution.particles_across=12",
                                   "gravity=[0,0,0]", "time_step.mode=fixed", "boundaries.0.bounce=0.25"});
    REQUIRE(s.fluids.at(0).viscosity == Approx(0.5));
    REQUIRE(s.integrator == sph::Integrator::Leapfrog);
    REQUIRE(s.particles_across == 12);
    REQUIRE(s.gravity == sph::Vec3d{0.0, 0.0, 0.0});
    REQUIRE(s.time_step.mode == sph::TimeStepMode::Fixed);
    REQUIRE(s.boundaries.at(0).shape.bounce == Approx(0.25f));
    // Untouched values keep the file's values.
    REQUIRE(s.fluids.at(0).speed_of_sound == Approx(20.0));
  }
  SECTION("a missing object on the path is created") {
    const sph::Scene s = parse(t, {"sph.viscosity=morris"});
    REQUIRE(s.viscosity == sph::ViscosityModel::Morris);
  }
  SECTION("later overrides win") {
    const sph::Scene s = parse(t, {"fluids.0.viscosity=0.5", "fluids.0.viscosity=0.25"});
    REQUIRE(s.fluids.at(0).viscosity == Approx(0.25));
  }
  SECTION("overrides of a shipped scene") {
    const sph::Scene s = sph::load_scene(scenes_dir() + "/dam_break.json", {"time_step.mode=fixed", "time_step.dt=0.05"});
    REQUIRE(s.time_step.mode == sph::TimeStepMode::Fixed);
    REQUIRE(s.time_step.dt == Approx(0.05));
  }
  SECTION("overridden values are validated like the file's") {
    REQUIRE_THROWS_WITH(parse(t, {"integrator=rk4"}), Contains("integrator") && Contains("leapfrog"));
    REQUIRE_THROWS_WITH(parse(t, {"fluids.0.speed_of_sound=0"}),
                        Contains("fluids.0.speed_of_sound") && Contains("out of range"));
    REQUIRE_THROWS_WITH(parse(t, {"fluids.0.viscosty=0.5"}), Contains("fluids.0.viscosty") && Contains("unknown key"));
    REQUIRE_THROWS_WITH(parse(t, {"resolution.spacing=0.01"}), Contains("exactly one of particles_across and spacing"));
  }
  SECTION("bad paths and malformed overrides") {
    REQUIRE_THROWS_AS(parse(t, {"fluids.3.viscosity=0.5"}), SceneError);
    REQUIRE_THROWS_WITH(parse(t, {"fluids.3.viscosity=0.5"}),
                        Contains("fluids.3.viscosity=0.5") && Contains("not an index") && Contains("size 1"));
    REQUIRE_THROWS_WITH(parse(t, {"fluids.water.viscosity=0.5"}), Contains("not an index"));
    REQUIRE_THROWS_WITH(parse(t, {"name.first=x"}), Contains("name.first=x") && Contains("not an object"));
    REQUIRE_THROWS_WITH(parse(t, {"fluids..viscosity=1"}), Contains("empty key"));
    REQUIRE_THROWS_WITH(parse(t, {"integrator"}), Contains("\"integrator\"") && Contains("key=value"));
    REQUIRE_THROWS_WITH(parse(t, {"=leapfrog"}), Contains("key=value"));
    REQUIRE_THROWS_WITH(parse(t, {"nonsense.key=1"}), Contains("nonsense") && Contains("unknown key"));
  }
}

TEST_CASE("loader: create_setup refuses particle counts beyond the limit or the memory, before allocating", "[loader]") {
  using clock = std::chrono::steady_clock;
  SceneText t;
  t.emitters = R"([{ "type": "box", "min": [0, 0, 0], "max": [1, 1, 1] }])";
  t.boundaries = "[]";

  SECTION("more than limits.max_particles") {
    t.resolution = R"({ "particles_across": 5000 })";  // 1.25e11 particles
    const sph::Scene s = parse(t);
    const auto t0 = clock::now();
    REQUIRE_THROWS_AS(sph::create_setup(s, 1.0), SceneError);
    REQUIRE_THROWS_WITH(sph::create_setup(s, 1.0),
                        Contains("test.json") && Contains("limits.max_particles") && Contains("resolution"));
    REQUIRE(std::chrono::duration<double>(clock::now() - t0).count() < 1.0);

    // A lower limit applies as well.
    t.resolution = R"({ "particles_across": 20 })";
    t.extra = R"("limits": { "max_particles": 1000 }, )";
    REQUIRE_THROWS_WITH(sph::create_setup(parse(t), 1.0), Contains("8000") && Contains("limits.max_particles = 1000"));
    t.extra = R"("limits": { "max_particles": 8000 }, )";
    REQUIRE(sph::create_setup(parse(t), 1.0).particles.size() == 8000);
  }
  SECTION("more than half of this machine's memory") {
    // 1250^3 = 1.95e9 particles, within the largest allowed limit (2e9), about 0.36 TB.
    t.resolution = R"({ "particles_across": 1250 })";
    t.extra = R"("limits": { "max_particles": 2e9 }, )";
    const sph::Scene s = parse(t);
    const double bytes = 1250.0 * 1250.0 * 1250.0 * double(sph::kBytesPerParticle);
    const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    if (bytes <= 0.5 * memory) {
      WARN("this machine has " << memory / 1e9 << " GB: the memory refusal cannot be provoked here");
      return;
    }
    const auto t0 = clock::now();
    REQUIRE_THROWS_AS(sph::create_setup(s, 1.0), SceneError);
    REQUIRE_THROWS_WITH(sph::create_setup(s, 1.0), Contains("test.json") && Contains("memory") && Contains("resolution"));
    REQUIRE(std::chrono::duration<double>(clock::now() - t0).count() < 1.0);
  }
  SECTION("a jet that keeps emitting for a long run") {
    t.emitters = R"([{ "type": "jet", "position": [0, 0, 0], "direction": [1, 0, 0], "radius": 0.05, "speed": 5 }])";
    t.resolution = R"({ "spacing": 0.01 })";
    const sph::Scene s = parse(t);
    REQUIRE_NOTHROW(sph::create_setup(s, 1.0));
    const auto t0 = clock::now();
    REQUIRE_THROWS_WITH(sph::create_setup(s, 1e6), Contains("limits.max_particles"));
    REQUIRE(std::chrono::duration<double>(clock::now() - t0).count() < 1.0);
  }
}
