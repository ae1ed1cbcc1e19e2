// The one small device-to-host read of a step (issue 11, item 6): a value the device writes, copied into
// page-locked host memory (cudaMallocHost) by an asynchronous copy enqueued behind the step's work, and
// read after the step has been waited for (device_faults.h, wait_for_step). Under g++ the device system's
// memory is host memory: the value is read directly. Either way each read is counted (device_reads.h).
#pragma once

#if defined(__CUDACC__)
#include <cuda_runtime.h>

#include "cuda_check.h"
#endif

#include "device_launch.h"
#include "device_reads.h"

namespace sph {
namespace SPH_DEVICE_NS {

#if defined(__CUDACC__)

template <class T>
class PinnedReadback {
 public:
  PinnedReadback() {
    void* p = nullptr;
    CUDA_CHECK(cudaMallocHost(&p, sizeof(T)));
    host_ = static_cast<T*>(p);
  }
  PinnedReadback(const PinnedReadback&) = delete;
  PinnedReadback& operator=(const PinnedReadback&) = delete;
  ~PinnedReadback() { (void)cudaFreeHost(host_); }  // no throw: the context may hold a sticky error

  // Enqueues the copy of *device (device memory); value() holds it once the stream has been waited for.
  void read_from(const T* device) {
    CUDA_CHECK(cudaMemcpyAsync(host_, device, sizeof(T), cudaMemcpyDeviceToHost, kStream));
    ++device_counters().reads;
  }
  const T& value() const { return *host_; }

 private:
  T* host_ = nullptr;
};

#else

template <class T>
class PinnedReadback {
 public:
  void read_from(const T* device) {
    value_ = *device;
    ++device_counters().reads;
  }
  const T& value() const { return value_; }

 private:
  T value_{};
};

#endif

}  // namespace SPH_DEVICE_NS
}  // namespace sph
