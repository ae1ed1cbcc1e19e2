#include "backends.h"

#include <stdexcept>

#include "../cpu/cpu_backend.h"
#include "../cuda/device_backend.h"

namespace sph {

std::vector<std::string> available_backends() {
  std::vector<std::string> names{"cpu"};
#if defined(SPH_HAVE_HOST)
  names.push_back("host");
#endif
  names.push_back("cuda");  // built by nvcc, or a stand-in that says why it cannot run
  return names;
}

BackendFactory backend_factory(const std::string& name) {
  if (name == "cpu") return [](const SimConstants& c) { return std::make_unique<CpuBackend>(c); };
#if defined(SPH_HAVE_HOST)
  if (name == "host") return [](const SimConstants& c) { return make_host_backend(c); };
#endif
  if (name == "cuda") {
    std::string why;
    if (!cuda_device_available(&why)) throw std::invalid_argument("back end \"cuda\" cannot run here: " + why);
    return [](const SimConstants& c) { return make_cuda_backend(c); };
  }
  std::string list;
  for (const auto& b : available_backends()) list += (list.empty() ? "" : ", ") + b;
  if (name == "host")
    throw std::invalid_argument("back end \"host\" is not part of this build (CCCL or OpenMP was not found); available: " + list);
  throw std::invalid_argument("unknown back end \"" + name + "\"; available: " + list);
}

}  // namespace sph
