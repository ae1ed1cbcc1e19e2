// Where the device back end's kernels read the simulation constants (issue 11, item 1).
//
// Under nvcc there is one copy, in the GPU's __constant__ memory: every thread reads the same bytes
// through the constant cache, and the shared per-particle code (src/common/) takes it by reference. The
// functors carry no SimConstants (about 2.7 KB): Thrust keeps a functor by value, and the shared code
// indexes c.fluids[] and c.shapes[] at run time and takes members' addresses, so a copy in a functor
// went to local memory, per thread (ptxas, sm_90: forces 126 registers and a 6,016-byte stack frame).
// The host build (g++, OpenMP) reads the back end's own copy through a pointer: the same physics, the
// same bytes, no copy per loop.
// The phase functors' operator() that reads them is SPH_KERNEL_FN (sph_hd.h).
#pragma once

#include "../common/params.h"
#include "../common/sph_hd.h"

#if defined(__CUDACC__)
#include "cuda_check.h"
#endif

namespace sph {
namespace SPH_DEVICE_NS {

#if defined(__CUDACC__)

// The one device copy. A process may hold several cuda back ends (the device test, the demo's back-end
// switch): ConstantsOwner below uploads a back end's constants before its kernels run.
__constant__ SimConstants device_constants;

// What a functor holds to reach the constants: nothing; on the device it names the constant symbol.
struct ConstantsRef {
  __device__ const SimConstants& operator*() const { return device_constants; }
};

// Keeps the constant symbol holding the constants of the back end that launches next. bind() before a
// back end's kernels: a copy of sizeof(SimConstants) bytes only when another back end (or none) bound it
// last or the constants changed since.
class ConstantsOwner {
 public:
  ConstantsOwner() = default;
  ConstantsOwner(const ConstantsOwner&) = delete;  // identity matters: it is what bound_ points to
  ConstantsOwner& operator=(const ConstantsOwner&) = delete;
  ~ConstantsOwner() {
    if (bound_ == this) bound_ = nullptr;  // a later back end at the same address uploads again
  }
  void changed() { fresh_ = false; }
  ConstantsRef bind(const SimConstants& c) {
    if (bound_ != this || !fresh_) {
      CUDA_CHECK(cudaMemcpyToSymbol(device_constants, &c, sizeof(SimConstants)));
      bound_ = this;
      fresh_ = true;
    }
    return ConstantsRef{};
  }

 private:
  static inline const ConstantsOwner* bound_ = nullptr;
  bool fresh_ = false;
};

#else

struct ConstantsRef {
  const SimConstants* host;
  const SimConstants& operator*() const { return *host; }
};

class ConstantsOwner {
 public:
  void changed() {}
  ConstantsRef bind(const SimConstants& c) { return ConstantsRef{&c}; }
};

#endif

}  // namespace SPH_DEVICE_NS
}  // namespace sph
