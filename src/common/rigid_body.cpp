#include "rigid_body.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "body_math.h"

namespace sph {
namespace {

// Contact with the walls of box containers, simple and robust: each corner of a box body (a mesh's vertex) (a sphere's lowest
// point towards each wall) found behind a wall is pushed back out (the body moves by the deepest
// penetration along each wall's normal) and gets an inelastic impulse at that point, j = -v_n /
// (1/M + n.((I^-1 (r x n)) x r)), so that it stops moving into the wall and the body turns about the contact
// (a box landing on an edge settles flat under gravity).
void contact_with_containers(RigidBody& b, const SimConstants& c) {
  const Eigen::Matrix3d R = quaternion(b.orientation).toRotationMatrix();
  const Eigen::Matrix3d inv_inertia = R * e3(b.inertia).cwiseInverse().asDiagonal() * R.transpose();
  std::vector<Eigen::Vector3d> points;  // contact candidates relative to the centre
  if (b.sphere) {
    for (int axis = 0; axis < 3; ++axis)
      for (const double side : {-1.0, 1.0}) points.push_back(side * b.half_extent[0] * Eigen::Vector3d::Unit(axis));
  } else {
    for (const BodyVector& corner : b.hull) points.push_back(R * e3(corner));
  }
  Eigen::Vector3d x = e3(b.centre), v = e3(b.velocity), w = e3(b.omega);
  for (int32_t s = 0; s < c.num_shapes; ++s) {
    const Shape& shape = c.shapes[s];
    if (shape.type != ShapeType::Box || !shape.keep_inside) continue;
    const double lo[3] = {shape.a.x, shape.a.y, shape.a.z}, hi[3] = {shape.b.x, shape.b.y, shape.b.z};
    for (int axis = 0; axis < 3; ++axis)
      for (const int side : {0, 1}) {
        if (side == 1 && axis == 1 && shape.open_top) continue;
        const Eigen::Vector3d n = (side == 0 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(axis);  // into the tank
        const double wall = side == 0 ? lo[axis] : hi[axis];
        double deepest = 0.0;
        for (const Eigen::Vector3d& r : points) {
          const double depth = (side == 0 ? wall - (x + r)(axis) : (x + r)(axis) - wall);
          if (depth <= 0.0) continue;
          deepest = std::max(deepest, depth);
          const Eigen::Vector3d vc = v + w.cross(r);
          const double vn = vc.dot(n);
          if (vn >= 0.0) continue;
          const Eigen::Vector3d rn = r.cross(n);
          const double j = -vn / (1.0 / b.mass + n.dot((inv_inertia * rn).cross(r)));
          v += (j / b.mass) * n;
          w += inv_inertia * (j * rn);
        }
        if (deepest > 0.0) {
          x += deepest * n;
          b.contact = true;
        }
      }
  }
  b.centre = b3(x);
  b.velocity = b3(v);
  b.omega = b3(w);
}

}  // namespace

BodyView RigidBody::view(const BoundaryView& local_view, float h) const {
  const Eigen::Matrix3d R = quaternion(orientation).toRotationMatrix();
  const auto col = [&](int i) { return Vec3{float(R(0, i)), float(R(1, i)), float(R(2, i))}; };
  const auto f3 = [](const BodyVector& v) { return Vec3{float(v[0]), float(v[1]), float(v[2])}; };
  const float reach = float(radius) + h;
  return BodyView{local_view, f3(centre), col(0), col(1), col(2), f3(velocity), f3(omega), reach * reach};
}

double depth_in_body(const RigidBody& b, const BodyVector& p) {
  const Eigen::Vector3d local = quaternion(b.orientation).conjugate() * (e3(p) - e3(b.centre));
  if (b.sphere) return b.half_extent[0] - local.norm();
  if (b.mesh) {  // outside its bounding box: outside it by at least the distance to the box (no triangle asked)
    const Eigen::Vector3d gap = (local.cwiseAbs() - e3(b.half_extent)).cwiseMax(0.0);
    if (gap.squaredNorm() > 0.0) return -gap.norm();
    return -mesh_signed_distance(b.surface, {local.x(), local.y(), local.z()});
  }
  return (e3(b.half_extent) - local.cwiseAbs()).minCoeff();
}

void prescribed_pose(RigidBody& b, double t) {
  const double w = 2.0 * 3.14159265358979323846 / b.period;
  const double s = std::sin(w * t), ds = w * std::cos(w * t);  // s and its rate
  const Eigen::Vector3d axis = e3(b.axis), pivot = e3(b.pivot), shift = e3(b.amplitude);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(b.angle * s, axis));
  const Eigen::Vector3d arm = q * (e3(b.start) - pivot);  // from the pivot to the centre, turned
  const Eigen::Vector3d omega = (b.angle * ds) * axis;
  b.centre = b3(pivot + arm + shift * s);
  b.orientation = {q.w(), q.x(), q.y(), q.z()};
  b.omega = b3(omega);
  b.velocity = b3(omega.cross(arm) + shift * ds);
}

void advance_body(RigidBody& b, const SimConstants& c, double dt) {
  b.contact = false;
  if (!(dt > 0.0)) return;
  if (b.motion == BodyMotion::Prescribed) {
    b.time += dt;
    prescribed_pose(b, b.time);
    return;
  }
  if (b.motion != BodyMotion::Free) return;
  const Eigen::Vector3d g(c.gravity.x, c.gravity.y, c.gravity.z);
  Eigen::Vector3d v = e3(b.velocity) + dt * (e3(b.force) / b.mass + g);
  Eigen::Quaterniond q = quaternion(b.orientation);
  const Eigen::Matrix3d R = q.toRotationMatrix();
  const Eigen::Matrix3d inertia = R * e3(b.inertia).asDiagonal() * R.transpose();
  const Eigen::Vector3d L = inertia * e3(b.omega) + dt * e3(b.torque);
  const Eigen::Vector3d omega = inertia.ldlt().solve(L);
  // q' = 0.5 [0, omega] q
  const Eigen::Quaterniond w(0.0, omega.x(), omega.y(), omega.z());
  Eigen::Quaterniond rate = w * q;
  q.coeffs() += 0.5 * dt * rate.coeffs();
  q.normalize();
  b.orientation = {q.w(), q.x(), q.y(), q.z()};
  b.velocity = b3(v);
  b.omega = b3(omega);
  const Eigen::Vector3d x = e3(b.centre) + dt * v;
  b.centre = b3(x);
  contact_with_containers(b, c);
}

}  // namespace sph
