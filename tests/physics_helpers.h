// Helpers shared by the physics tests: running a scene on the serial reference and measuring it.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "common/scene.h"
#include "common/simulation.h"
#include "cpu/cpu_backend.h"

namespace sph_test {

inline sph::BackendFactory cpu_factory() {
  return [](const sph::SimConstants& c) { return std::make_unique<sph::CpuBackend>(c); };
}

inline sph::Scene scene_file(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return sph::load_scene(std::string(SPH_SOURCE_DIR) + "/scenes/" + name, overrides);
}

// Smallest distance between any two particles (brute force; the tests use small particle counts).
inline double min_pair_distance(const sph::ParticleState& ps) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < ps.size(); ++a)
    for (std::size_t b = a + 1; b < ps.size(); ++b) {
      const double dx = ps.pos[a].x - ps.pos[b].x, dy = ps.pos[a].y - ps.pos[b].y, dz = ps.pos[a].z - ps.pos[b].z;
      best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  return best;
}

// Fraction of particles that have another particle closer than `fraction` of the spacing.
inline double clustered_fraction(const sph::ParticleState& ps, double distance) {
  std::size_t count = 0;
  for (std::size_t a = 0; a < ps.size(); ++a)
    for (std::size_t b = 0; b < ps.size(); ++b) {
      if (a == b) continue;
      const double dx = ps.pos[a].x - ps.pos[b].x, dy = ps.pos[a].y - ps.pos[b].y, dz = ps.pos[a].z - ps.pos[b].z;
      if (dx * dx + dy * dy + dz * dz < distance * distance) {
        ++count;
        break;
      }
    }
  return ps.size() ? double(count) / double(ps.size()) : 0.0;
}

// Runs sim until `until` [s] and returns rigid body `body`'s mean centre height (y) [m] over the steps that
// end after `from` [s] (0 when none do).
inline double mean_body_height(sph::Simulation& sim, double from, double until, std::size_t body = 0) {
  double sum = 0.0;
  int samples = 0;
  while (sim.time() < until) {
    sim.advance();
    if (sim.time() > from) {
      sum += sim.backend().bodies().at(body).centre[1];
      ++samples;
    }
  }
  return samples > 0 ? sum / samples : 0.0;
}

// The contact angle [degrees] of a spherical cap on a wall with the given volume [m^3] and height [m]: with R
// the sphere's radius, V = pi H^2 (3 R - H) / 3 and cos(theta) = 1 - H / R.
inline double spherical_cap_angle(double volume, double height) {
  const double pi = 3.14159265358979323846;
  const double radius = (3.0 * volume / (pi * height * height) + height) / 3.0;
  return std::acos(std::max(-1.0, std::min(1.0, 1.0 - height / radius))) * 180.0 / pi;
}

// Mean height of the 100 highest particles: the top layer of the 10 x 10 column, whatever splashes above it
// moves it little.
inline double top_layer_height(const sph::ParticleState& ps) {
  std::vector<float> y(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) y[i] = ps.pos[i].y;
  const std::size_t n = std::min<std::size_t>(100, y.size());
  std::partial_sort(y.begin(), y.begin() + std::ptrdiff_t(n), y.end(), std::greater<float>());
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += y[i];
  return n > 0 ? sum / double(n) : 0.0;
}

}  // namespace sph_test
