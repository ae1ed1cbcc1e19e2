// CUDA_CHECK: every CUDA runtime call is checked; a failure throws with the call, file and line.
#pragma once

#include <stdexcept>
#include <string>

#include <cuda_runtime.h>

#define CUDA_CHECK(call)                                                                               \
  do {                                                                                                 \
    const cudaError_t sph_cuda_status = (call);                                                        \
    if (sph_cuda_status != cudaSuccess)                                                                \
      throw std::runtime_error(std::string("CUDA error in ") + #call + " at " + __FILE__ + ":" +       \
                               std::to_string(__LINE__) + ": " + cudaGetErrorString(sph_cuda_status)); \
  } while (0)
