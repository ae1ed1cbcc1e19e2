// launch(n, f): one data-parallel loop, f(i) for i in [0, n), over particle or cell indices. Under nvcc a
// kernel of the project's own, enqueued on the back end's stream without waiting (the step waits once, at
// its end: device_faults.h); under g++ Thrust's OpenMP for_each.
//
// kStream: where all the back end's device work goes, in order. Under nvcc one stream, CUDA's legacy
// default stream: the project's kernels, CUB's algorithms and Thrust's (par_nosync: no synchronisation at
// the end of each algorithm, issue 11 item 6) all run in the order they are enqueued, and so do
// thrust::device_vector's own allocations and copies, which always use the default stream. A stream of
// our own would need explicit ordering against those.
#pragma once

#include <cstdint>
#include <type_traits>

#include <thrust/execution_policy.h>
#include <thrust/for_each.h>
#include <thrust/iterator/counting_iterator.h>

#if defined(__CUDACC__)
#include <cuda_runtime.h>
#endif

namespace sph {
namespace SPH_DEVICE_NS {

#if defined(__CUDACC__)
inline const cudaStream_t kStream = nullptr;  // the legacy default stream
// The project's own kernels, one thread per index. Thrust's for_each (two indices per thread, bounded to
// 256 threads) took forces to 114 registers and spilled in density. A functor may set kBlocksPerSm, the
// blocks of kBlockThreads that must fit on one SM (__launch_bounds__), which caps its registers at
// 65536 / (256 kBlocksPerSm); the rest are unbounded. Set only where ptxas then needs no spill
// (tests/ptxas_resources.sh checks): a bare bound of 256 threads made ptxas aim low and spill.
constexpr int32_t kBlockThreads = 256;

template <class F, class = void>
struct BlocksPerSm {
  static constexpr int value = 0;
};
template <class F>
struct BlocksPerSm<F, std::void_t<decltype(F::kBlocksPerSm)>> {
  static constexpr int value = F::kBlocksPerSm;
};

template <class F>
__global__ void for_each_index(int32_t n, F f) {
  const int32_t i = int32_t(blockIdx.x * blockDim.x + threadIdx.x);
  if (i < n) f(i);
}

template <class F, int kBlocks>
__global__ void __launch_bounds__(kBlockThreads, kBlocks) for_each_index_bounded(int32_t n, F f) {
  const int32_t i = int32_t(blockIdx.x * blockDim.x + threadIdx.x);
  if (i < n) f(i);
}

template <class F>
void launch(int32_t n, const F& f) {
  if (n <= 0) return;
  const int32_t blocks = (n + kBlockThreads - 1) / kBlockThreads;
  if constexpr (BlocksPerSm<F>::value > 0)
    for_each_index_bounded<F, BlocksPerSm<F>::value><<<blocks, kBlockThreads, 0, kStream>>>(n, f);
  else
    for_each_index<<<blocks, kBlockThreads, 0, kStream>>>(n, f);
}
#else
template <class F>
void launch(int32_t n, const F& f) {
  if (n > 0) thrust::for_each_n(thrust::device, thrust::counting_iterator<int32_t>(0), n, f);
}
#endif

}  // namespace SPH_DEVICE_NS
}  // namespace sph
