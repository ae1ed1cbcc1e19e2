// Phase timers of the device back end (PhaseTimes, backend.h: accumulated seconds per phase).
//
// Under nvcc the step is asynchronous (issue 11, item 6): a host clock around a phase would measure how
// long it takes to enqueue it. So each phase records a pair of CUDA events on the stream, and the elapsed
// time between them is read once the step has been waited for (collect), or when the same phase is
// timed again before that. Under g++ every loop has finished when it returns: host wall clocks, as the
// cpu back end.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>

#if defined(__CUDACC__)
#include <cuda_runtime.h>

#include "cuda_check.h"
#endif

#include "../common/backend.h"
#include "device_launch.h"

namespace sph {
namespace SPH_DEVICE_NS {

#if defined(__CUDACC__)

class PhaseClock {
 public:
  PhaseClock() {
    for (Pair& p : pairs_) {
      CUDA_CHECK(cudaEventCreate(&p.start));
      CUDA_CHECK(cudaEventCreate(&p.stop));
    }
  }
  PhaseClock(const PhaseClock&) = delete;
  PhaseClock& operator=(const PhaseClock&) = delete;
  ~PhaseClock() {
    for (Pair& p : pairs_) {  // no throw: the context may hold a sticky error
      (void)cudaEventDestroy(p.start);
      (void)cudaEventDestroy(p.stop);
    }
  }

  void start(Phase phase, PhaseTimes& times) {
    Pair& p = pairs_[std::size_t(phase)];
    if (p.recorded) add(phase, p, times);  // timed twice before collect: read the first pair now
    CUDA_CHECK(cudaEventRecord(p.start, kStream));
  }
  void stop(Phase phase, PhaseTimes&) {
    Pair& p = pairs_[std::size_t(phase)];
    CUDA_CHECK(cudaEventRecord(p.stop, kStream));
    p.recorded = true;
  }
  // Adds the elapsed time of every recorded pair to times; waits for the events that are not complete.
  // Errors (a faulted context) leave the times as they are: the fault is reported where the step waits.
  void collect(PhaseTimes& times) {
    for (std::size_t i = 0; i < pairs_.size(); ++i)
      if (pairs_[i].recorded) add(Phase(i), pairs_[i], times);
  }

 private:
  struct Pair {
    cudaEvent_t start = nullptr, stop = nullptr;
    bool recorded = false;
  };
  static void add(Phase phase, Pair& p, PhaseTimes& times) {
    p.recorded = false;
    float ms = 0.0f;
    if (cudaEventSynchronize(p.stop) == cudaSuccess && cudaEventElapsedTime(&ms, p.start, p.stop) == cudaSuccess)
      times.seconds[std::size_t(phase)] += 1e-3 * double(ms);
  }
  std::array<Pair, std::size_t(Phase::Count)> pairs_;
};

#else

class PhaseClock {
 public:
  void start(Phase phase, PhaseTimes&) { started_[std::size_t(phase)] = std::chrono::steady_clock::now(); }
  void stop(Phase phase, PhaseTimes& times) {
    times.seconds[std::size_t(phase)] +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_[std::size_t(phase)]).count();
  }
  void collect(PhaseTimes&) {}

 private:
  std::array<std::chrono::steady_clock::time_point, std::size_t(Phase::Count)> started_{};
};

#endif

}  // namespace SPH_DEVICE_NS
}  // namespace sph
