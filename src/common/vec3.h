// A three-component float vector usable on host and device. Single precision everywhere, so the serial
// reference and the device back ends round the same way.
#pragma once

#include <cmath>

#include "sph_hd.h"

namespace sph {

struct Vec3 {
  float x, y, z;
};

SPH_HD inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
SPH_HD inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
SPH_HD inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
SPH_HD inline Vec3 operator*(float s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
SPH_HD inline Vec3 operator*(Vec3 a, float s) { return {s * a.x, s * a.y, s * a.z}; }
SPH_HD inline Vec3& operator+=(Vec3& a, Vec3 b) {
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
SPH_HD inline Vec3& operator-=(Vec3& a, Vec3 b) {
  a.x -= b.x;
  a.y -= b.y;
  a.z -= b.z;
  return a;
}
SPH_HD inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
SPH_HD inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
SPH_HD inline float length2(Vec3 a) { return dot(a, a); }
SPH_HD inline float length(Vec3 a) { return sqrtf(dot(a, a)); }

// A vector and a fourth value in one 16-byte aligned record, so that a GPU reads a neighbour's position
// and mass (or velocity and 1 / rho) in one 128-bit load instead of three or four scalar loads (issue 11,
// item 4). The neighbour loops read such packed copies (SPH_DERIVED_FIELDS in particle_state.h).
struct alignas(16) Vec4 {
  float x, y, z, w;
};
static_assert(sizeof(Vec4) == 16 && alignof(Vec4) == 16, "one 128-bit load per record");

SPH_HD inline Vec4 with_w(Vec3 a, float w) { return {a.x, a.y, a.z, w}; }
SPH_HD inline Vec3 xyz(Vec4 a) { return {a.x, a.y, a.z}; }
SPH_HD inline Vec3 xyz(Vec3 a) { return a; }

}  // namespace sph
