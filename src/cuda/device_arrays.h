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
  thrust::device_vector<Vec3> pos, vel, vel_force, acc, xsph_dv;
  thrust::device_vector<float> density, near_density, pressure, near_pressure, age;
  thrust::device_vector<uint8_t> fluid;
  thrust::device_vector<int32_t> id;

  std::size_t size() const { return pos.size(); }

  // Calls f(device_field, host_field) for every field, so copies and permutations list them once.
  template <class State, class F>
  void each(State& h, F&& f) {
    f(pos, h.pos);
    f(vel, h.vel);
    f(vel_force, h.vel_force);
    f(acc, h.acc);
    f(xsph_dv, h.xsph_dv);
    f(density, h.density);
    f(near_density, h.near_density);
    f(pressure, h.pressure);
    f(near_pressure, h.near_pressure);
    f(age, h.age);
    f(fluid, h.fluid);
    f(id, h.id);
  }
  template <class F>
  void each_pair(DeviceArrays& o, F&& f) {
    f(pos, o.pos);
    f(vel, o.vel);
    f(vel_force, o.vel_force);
    f(acc, o.acc);
    f(xsph_dv, o.xsph_dv);
    f(density, o.density);
    f(near_density, o.near_density);
    f(pressure, o.pressure);
    f(near_pressure, o.near_pressure);
    f(age, o.age);
    f(fluid, o.fluid);
    f(id, o.id);
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
    each_pair(src, [&](auto& dst_field, auto& src_field) {
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
                        thrust::raw_pointer_cast(id.data())};
  }
};

}  // namespace SPH_DEVICE_NS
}  // namespace sph
