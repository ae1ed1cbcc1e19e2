// The GPU memory check before upload (issue 11, Build item 7). Plain C++ with no CUDA type, so the host
// tests check its arithmetic and its message; the cuda build feeds it cudaMemGetInfo's figures
// (device_faults.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sph {

// "" when `particles` particles (bytes_per_particle each, plus grid_bytes for the grid) fit in
// available_bytes; otherwise the refusal, naming what they need, what is free of total_bytes, and how many
// particles would fit.
inline std::string device_memory_shortfall(std::size_t particles, std::size_t bytes_per_particle,
                                           std::size_t grid_bytes, std::size_t available_bytes,
                                           std::size_t total_bytes) {
  const std::size_t needed = particles * bytes_per_particle + grid_bytes;
  if (needed <= available_bytes) return "";
  const std::size_t fit = available_bytes > grid_bytes ? (available_bytes - grid_bytes) / bytes_per_particle : 0;
  auto mib = [](std::size_t bytes) { return std::to_string(int64_t(double(bytes) / (1024.0 * 1024.0))); };
  return std::to_string(particles) + " particles need " + mib(needed) + " MiB of GPU memory (" +
         std::to_string(bytes_per_particle) + " bytes per particle plus " + mib(grid_bytes) +
         " MiB for the grid), but only " + mib(available_bytes) + " MiB of the GPU's " + mib(total_bytes) +
         " MiB are free: at most " + std::to_string(fit) +
         " particles fit; lower the resolution or limits.max_particles";
}

}  // namespace sph
