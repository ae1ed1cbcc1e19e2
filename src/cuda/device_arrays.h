// Particle arrays in device memory (thrust::device_vector: GPU memory under nvcc, host memory under the
// OpenMP device system), one vector per field, owned here and released by the destructor (RAII).
#pragma once

#include <thrust/copy.h>
#include <thrust/device_vector.h>
#include <thrust/execution_policy.h>

#include "../common/boundary_particles.h"
#include "../common/springs.h"
#include "../common/particle_state.h"
#include "../common/particle_view.h"
#include "../common/sph_hd.h"

#if defined(__CUDACC__)
#include <cuda_runtime.h>

#include <cub/util_allocator.cuh>
#include <thrust/system/cuda/execution_policy.h>

#include "cuda_check.h"
#endif
#include "device_launch.h"

namespace sph {
namespace SPH_DEVICE_NS {

#if defined(__CUDACC__)
// After a kernel fault the CUDA context keeps the error ("sticky"), and every later cudaFree returns it.
// Thrust's allocators throw on that from noexcept deallocations, so the unwinding that carries the fault
// to the caller ended in std::terminate (issue 11, item 5). These allocators free without throwing: the
// fault itself has already been reported, and the context's memory goes with it.
template <class T>
struct QuietFreeAllocator : thrust::device_allocator<T> {
  template <class U>
  struct rebind {
    using other = QuietFreeAllocator<U>;
  };
  QuietFreeAllocator() = default;
  template <class U>
  QuietFreeAllocator(const QuietFreeAllocator<U>&) {}
  void deallocate(thrust::device_ptr<T> p, std::size_t) noexcept { (void)cudaFree(thrust::raw_pointer_cast(p)); }
};

template <class T>
using DeviceVector = thrust::device_vector<T, QuietFreeAllocator<T>>;

// Temporary storage of the scan, select and reduce algorithms (Thrust's, through with_temporaries, and
// CUB's, through cub_temporaries), from a cache: blocks come back to it when an algorithm has been
// enqueued and are reused by later ones on the same stream, so a step allocates nothing once the sizes are
// known (issue 11, item 6: cudaMalloc/cudaFree per algorithm and step before). Bins are powers of two from
// 1 KiB, none too large to cache (a block wastes less than half its size). Blocks are freed without
// throwing, for the same reason as above; the cache's destructor ignores errors too.
class QuietTemporaryAllocator {
 public:
  using value_type = char;
  QuietTemporaryAllocator() = default;
  QuietTemporaryAllocator(const QuietTemporaryAllocator&) = delete;  // Thrust takes it by reference
  QuietTemporaryAllocator& operator=(const QuietTemporaryAllocator&) = delete;
  char* allocate(std::ptrdiff_t bytes) {
    void* p = nullptr;
    CUDA_CHECK(cache_.DeviceAllocate(&p, std::size_t(bytes), kStream));
    return static_cast<char*>(p);
  }
  void deallocate(char* p, std::size_t) noexcept { (void)cache_.DeviceFree(p); }

 private:
  static constexpr unsigned kBinGrowth = 2, kMinBin = 10;  // 1 KiB
  cub::CachingDeviceAllocator cache_{kBinGrowth, kMinBin};
};

// Thrust's execution policy for algorithms that need temporary storage: enqueued, not waited for.
inline auto with_temporaries(QuietTemporaryAllocator& a) { return thrust::cuda::par_nosync(a).on(kStream); }

// Runs a CUB device algorithm f(temporary, bytes) the CUB way: once to size its temporary storage, once
// to enqueue it with storage from the cache (released at once: later users are ordered after it on the
// stream).
template <class F>
void cub_temporaries(QuietTemporaryAllocator& a, F&& f) {
  std::size_t bytes = 0;
  CUDA_CHECK(f(static_cast<void*>(nullptr), bytes));
  char* storage = a.allocate(std::ptrdiff_t(bytes));
  const cudaError_t status = f(static_cast<void*>(storage), bytes);
  a.deallocate(storage, bytes);
  CUDA_CHECK(status);
}
#else
template <class T>
using DeviceVector = thrust::device_vector<T>;

struct QuietTemporaryAllocator {};
inline auto with_temporaries(QuietTemporaryAllocator&) { return thrust::device; }
#endif

// dst[j] = src[index[j]] for every particle field, for j < *count (for every j of dst when count is null).
// One loop for all fields: one launch (nvcc) or one parallel loop (OpenMP) where a gather per field took
// one for each of the 13 fields.
struct GatherFn {
  ParticleView src, dst;
  const int32_t* index;
  const int32_t* count;
  SPH_HD void operator()(int32_t j) const {
    if (count != nullptr && j >= *count) return;
    const int32_t i = index[j];
#define SPH_GATHER_FIELD(type, name) dst.name[j] = src.name[i];
    SPH_PARTICLE_FIELDS(SPH_GATHER_FIELD)
#undef SPH_GATHER_FIELD
  }
};

struct DeviceArrays {
#define SPH_DECLARE_DEVICE_FIELD(type, name) DeviceVector<type> name;
  SPH_PARTICLE_FIELDS(SPH_DECLARE_DEVICE_FIELD)
  SPH_DERIVED_FIELDS(SPH_DECLARE_DEVICE_FIELD)
  SPH_SOLVER_FIELDS(SPH_DECLARE_DEVICE_FIELD)
#undef SPH_DECLARE_DEVICE_FIELD

