// The device back end, in two builds of one source (device_backend.cu):
//   "host": compiled by g++ against CCCL with Thrust's OpenMP device system: device code on the host's cores;
//   "cuda": compiled by nvcc for NVIDIA GPUs.
// This header is plain C++: no CUDA type appears here, so everything else builds with g++ alone.
#pragma once

#include <memory>
#include <string>

#include "../common/backend.h"

namespace sph {

std::unique_ptr<Backend> make_host_backend(const SimConstants& constants);

// Throws std::runtime_error when no usable GPU is present (the message says why).
std::unique_ptr<Backend> make_cuda_backend(const SimConstants& constants);

// Whether CUDA device 0 can be used: present, and this build holds code for its architecture (a probe
// kernel's attributes can be read); otherwise *why says what is missing.
bool cuda_device_available(std::string* why);

// The name of CUDA device 0, or "" when there is none.
std::string cuda_device_name();

}  // namespace sph
