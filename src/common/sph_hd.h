// SPH_HD marks functions shared by every back end: __host__ __device__ under nvcc, nothing under a plain
// C++ compiler. Nothing in src/common/ includes a CUDA header, so the reference builds with g++ alone.
#pragma once

#if defined(__CUDACC__)
#define SPH_HD __host__ __device__
#else
#define SPH_HD
#endif