  std::size_t size() const { return pos.size(); }

  // Bytes of device memory per particle: the fields, in this and in the reordering copy, and the derived
  // fields once.
  static constexpr std::size_t kBytesPerParticle = 2 * kParticleFieldBytes + kDerivedFieldBytes + kSolverFieldBytes;

  // Sizes the derived fields (SPH_DERIVED_FIELDS) to the particle count; their values are left to the
  // grid phase's packing and the pressure phase, which write them before every use; the solver fields
  // (SPH_SOLVER_FIELDS) too when solver_fields is set, else they are freed.
  void fit_derived(bool solver_fields) { fit_derived_fields(*this, size(), solver_fields); }

  // After a swap with the reordering buffer: takes back the derived fields, so that only one of the two
  // ever holds them (kBytesPerParticle counts them once).
  void take_derived(DeviceArrays& other) {
#define SPH_TAKE_DERIVED_FIELD(type, name) name.swap(other.name);
    SPH_DERIVED_FIELDS(SPH_TAKE_DERIVED_FIELD)
    SPH_SOLVER_FIELDS(SPH_TAKE_DERIVED_FIELD)
#undef SPH_TAKE_DERIVED_FIELD
  }

  // Calls f(device_field, other_field) for every field of the list in particle_state.h (not the derived
  // ones), where other is a host ParticleState or another DeviceArrays.
  template <class Other, class F>
  void each(Other& other, F&& f) {
#define SPH_EACH_FIELD(type, name) f(name, other.name);
    SPH_PARTICLE_FIELDS(SPH_EACH_FIELD)
#undef SPH_EACH_FIELD
  }

  void upload(const ParticleState& h) {
    each(h, [](auto& d, auto& v) { d.assign(v.begin(), v.end()); });
  }
  void download(ParticleState& h) {
    each(h, [](auto& d, auto& v) {
      v.resize(d.size());
      thrust::copy(d.begin(), d.end(), v.begin());
    });
  }
  // Keeps the first n particles; new ones, if n > size(), are value-initialised.
  void resize(std::size_t n) {
    each(*this, [n](auto& d, auto&) { d.resize(n); });
  }
  // Appends the particles of h after the current ones.
  void append(const ParticleState& h) {
    each(h, [](auto& d, auto& v) {
      const std::size_t old = d.size();
      d.resize(old + v.size());
      thrust::copy(v.begin(), v.end(), d.begin() + std::ptrdiff_t(old));
    });
  }
  // this[j] = src[index[j]] for every field; this takes index.size() particles.
  void gather_from(DeviceArrays& src, const DeviceVector<int32_t>& index) {
    resize(index.size());
    launch(int32_t(index.size()), GatherFn{src.view(), view(), thrust::raw_pointer_cast(index.data()), nullptr});
  }

