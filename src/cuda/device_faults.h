// Faults with names (issue 11, item 7): on the cuda build an error in a phase (a failed launch, a fault
// inside a kernel, a CUDA call that fails, device memory running out) becomes an ordinary
// std::runtime_error that names the back end, the phase and the CUDA error, which sph_run and sph_demo
// report with exit status 1. Teardown after such an error is safe (device_arrays.h frees quietly).
// On the host build errors are ordinary C++ exceptions already, and these checks cost nothing.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#if defined(__CUDACC__)
#include <cuda_runtime.h>
#endif

#include "device_memory.h"

namespace sph {
namespace SPH_DEVICE_NS {

#if defined(__CUDACC__)

// Throws when the device has reported an error. A failed launch shows at once (cudaGetLastError); a fault
// inside a kernel shows only when the host waits for it, so `wait` waits for the device.
inline void check_device(bool wait) {
  const cudaError_t launched = cudaGetLastError();
  const cudaError_t status = launched != cudaSuccess ? launched : (wait ? cudaDeviceSynchronize() : cudaSuccess);
  if (status != cudaSuccess)
    throw std::runtime_error(std::string(cudaGetErrorName(status)) + ": " + cudaGetErrorString(status));
}

// Runs f, one phase of a step (or another piece of work: "upload", "download"); any error it throws or
// leaves on the device comes out as std::runtime_error naming the back end and the phase. It waits for
// the device at the end of each phase, so a fault is named by its phase and the phase timers (host
// clocks) measure the work, not its launch; an asynchronous step would time phases with CUDA events
// and check once per step instead (issue 11, Build item 2).
template <class F>
void run_phase(const std::string& backend, const char* phase, F&& f) {
  try {
    f();
    check_device(true);
  } catch (const std::exception& e) {
    throw std::runtime_error("back end \"" + backend + "\", phase \"" + phase + "\": " + e.what());
  }
}

// Refuses, before anything is allocated, a particle count whose arrays cannot fit in the GPU's free memory
// (cudaMemGetInfo). bytes_per_particle and grid_bytes: what the back end allocates for `particles`
// particles; held_bytes: what it holds now and will reuse.
inline void check_device_memory(std::size_t particles, std::size_t bytes_per_particle, std::size_t grid_bytes,
                                std::size_t held_bytes) {
  std::size_t free_bytes = 0, total_bytes = 0;
  const cudaError_t status = cudaMemGetInfo(&free_bytes, &total_bytes);
  if (status != cudaSuccess)
    throw std::runtime_error(std::string("cudaMemGetInfo failed: ") + cudaGetErrorString(status));
  const std::string refusal =
      device_memory_shortfall(particles, bytes_per_particle, grid_bytes, free_bytes + held_bytes, total_bytes);
  if (!refusal.empty()) throw std::runtime_error(refusal);
}

#else

template <class F>
void run_phase(const std::string&, const char*, F&& f) {
  f();
}
inline void check_device(bool) {}
inline void check_device_memory(std::size_t, std::size_t, std::size_t, std::size_t) {}

#endif

}  // namespace SPH_DEVICE_NS
}  // namespace sph
