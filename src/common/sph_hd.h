// SPH_HD marks functions shared by every back end: __host__ __device__ under nvcc, nothing under a plain
// C++ compiler. Nothing in src/common/ includes a CUDA header, so the reference builds with g++ alone.
#pragma once

#if defined(__CUDACC__)
#define SPH_HD __host__ __device__
#else
#define SPH_HD
#endif

// SPH_HD_ALWAYS_INLINE: for a pair body used at two sites (particles and wall ghosts), so that each loop
// keeps its own inlined copy instead of a call per pair.
#if defined(__CUDACC__)
#define SPH_HD_ALWAYS_INLINE __host__ __device__ __forceinline__
#elif defined(__GNUC__)
#define SPH_HD_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SPH_HD_ALWAYS_INLINE inline
#endif

// SPH_INLINE_LAMBDA: after a pair loop's lambda parameters, so that g++ inlines the pair body into the loop over
// candidates: with the forces specialised per model (forces.h) it outlined the body of some models and made
// each pair a call (1.8 times slower forces in a dense clump of 12,000 particles). nvcc inlines it unasked.
#if defined(__GNUC__) && !defined(__CUDACC__)
#define SPH_INLINE_LAMBDA __attribute__((always_inline))
#else
#define SPH_INLINE_LAMBDA
#endif

// SPH_KERNEL_FN marks the operator() of a phase functor (src/solvers/) that reads the constants through its
// back end's reference: device code only under nvcc (the constant symbol exists only there,
// src/cuda/device_constants.h), an ordinary member function under a plain C++ compiler.
#if defined(__CUDACC__)
#define SPH_KERNEL_FN __device__
#else
#define SPH_KERNEL_FN
#endif
