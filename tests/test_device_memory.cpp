// The GPU memory check before upload (src/cuda/device_memory.h): a particle count that cannot fit is
// refused with a message that names the need, the free memory and how many particles would fit
// (issue 11, Build item 7). Plain arithmetic: runs without a GPU.
#include <string>

#include <catch2/catch.hpp>

#include "cuda/device_memory.h"

using Catch::Matchers::Contains;

namespace {
constexpr std::size_t kMiB = 1024 * 1024;
}

TEST_CASE("GPU memory check accepts what fits, including an exact fit", "[device_memory]") {
  CHECK(sph::device_memory_shortfall(1000, 256, kMiB, 100 * kMiB, 141 * 1024 * kMiB).empty());
  CHECK(sph::device_memory_shortfall(1000, 256, 1000, 1000 * 256 + 1000, 2000 * 256).empty());
  CHECK(sph::device_memory_shortfall(0, 256, 0, 0, 0).empty());
}

TEST_CASE("GPU memory check refuses one particle too many and names the limit", "[device_memory]") {
  const std::size_t per = 230, grid = 64 * kMiB, available = 1024 * kMiB;
  const std::size_t fit = (available - grid) / per;  // 4,376,665 particles
  CHECK(sph::device_memory_shortfall(fit, per, grid, available, 2048 * kMiB).empty());
  const std::string refusal = sph::device_memory_shortfall(fit + 1, per, grid, available, 2048 * kMiB);
  REQUIRE_FALSE(refusal.empty());
  CHECK_THAT(refusal, Contains(std::to_string(fit + 1) + " particles need 1024 MiB of GPU memory"));
  CHECK_THAT(refusal, Contains("230 bytes per particle plus 64 MiB for the grid"));
  CHECK_THAT(refusal, Contains("only 1024 MiB of the GPU's 2048 MiB are free"));
  CHECK_THAT(refusal, Contains("at most " + std::to_string(fit) + " particles fit"));
}

TEST_CASE("GPU memory check: a grid larger than the free memory leaves room for no particle", "[device_memory]") {
  const std::string refusal = sph::device_memory_shortfall(10, 100, 2 * kMiB, kMiB, 4 * kMiB);
  CHECK_THAT(refusal, Contains("at most 0 particles fit"));
}
