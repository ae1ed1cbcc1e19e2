// The "cuda" build of the device back end: device_backend.cu compiled by nvcc for NVIDIA GPUs, with
// CUDA-OpenGL interop where OpenGL headers exist (GL/glew.h must come before cuda_gl_interop.h).
#include <fstream>
#include <string>

#if defined(SPH_WITH_GL_HEADERS)
#include <GL/glew.h>
#include <cuda_gl_interop.h>
#define SPH_DEVICE_GL_INTEROP 1
#endif

#include "cuda_check.h"
#include "device_backend.h"

namespace sph {

namespace {
// A kernel that does nothing, built for the same architectures as every other kernel of this file: its
// attributes can be read only where this build holds code the device can run.
__global__ void kernel_image_probe() {}
}  // namespace

namespace {
// Why cudaGetDeviceCount failed, in words a user can act on. The runtime says "driver version is
// insufficient" both where the driver is too old and where there is no NVIDIA driver at all; the
// kernel module's /proc/driver/nvidia/version tells the two apart (Linux).
std::string device_count_failure(cudaError_t status) {
  std::string driver;
  std::getline(std::ifstream("/proc/driver/nvidia/version"), driver);
  int runtime = 0;
  (void)cudaRuntimeGetVersion(&runtime);
  const std::string needs = "CUDA " + std::to_string(runtime / 1000) + "." + std::to_string(runtime % 1000 / 10);
  if (status == cudaErrorInsufficientDriver && driver.empty())
    return "no NVIDIA driver is loaded (no /proc/driver/nvidia/version); install the NVIDIA driver for " + needs +
           " or newer, or use the host back end";
  if (status == cudaErrorInsufficientDriver)
    return "the NVIDIA driver (" + driver + ") is older than this build's runtime, " + needs +
           ", needs; update the driver or use the host back end";
  if (status == cudaErrorNoDevice) return "no CUDA device found";
  return std::string("no usable CUDA device: ") + cudaGetErrorName(status) + " (" + cudaGetErrorString(status) + ")";
}
}  // namespace

bool cuda_device_available(std::string* why) {
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    (void)cudaGetLastError();  // not sticky: clear it
    if (why) *why = device_count_failure(status);
    return false;
  }
  if (count == 0) {
    if (why) *why = "no CUDA device found";
    return false;
  }
  // A device the build has no code for (say compute capability 8.0 without sm_80 in
  // CMAKE_CUDA_ARCHITECTURES) fails here with cudaErrorNoKernelImageForDevice, not in the first step.
  cudaFuncAttributes attributes{};
  const cudaError_t image = cudaFuncGetAttributes(&attributes, kernel_image_probe);
  if (image != cudaSuccess) {
    (void)cudaGetLastError();  // not a sticky error: clear it
    if (why) {
      cudaDeviceProp prop{};
      const bool named = cudaGetDeviceProperties(&prop, 0) == cudaSuccess;
      *why = "CUDA device 0" + (named ? " (" + std::string(prop.name) + ", compute capability " + std::to_string(prop.major) +
                                            "." + std::to_string(prop.minor) + ")"
                                      : std::string()) +
             " cannot run this build: " + cudaGetErrorName(image) + " (" + cudaGetErrorString(image) +
             "); rebuild with its architecture in CMAKE_CUDA_ARCHITECTURES" +
             (named ? " (-DCMAKE_CUDA_ARCHITECTURES=" + std::to_string(prop.major) + std::to_string(prop.minor) + ")"
                    : std::string());
    }
    return false;
  }
  return true;
}

std::string cuda_device_name() {
  if (!cuda_device_available(nullptr)) return "";
  cudaDeviceProp prop{};
  CUDA_CHECK(cudaGetDeviceProperties(&prop, 0));
  return prop.name;
}

namespace {
void require_cuda_device() {
  std::string why;
  if (!cuda_device_available(&why)) throw std::runtime_error("back end \"cuda\": " + why);
  CUDA_CHECK(cudaSetDevice(0));
}
}  // namespace

}  // namespace sph

#define SPH_DEVICE_NS cuda_device
#define SPH_DEVICE_FACTORY make_cuda_backend
#define SPH_DEVICE_NAME "cuda"
#define SPH_DEVICE_PREPARE() require_cuda_device()
#include "device_backend.cu"
