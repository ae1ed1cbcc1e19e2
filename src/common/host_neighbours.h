// A neighbour search on the host for set-up work that runs once, before a back end's grid exists
// (cohesion_energy.cpp: the surface energy of the start; springs.cpp: the springs of the start): the chosen
// particles binned in cells of h in a hash map.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "particle_state.h"

namespace sph {

class HostNeighbours {
 public:
  // Bins the particles of ps for which include(index) is true, in cells of h [m].
  template <class Include>
  HostNeighbours(const ParticleState& ps, double h, Include include) : ps_(ps), h_(h) {
    for (std::size_t a = 0; a < ps.size(); ++a)
      if (include(a)) cells_[key(cell_of(ps.pos[a]))].push_back(uint32_t(a));
  }

  // f(b, x_ab) for every binned particle b != a of a's fluid in the 27 cells around a's (every one closer
  // than h among them; the caller measures the distance as it needs), x_ab = x_a - x_b in single precision.
  template <class F>
  void for_each_same_fluid(std::size_t a, F f) const {
    for_each(a, [&](std::size_t b, Vec3 x) {
      if (ps_.fluid[b] == ps_.fluid[a]) f(b, x);
    });
  }

  // The same for the binned particles of every fluid.
  template <class F>
  void for_each(std::size_t a, F f) const {
    const std::array<int64_t, 3> ca = cell_of(ps_.pos[a]);
    for (int64_t dk = -1; dk <= 1; ++dk)
      for (int64_t dj = -1; dj <= 1; ++dj)
        for (int64_t di = -1; di <= 1; ++di) {
          const auto it = cells_.find(key({ca[0] + di, ca[1] + dj, ca[2] + dk}));
          if (it == cells_.end()) continue;
          for (const uint32_t b : it->second)
            if (b != a) f(std::size_t(b), ps_.pos[a] - ps_.pos[b]);
        }
  }

 private:
  std::array<int64_t, 3> cell_of(const Vec3& x) const {
    return {int64_t(std::floor(x.x / h_)), int64_t(std::floor(x.y / h_)), int64_t(std::floor(x.z / h_))};
  }
  static uint64_t key(const std::array<int64_t, 3>& c) {
    return (uint64_t(c[0]) & 0x1FFFFF) | ((uint64_t(c[1]) & 0x1FFFFF) << 21) | ((uint64_t(c[2]) & 0x1FFFFF) << 42);
  }
  const ParticleState& ps_;
  double h_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

}  // namespace sph
