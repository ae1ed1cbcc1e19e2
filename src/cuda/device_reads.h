// Counts of what the device back ends (both builds) do that a step's cost depends on and no result shows,
// for tests (tests/test_device_reads.cpp): the device-to-host reads, of which a step makes one, its summary
// (issue 11, item 2), and how often the grid's block tables had to grow (device_grid.h). Plain C++.
#pragma once

#include <atomic>
#include <cstdint>

namespace sph {

struct DeviceCounters {
  std::atomic<int64_t> reads{0};          // device-to-host copies (device_readback.h)
  std::atomic<int64_t> table_growths{0};  // times the block tables' capacity grew
};

// The process's counters, shared by the host and cuda builds.
inline DeviceCounters& device_counters() {
  static DeviceCounters counters;
  return counters;
}

}  // namespace sph
