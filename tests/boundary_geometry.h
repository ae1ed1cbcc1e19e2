// Geometry in double precision for the penalty boundaries' tests (test_boundaries.cpp, test_boundary_runs.cpp):
// a small vector type, the signed distance of a point to a shape's allowed region, and seeded random draws.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include "common/boundaries.h"

namespace sph_test {

using sph::Shape;
using sph::ShapeType;
using sph::Vec3;

struct D3 {
  double x, y, z;
};
inline D3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
inline Vec3 f3(D3 v) { return {float(v.x), float(v.y), float(v.z)}; }
inline D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline D3 operator*(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dotd(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double lend(D3 a) { return std::sqrt(dotd(a, a)); }
inline D3 unit(D3 a) { return (1.0 / lend(a)) * a; }
inline double comp(const D3& a, int axis) { return axis == 0 ? a.x : (axis == 1 ? a.y : a.z); }
inline double& ref(D3& a, int axis) { return axis == 0 ? a.x : (axis == 1 ? a.y : a.z); }

// Signed distance to the boundary, positive in the allowed region (first order for quadrics, and for
// box corners the smallest per-axis distance, which is all an inside test needs).
inline double allowed_distance(const Shape& s, D3 x) {
  switch (s.type) {
    case ShapeType::Box: {
      const D3 lo = d3(s.a), hi = d3(s.b);
      if (s.keep_inside) {
        double m = 1e30;
        for (int i = 0; i < 3; ++i) {
          m = std::min(m, comp(x, i) - comp(lo, i));
          if (!(i == 1 && s.open_top)) m = std::min(m, comp(hi, i) - comp(x, i));
        }
        return m;
      }
      double m = -1e30;  // obstacle: allowed outside, largest per-axis distance past a face
      for (int i = 0; i < 3; ++i) m = std::max({m, comp(lo, i) - comp(x, i), comp(x, i) - comp(hi, i)});
      return m;
    }
    case ShapeType::Plane:
      return dotd(x - d3(s.a), d3(s.b));
    case ShapeType::Sphere: {
      const double r = lend(x - d3(s.a));
      return s.keep_inside ? s.radius - r : r - s.radius;
    }
    case ShapeType::Quadric: {
      const double h[4] = {x.x, x.y, x.z, 1.0};
      double f = 0.0, g[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) f += h[i] * double(s.q[4 * i + j]) * h[j];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) g[i] += 2.0 * double(s.q[4 * i + j]) * h[j];
      return f / std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    }
  }
  return 0.0;
}

// Seeded random numbers for the tests' samples: one engine, drawn in the order of the calls.
class RandomDraws {
 public:
  explicit RandomDraws(unsigned seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  D3 direction() {
    std::normal_distribution<double> g;
    return unit({g(rng_), g(rng_), g(rng_)});
  }

 private:
  std::mt19937 rng_;
};

}  // namespace sph_test
