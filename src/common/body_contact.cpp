#include "body_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "body_math.h"

namespace sph {
namespace {

constexpr int kImpulseIterations = 20;  // projected Gauss-Seidel sweeps over a pair's contact points

// A body as contact sees it: pose, axes, half extents, and how it yields. A fixed or prescribed body has
// zero inverses: it moves as it must, whatever it touches.
struct Solid {
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;  // columns: the body's axes in the world
  Eigen::Vector3d half;
  bool sphere;
  double inv_mass = 0.0;
  Eigen::Matrix3d inv_inertia = Eigen::Matrix3d::Zero();
};

Solid solid_of(const RigidBody& b) {
  Solid s{e3(b.centre), quaternion(b.orientation).toRotationMatrix(), e3(b.half_extent), b.sphere};
  if (b.motion == BodyMotion::Free) {
    s.inv_mass = 1.0 / b.mass;
    s.inv_inertia = s.axes * e3(b.inertia).cwiseInverse().asDiagonal() * s.axes.transpose();
  }
  return s;
}

// Half the extent of solid s along unit axis l.
double radius_along(const Solid& s, const Eigen::Vector3d& l) {
  if (s.sphere) return s.half.x();
  return s.half.x() * std::fabs(l.dot(s.axes.col(0))) + s.half.y() * std::fabs(l.dot(s.axes.col(1))) +
         s.half.z() * std::fabs(l.dot(s.axes.col(2)));
}

// Closest point of box b to p (p itself when inside).
Eigen::Vector3d closest_on_box(const Solid& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d local = b.axes.transpose() * (p - b.centre);
  return b.centre + b.axes * local.cwiseMax(-b.half).cwiseMin(b.half);
}

// Whether a and b overlap; if so the unit normal n from b towards a and the overlap along it [m]: the axis
// of least overlap (separating-axis test: box-box over the 6 face normals and 9 edge-edge cross products,
// face axes preferred within 1%, the usual bias against jitter; a sphere against the closest point).
bool overlap(const Solid& a, const Solid& b, Eigen::Vector3d& n, double& depth) {
  const Eigen::Vector3d d = a.centre - b.centre;
  if (a.sphere && b.sphere) {
    const double dist = d.norm();
    depth = a.half.x() + b.half.x() - dist;
    n = dist > 0.0 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d::UnitY();
    return depth > 0.0;
  }
  if (a.sphere || b.sphere) {
    const Solid& sphere = a.sphere ? a : b;
    const Solid& box = a.sphere ? b : a;
    const Eigen::Vector3d q = closest_on_box(box, sphere.centre);
    const Eigen::Vector3d out = sphere.centre - q;  // from the box towards the sphere's centre
    const double dist = out.norm();
    Eigen::Vector3d towards_sphere;
    if (dist > 0.0) {
      towards_sphere = out / dist;
      depth = sphere.half.x() - dist;
    } else {  // the centre is inside the box: out through the nearest face
      const Eigen::Vector3d local = box.axes.transpose() * (sphere.centre - box.centre);
      int axis = 0;
      double gap = box.half.x() - std::fabs(local.x());
      for (int k = 1; k < 3; ++k)
        if (box.half(k) - std::fabs(local(k)) < gap) gap = box.half(k) - std::fabs(local(k)), axis = k;
      towards_sphere = (local(axis) >= 0.0 ? 1.0 : -1.0) * box.axes.col(axis);
      depth = sphere.half.x() + gap;
    }
    n = a.sphere ? towards_sphere : Eigen::Vector3d(-towards_sphere);
    return depth > 0.0;
  }
  double best = std::numeric_limits<double>::infinity();  // the biased overlap of the axis kept
  auto test = [&](Eigen::Vector3d l, double bias) {
    const double len = l.norm();
    if (len < 1e-9) return true;  // parallel edges: no axis
    l /= len;
    const double o = radius_along(a, l) + radius_along(b, l) - std::fabs(l.dot(d));
    if (o <= 0.0) return false;
    if (o * bias < best) best = o * bias, depth = o, n = l.dot(d) >= 0.0 ? l : Eigen::Vector3d(-l);
    return true;
  };
  for (int k = 0; k < 3; ++k)
    if (!test(a.axes.col(k), 1.0) || !test(b.axes.col(k), 1.0)) return false;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      if (!test(a.axes.col(i).cross(b.axes.col(k)), 1.01)) return false;
  return true;
}

// Whether world point p lies inside solid s.
bool inside(const Solid& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d local = s.axes.transpose() * (p - s.centre);
  if (s.sphere) return local.norm() < s.half.x();
  return (local.cwiseAbs() - s.half).maxCoeff() < 0.0;
}

// Body `from`'s surface points (outer-layer particles moved out along their normal) inside `into`.
void touching_points(const RigidBody& from, const Solid& from_solid, const Solid& into, std::vector<Eigen::Vector3d>& out) {
  const BoundaryParticles& local = from.local;
  for (std::size_t i = 0; i < local.pos_volume.size(); ++i) {
    const Vec4& nd = local.normal_depth[i];
    if (nd.w > from.spacing) continue;
    const Vec4& pv = local.pos_volume[i];
    const Eigen::Vector3d p = from_solid.centre + from_solid.axes * Eigen::Vector3d(pv.x + nd.w * nd.x, pv.y + nd.w * nd.y,
                                                                                   pv.z + nd.w * nd.z);
    if (inside(into, p)) out.push_back(p);
  }
}

void pair_contact(RigidBody& a, RigidBody& b) {
  const Solid sa = solid_of(a), sb = solid_of(b);
  if (sa.inv_mass + sb.inv_mass == 0.0) return;
  Eigen::Vector3d n = Eigen::Vector3d::UnitY();
  double depth = 0.0;
  if (!overlap(sa, sb, n, depth)) return;
  std::vector<Eigen::Vector3d> points;
  touching_points(a, sa, sb, points);
  touching_points(b, sb, sa, points);
  Eigen::Vector3d va = e3(a.velocity), vb = e3(b.velocity), wa = e3(a.omega), wb = e3(b.omega);
  std::vector<double> lambda(points.size(), 0.0), k_inv(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d ra = points[i] - sa.centre, rb = points[i] - sb.centre;
    k_inv[i] = 1.0 / (sa.inv_mass + sb.inv_mass + n.dot((sa.inv_inertia * ra.cross(n)).cross(ra)) +
                      n.dot((sb.inv_inertia * rb.cross(n)).cross(rb)));
  }
  for (int sweep = 0; sweep < kImpulseIterations; ++sweep)
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d ra = points[i] - sa.centre, rb = points[i] - sb.centre;
      const double vn = ((va + wa.cross(ra)) - (vb + wb.cross(rb))).dot(n);
      const double total = std::max(0.0, lambda[i] - vn * k_inv[i]);  // accumulated, never pulling
      const double j = total - lambda[i];
      lambda[i] = total;
      va += (j * sa.inv_mass) * n;
      wa += sa.inv_inertia * (ra.cross(j * n));
      vb -= (j * sb.inv_mass) * n;
      wb -= sb.inv_inertia * (rb.cross(j * n));
    }
  const double share = sa.inv_mass / (sa.inv_mass + sb.inv_mass);
  a.centre = b3(sa.centre + share * depth * n);
  b.centre = b3(sb.centre - (1.0 - share) * depth * n);
  a.body_contact = b.body_contact = true;
  if (a.motion == BodyMotion::Free) a.velocity = b3(va), a.omega = b3(wa);
  if (b.motion == BodyMotion::Free) b.velocity = b3(vb), b.omega = b3(wb);
}

}  // namespace

void contact_between_bodies(std::vector<RigidBody>& bodies) {
  for (RigidBody& b : bodies) b.body_contact = false;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (std::size_t k = i + 1; k < bodies.size(); ++k) {
      const double reach = bodies[i].radius + bodies[k].radius + std::max(bodies[i].spacing, bodies[k].spacing);
      if ((e3(bodies[i].centre) - e3(bodies[k].centre)).squaredNorm() <= reach * reach) pair_contact(bodies[i], bodies[k]);
    }
}

}  // namespace sph
