// Faults with names (issue 11, item 7): on the cuda build an error in a phase (a failed launch, a fault
// inside a kernel, a CUDA call that fails, device memory running out) becomes an ordinary
// std::runtime_error that names the back end, the phase and the CUDA error, which sph_run and sph_demo
// report with exit status 1. Teardown after such an error is safe (device_arrays.h frees quietly).
// The step is asynchronous (issue 11, item 6), so a fault inside a kernel is named by the phase only with
// SPH_DEVICE_SYNC=1; otherwise it is "phase step (fault detected after ...)" at the step's end.
// On the host build errors are ordinary C++ exceptions already, and these checks cost nothing.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <stdexcept>
#include <string>

#if defined(__CUDACC__)
#include <cuda_runtime.h>
#endif

#include "device_launch.h"
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

// Whether every phase waits for the device (SPH_DEVICE_SYNC=1 in the environment, read once): a debugging
// mode that names the exact phase a kernel faults in, at the cost of one synchronisation per phase.
inline bool sync_each_phase() {
  static const bool on = [] {
    const char* v = std::getenv("SPH_DEVICE_SYNC");
    return v != nullptr && std::string(v) == "1";
  }();
  return on;
}

// Runs f, one phase of a step (or another piece of work: "upload", "download"); any error it throws or
// leaves on the device comes out as std::runtime_error naming the back end and the phase. A failed launch
// is seen at once (cudaGetLastError, no waiting). A fault inside a kernel shows only when the host waits
// for the device: with `wait` at the end of this phase, otherwise at the step's one synchronisation
// (wait_for_step below), which names the step instead; sync_each_phase() makes every phase wait.
template <class F>
void run_phase(const std::string& backend, const char* phase, F&& f, bool wait = true) {
  try {
    f();
    check_device(wait || sync_each_phase());
  } catch (const std::exception& e) {
    throw std::runtime_error("back end \"" + backend + "\", phase \"" + phase + "\": " + e.what());
  }
}

// The step's one synchronisation: waits for everything enqueued on the stream. A fault inside any of the
// step's kernels is reported here, as phase "step" with the last phase enqueued before it.
inline void wait_for_step(const std::string& backend, const char* last_phase) {
  const cudaError_t status = cudaStreamSynchronize(kStream);
  if (status != cudaSuccess)
    throw std::runtime_error("back end \"" + backend + "\", phase \"step\" (fault detected after \"" + last_phase +
                             "\"; SPH_DEVICE_SYNC=1 names the phase it happened in): " + cudaGetErrorName(status) +
                             ": " + cudaGetErrorString(status));
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
void run_phase(const std::string&, const char*, F&& f, bool = true) {
  f();
}
inline void wait_for_step(const std::string&, const char*) {}
inline void check_device(bool) {}
inline void check_device_memory(std::size_t, std::size_t, std::size_t, std::size_t) {}

#endif

}  // namespace SPH_DEVICE_NS
}  // namespace sph
