// Eigen views of a rigid body's double-precision state (rigid_body.h), for the host code that moves bodies
// (rigid_body.cpp) and makes them touch (body_contact.cpp).
#pragma once

#include <array>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "rigid_body.h"

namespace sph {

inline Eigen::Vector3d e3(const BodyVector& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }
inline BodyVector b3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
// (w, x, y, z) as stored, body to world.
inline Eigen::Quaterniond quaternion(const std::array<double, 4>& q) { return Eigen::Quaterniond(q[0], q[1], q[2], q[3]); }

}  // namespace sph
