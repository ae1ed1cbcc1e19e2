// A small valid scene assembled from parts, shared by the scene-loader tests (test_scene_loader.cpp,
// test_scene_solver.cpp): each test replaces exactly one part and parses the result as "test.json".
#pragma once

#include <string>
#include <vector>

#include "common/scene.h"

namespace scene_text {

struct SceneText {
  std::string fluids = R"([{ "name": "water", "rest_density": 1000, "speed_of_sound": 20, "viscosity": 0.001 }])";
  std::string emitters = R"([{ "type": "box", "fluid": "water", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1] }])";
  std::string boundaries = R"([{ "type": "box", "min": [0, 0, 0], "max": [0.3, 0.3, 0.3] }])";
  std::string resolution = R"({ "particles_across": 8 })";
  std::string extra;  // more top-level members, each followed by a comma

  std::string str() const {
    return "{ " + extra + R"("name": "test", "fluids": )" + fluids + R"(, "emitters": )" + emitters +
           R"(, "boundaries": )" + boundaries + R"(, "resolution": )" + resolution + " }";
  }
};

inline sph::Scene parse(const SceneText& t, const std::vector<std::string>& overrides = {}) {
  return sph::parse_scene(t.str(), "test.json", overrides);
}
// The base scene with one part replaced.
inline sph::Scene parse_with(std::string SceneText::*part, const std::string& text) {
  SceneText t;
  t.*part = text;
  return parse(t);
}
inline sph::Scene parse_with_extra(const std::string& extra) { return parse_with(&SceneText::extra, extra + ", "); }
inline sph::Scene parse_with_boundary(const std::string& b) { return parse_with(&SceneText::boundaries, "[" + b + "]"); }
inline sph::Scene parse_with_emitter(const std::string& e) { return parse_with(&SceneText::emitters, "[" + e + "]"); }
inline sph::Scene parse_with_fluid(const std::string& f) { return parse_with(&SceneText::fluids, "[" + f + "]"); }
inline sph::Scene parse_with_resolution(const std::string& r) { return parse_with(&SceneText::resolution, r); }

inline std::string scenes_dir() { return std::string(SPH_SOURCE_DIR) + "/scenes"; }
inline std::string data_dir() { return std::string(SPH_SOURCE_DIR) + "/tests/data"; }

}  // namespace scene_text
