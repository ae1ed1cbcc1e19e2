// Orbit camera: yaw and pitch around a target, distance to zoom, target moves to pan.
#pragma once

#include <algorithm>
#include <cmath>

#include "math3d.h"

namespace sph::render {

struct OrbitCamera {
  Vec3 target{0.0f, 0.0f, 0.0f};
  float distance = 1.0f;
  float yaw = 0.0f;     // radians around +y; 0 looks along -z (front view)
  float pitch = 0.25f;  // radians above the horizon
  float fovy = 0.8f;

  Vec3 eye() const {
    const float c = std::cos(pitch);
    return target + distance * Vec3{c * std::sin(yaw), std::sin(pitch), c * std::cos(yaw)};
  }
  Mat4 view() const { return look_at(eye(), target, Vec3{0.0f, 1.0f, 0.0f}); }
  Mat4 projection(float aspect) const { return perspective(fovy, aspect, 0.01f * distance, 100.0f * distance); }

  void orbit(float dx, float dy) {
    yaw -= dx;
    pitch = std::clamp(pitch + dy, -1.5f, 1.5f);
  }
  void zoom(float factor) { distance = std::clamp(distance * factor, 1e-3f, 1e4f); }
  void pan(float dx, float dy) {
    const Mat4 v = view();
    const Vec3 right{v[0], v[4], v[8]}, up{v[1], v[5], v[9]};
    target += (distance * -dx) * right + (distance * dy) * up;
  }
  // Frames a box: target at its centre, distance so that it fits the view.
  void frame(Vec3 lo, Vec3 hi) {
    target = 0.5f * (lo + hi);
    distance = std::max(0.62f * length(hi - lo) / std::tan(0.5f * fovy), 1e-3f);
  }
};

}  // namespace sph::render
