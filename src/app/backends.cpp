#include "backends.h"

#include <stdexcept>

#include "../cpu/cpu_backend.h"

namespace sph {

std::vector<std::string> available_backends() { return {"cpu"}; }

BackendFactory backend_factory(const std::string& name) {
  if (name == "cpu") return [](const SimConstants& c) { return std::make_unique<CpuBackend>(c); };
  std::string list;
  for (const auto& b : available_backends()) list += (list.empty() ? "" : ", ") + b;
  if (name == "host" || name == "cuda")
    throw std::invalid_argument("back end \"" + name + "\" is not part of this build yet; available: " + list);
  throw std::invalid_argument("unknown back end \"" + name + "\"; available: " + list);
}

}  // namespace sph