  ParticleView view() {
    return ParticleView{int32_t(size()),
                        thrust::raw_pointer_cast(pos.data()),
                        thrust::raw_pointer_cast(vel.data()),
                        thrust::raw_pointer_cast(vel_force.data()),
                        thrust::raw_pointer_cast(acc.data()),
                        thrust::raw_pointer_cast(xsph_dv.data()),
                        thrust::raw_pointer_cast(density.data()),
                        thrust::raw_pointer_cast(near_density.data()),
                        thrust::raw_pointer_cast(pressure.data()),
                        thrust::raw_pointer_cast(near_pressure.data()),
                        thrust::raw_pointer_cast(age.data()),
                        thrust::raw_pointer_cast(fluid.data()),
                        thrust::raw_pointer_cast(id.data()),
                        thrust::raw_pointer_cast(pos_start.data()),
                        thrust::raw_pointer_cast(pos_mass.data()),
                        thrust::raw_pointer_cast(vel_inv_rho.data()),
                        thrust::raw_pointer_cast(pressure_rho2.data()),
                        thrust::raw_pointer_cast(near_pressure_rho2.data()),
                        thrust::raw_pointer_cast(alpha.data()),
                        thrust::raw_pointer_cast(kappa.data()),
                        thrust::raw_pointer_cast(lambda.data()),
                        thrust::raw_pointer_cast(solver_error.data()),
                        thrust::raw_pointer_cast(delta_pos.data()),
                        thrust::raw_pointer_cast(omega.data()),
                        thrust::raw_pointer_cast(pos_previous.data()),
                        thrust::raw_pointer_cast(support.data()),
                        thrust::raw_pointer_cast(surface_normal.data()),
                        thrust::raw_pointer_cast(curvature_own.data()),
                        thrust::raw_pointer_cast(curvature.data())};
  }
};

// The static boundary particles (boundary_particles.h) in device memory: copied once, read through a
// BoundaryView by every neighbour loop.
struct DeviceBoundary {
  DeviceVector<Vec4> pos_volume;
  DeviceVector<float> friction;
  DeviceVector<Vec4> normal_depth;
  DeviceVector<int32_t> solid;
  DeviceVector<int32_t> cell_start;
  BoundaryView geometry{};  // the host view's grid; its pointers are replaced by view()

  void upload(const BoundaryParticles& b) {
    pos_volume.assign(b.pos_volume.begin(), b.pos_volume.end());
    friction.assign(b.friction.begin(), b.friction.end());
    normal_depth.assign(b.normal_depth.begin(), b.normal_depth.end());
    solid.assign(b.solid.begin(), b.solid.end());
    cell_start.assign(b.cell_start.begin(), b.cell_start.end());
    geometry = b.view();
  }
  BoundaryView view() const {
    BoundaryView v = geometry;
    v.n = int32_t(pos_volume.size());
    v.pos_volume = thrust::raw_pointer_cast(pos_volume.data());
    v.friction = thrust::raw_pointer_cast(friction.data());
    v.normal_depth = thrust::raw_pointer_cast(normal_depth.data());
    v.solid = thrust::raw_pointer_cast(solid.data());
    v.cell_start = thrust::raw_pointer_cast(cell_start.data());
    return v;
  }
};

// The viscoelastic springs (springs.h) in device memory, by particle id.
struct DeviceSprings {
  int32_t capacity = 0;
  DeviceVector<int32_t> partner;
  DeviceVector<float> rest;
  DeviceVector<float> stiffness;
  DeviceVector<int32_t> index_of_id;

  void upload(const SpringNetwork& s) {
    capacity = s.capacity;
    partner.assign(s.partner.begin(), s.partner.end());
    rest.assign(s.rest.begin(), s.rest.end());
    stiffness.assign(s.stiffness.begin(), s.stiffness.end());
    index_of_id.assign(s.index_of_id.begin(), s.index_of_id.end());
  }
  SpringNetwork download() const {
    SpringNetwork s;
    s.capacity = capacity;
    s.partner.resize(partner.size());
    s.rest.resize(rest.size());
    s.stiffness.resize(stiffness.size());
    s.index_of_id.resize(index_of_id.size());
    thrust::copy(partner.begin(), partner.end(), s.partner.begin());
    thrust::copy(rest.begin(), rest.end(), s.rest.begin());
    thrust::copy(stiffness.begin(), stiffness.end(), s.stiffness.begin());
    thrust::copy(index_of_id.begin(), index_of_id.end(), s.index_of_id.begin());
    return s;
  }
  SpringView view() {
    return SpringView{capacity, int32_t(index_of_id.size()), thrust::raw_pointer_cast(partner.data()),
                      thrust::raw_pointer_cast(rest.data()), thrust::raw_pointer_cast(stiffness.data()),
                      thrust::raw_pointer_cast(index_of_id.data())};
  }
};

}  // namespace SPH_DEVICE_NS
}  // namespace sph
