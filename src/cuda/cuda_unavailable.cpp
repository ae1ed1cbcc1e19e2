// Stand-in for the "cuda" back end in builds configured without nvcc.
#include <stdexcept>

#include "device_backend.h"

namespace sph {

bool cuda_device_available(std::string* why) {
  if (why) *why = "the cuda back end is not part of this build (nvcc was not found when it was configured)";
  return false;
}

std::string cuda_device_name() { return ""; }

std::unique_ptr<Backend> make_cuda_backend(const SimConstants&) {
  std::string why;
  cuda_device_available(&why);
  throw std::runtime_error("back end \"cuda\": " + why);
}

}  // namespace sph
