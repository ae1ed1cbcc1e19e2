// Particle arrays in device memory (thrust::device_vector: GPU memory under nvcc, host memory under the
// OpenMP device system), one vector per field, owned here and released by the destructor (RAII).
#pragma once

#include <thrust/copy.h>
#include <thrust/device_vector.h>
#include <thrust/gather.h>

#include "../common/particle_state.h"

namespace sph {
namespace SPH_DEVICE_NS {

struct DeviceArrays {
#define SPH_DECLARE_DEVICE_FIELD(type, name) thrust::device_vector<type> name;
  SPH_PARTICLE_FIELDS(SPH_DECLARE_DEVICE_FIELD)
#undef SPH_DECLARE_DEVICE_FIELD

  std::size_t size() const { return pos.size(); }

  // Calls f(device_field, other_field) for every field of the list in particle_state.h, where other is a
  // host ParticleState or another DeviceArrays.
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
  // Appends the particles of h after the current ones.
  void append(const ParticleState& h) {
    each(h, [](auto& d, auto& v) {
      const std::size_t old = d.size();
      d.resize(old + v.size());
      thrust::copy(v.begin(), v.end(), d.begin() + std::ptrdiff_t(old));
    });
  }
  // this[j] = src[index[j]] for every field; this takes index.size() particles.
  void gather_from(DeviceArrays& src, const thrust::device_vector<int32_t>& index) {
    each(src, [&](auto& dst_field, auto& src_field) {
      dst_field.resize(index.size());
      thrust::gather(index.begin(), index.end(), src_field.begin(), dst_field.begin());
    });
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
                        thrust::raw_pointer_cast(pos_start.data())};
  }
};

}  // namespace SPH_DEVICE_NS
}  // namespace sph
