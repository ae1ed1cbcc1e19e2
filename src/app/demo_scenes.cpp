#include "demo_scenes.h"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace sph {

DemoScenes::DemoScenes(const std::string& first, std::vector<std::string> sets) : sets_(std::move(sets)) {
  const fs::path dir = fs::path(first).parent_path().empty() ? fs::path(".") : fs::path(first).parent_path();
  paths_.push_back(first);
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".json" && fs::absolute(e.path()) != fs::absolute(first)) paths_.push_back(e.path().string());
  std::sort(paths_.begin() + 1, paths_.end());
}

std::unique_ptr<Simulation> DemoScenes::load(int index, const BackendFactory& factory,
                                             const std::function<void(const std::string&)>& note) const {
  const std::string& path = paths_[std::size_t(index)];
  Scene scene;
  try {
    scene = load_scene(path, sets_);
  } catch (const SceneError& e) {
    if (sets_.empty()) throw;
    scene = load_scene(path);
    note(std::string("overrides not applied: ") + e.what());
  }
  auto sim = std::make_unique<Simulation>(scene, factory, scene.run_time);
  sim->stop_emission_at_limit(true);
  return sim;
}

}  // namespace sph
