// Minimal column-major 4x4 matrices for the camera (OpenGL conventions).
#pragma once

#include <array>
#include <cmath>

#include "../common/vec3.h"

namespace sph::render {

using Mat4 = std::array<float, 16>;  // column-major: m[col * 4 + row]

inline Vec3 normalise(Vec3 a) {
  const float l = length(a);
  return l > 0.0f ? (1.0f / l) * a : a;
}

inline Mat4 look_at(Vec3 eye, Vec3 target, Vec3 up) {
  const Vec3 f = normalise(target - eye), s = normalise(cross(f, up)), u = cross(s, f);
  return {s.x, u.x, -f.x, 0.0f, s.y, u.y, -f.y, 0.0f, s.z, u.z, -f.z, 0.0f,
          -dot(s, eye), -dot(u, eye), dot(f, eye), 1.0f};
}

inline Mat4 perspective(float fovy_radians, float aspect, float near, float far) {
  const float t = 1.0f / std::tan(0.5f * fovy_radians);
  Mat4 m{};
  m[0] = t / aspect;
  m[5] = t;
  m[10] = (far + near) / (near - far);
  m[11] = -1.0f;
  m[14] = 2.0f * far * near / (near - far);
  return m;
}

inline Vec3 transform_direction(const Mat4& m, Vec3 d) {
  return {m[0] * d.x + m[4] * d.y + m[8] * d.z, m[1] * d.x + m[5] * d.y + m[9] * d.z,
          m[2] * d.x + m[6] * d.y + m[10] * d.z};
}

}  // namespace sph::render
