// Particle state on the host: structure of arrays, one std::vector per field. The serial reference works on
// it directly; device back ends copy it in and out (upload / download).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "particle_view.h"
#include "vec3.h"

namespace sph {

// One particle to create: from an instant emitter at start-up or a jet emitter during the run.
struct Spawn {
  Vec3 pos;
  Vec3 vel;
  float age;      // < 0: still inside a jet's inlet, moved kinematically until age reaches 0
  float density;  // initial density (rest density: the continuity method integrates from there)
  uint8_t fluid;
  int32_t id;
};

struct ParticleState {
  std::vector<Vec3> pos, vel, vel_force, acc, xsph_dv;
  std::vector<float> density, near_density, pressure, near_pressure, age;
  std::vector<uint8_t> fluid;
  std::vector<int32_t> id;

  std::size_t size() const { return pos.size(); }

  void resize(std::size_t n) {
    pos.resize(n);
    vel.resize(n);
    vel_force.resize(n);
    acc.resize(n);
    xsph_dv.resize(n);
    density.resize(n);
    near_density.resize(n);
    pressure.resize(n);
    near_pressure.resize(n);
    age.resize(n);
    fluid.resize(n);
    id.resize(n);
  }

  void append(const Spawn& s) {
    const std::size_t i = size();
    resize(i + 1);
    pos[i] = s.pos;
    vel[i] = s.vel;
    vel_force[i] = s.vel;
    acc[i] = Vec3{0.0f, 0.0f, 0.0f};
    xsph_dv[i] = Vec3{0.0f, 0.0f, 0.0f};
    density[i] = s.density;
    near_density[i] = 0.0f;
    pressure[i] = 0.0f;
    near_pressure[i] = 0.0f;
    age[i] = s.age;
    fluid[i] = s.fluid;
    id[i] = s.id;
  }

  // Copies particle `from` of `src` into slot `to` of this state (used by reordering and removal).
  void copy_particle(std::size_t to, const ParticleState& src, std::size_t from) {
    pos[to] = src.pos[from];
    vel[to] = src.vel[from];
    vel_force[to] = src.vel_force[from];
    acc[to] = src.acc[from];
    xsph_dv[to] = src.xsph_dv[from];
    density[to] = src.density[from];
    near_density[to] = src.near_density[from];
    pressure[to] = src.pressure[from];
    near_pressure[to] = src.near_pressure[from];
    age[to] = src.age[from];
    fluid[to] = src.fluid[from];
    id[to] = src.id[from];
  }

  ParticleView view() {
    return ParticleView{int32_t(size()), pos.data(),          vel.data(),      vel_force.data(),
                        acc.data(),      xsph_dv.data(),      density.data(),  near_density.data(),
                        pressure.data(), near_pressure.data(), age.data(),     fluid.data(),
                        id.data()};
  }
};

// Bytes of host memory one particle needs in the reference back end (state, reorder copy, grid arrays):
// used to refuse particle counts that cannot fit before allocating anything.
constexpr std::size_t kBytesPerParticle = 2 * (5 * sizeof(Vec3) + 5 * sizeof(float) + 1 + 4) + 3 * 4;

}  // namespace sph
