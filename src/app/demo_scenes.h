// The scenes sph_demo cycles through with [ and ], and how it loads one: the command line's file first,
// then every other JSON file beside it (sorted by name), each with the command line's --set overrides.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "../common/simulation.h"

namespace sph {

class DemoScenes {
 public:
  // first: the command line's scene file; sets: its --set overrides (key=value). Lists the folder once.
  DemoScenes(const std::string& first, std::vector<std::string> sets);

  int size() const { return int(paths_.size()); }
  // Index modulo size(), negative indexes counting from the end.
  int wrap(int index) const { return (index % size() + size()) % size(); }

  // The simulation of scene `index` (0 <= index < size()) on the back end `factory`, set up for the
  // scene's run.time as sph_run would, with jets that stop emitting at limits.max_particles (the demo runs
  // on past run.time). A scene that refuses the overrides (an index it does not have) is loaded without
  // them and `note` says so. Throws SceneError, BlowUp (relaxation) or std::invalid_argument (back end)
  // with the file's name when the scene cannot run.
  std::unique_ptr<Simulation> load(int index, const BackendFactory& factory,
                                   const std::function<void(const std::string&)>& note) const;

 private:
  std::vector<std::string> paths_;
  std::vector<std::string> sets_;
};

}  // namespace sph
