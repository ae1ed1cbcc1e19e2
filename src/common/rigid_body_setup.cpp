#include "rigid_body_setup.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "body_math.h"
#include "setup_checks.h"

namespace sph {
namespace {

// The body as an obstacle shape where it starts.
Shape body_shape(const BodySpec& b) {
  Shape s{};
  s.type = b.sphere ? ShapeType::Sphere : ShapeType::Box;
  s.keep_inside = 0;
  s.slip = float(b.slip);
  if (b.sphere) {
    s.a = Vec3{float(b.center[0]), float(b.center[1]), float(b.center[2])};
    s.radius = float(b.radius);
  } else {
    s.a = Vec3{float(b.min[0]), float(b.min[1]), float(b.min[2])};
    s.b = Vec3{float(b.max[0]), float(b.max[1]), float(b.max[2])};
  }
  return s;
}

void bounds(const BodySpec& b, Vec3d& lo, Vec3d& hi) {
  for (int i = 0; i < 3; ++i) {
    lo[std::size_t(i)] = b.sphere ? b.center[std::size_t(i)] - b.radius : b.min[std::size_t(i)];
    hi[std::size_t(i)] = b.sphere ? b.center[std::size_t(i)] + b.radius : b.max[std::size_t(i)];
  }
}

// The bounding box of body b at its current pose (a box's corners turned by its orientation).
void pose_bounds(const RigidBody& b, Vec3d& lo, Vec3d& hi) {
  const Eigen::Matrix3d R = quaternion(b.orientation).toRotationMatrix();
  const Eigen::Vector3d h = e3(b.half_extent);
  const Eigen::Vector3d reach = b.sphere ? h : Eigen::Vector3d(R.cwiseAbs() * h);
  lo = b3(e3(b.centre) - reach);
  hi = b3(e3(b.centre) + reach);
}

// The first box container whose walls the box [lo, hi] crosses (not through an open top), or -1.
int32_t crossed_container(const SimConstants& c, const Vec3d& lo, const Vec3d& hi) {
  for (int32_t s = 0; s < c.num_shapes; ++s) {
    const Shape& w = c.shapes[s];
    if (w.type != ShapeType::Box || !w.keep_inside) continue;
    const double wl[3] = {w.a.x, w.a.y, w.a.z}, wh[3] = {w.b.x, w.b.y, w.b.z};
    for (int a = 0; a < 3; ++a)
      if (lo[std::size_t(a)] < wl[a] || (hi[std::size_t(a)] > wh[a] && !(a == 1 && w.open_top))) return s;
  }
  return -1;
}

}  // namespace

double body_clearance(const BodySpec& b, const Vec3d& p) { return boundary_clearance(body_shape(b), p); }

std::vector<RigidBody> make_rigid_bodies(const Scene& scene, const SimConstants& c, double spacing, double max_particles,
                                         std::vector<std::string>& report) {
  std::vector<RigidBody> out;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    const std::string label = "bodies." + std::to_string(i) + (spec.sphere ? " (sphere)" : " (box)");
    const auto refuse = [&](const std::string& why) { throw SceneError(scene.source + ": " + label + ": " + why); };
    Vec3d lo, hi;
    bounds(spec, lo, hi);
    for (std::size_t a = 0; a < 3; ++a)
      if (hi[a] - lo[a] < 2.0 * spacing) {
        std::ostringstream os;
        os << "it is " << hi[a] - lo[a] << " m thick along axis " << "xyz"[a] << ", less than two particle spacings ("
           << 2.0 * spacing << " m): its boundary particles could not tell its faces apart; make it thicker or refine the resolution";
        refuse(os.str());
      }
    const int32_t crossed = crossed_container(c, lo, hi);
    if (crossed >= 0)
      refuse("it crosses a wall of boundaries." + std::to_string(crossed) + " (box container) where it starts; place it inside");
    for (std::size_t j = 0; j < i; ++j) {
      Vec3d lo2, hi2;
      bounds(scene.bodies[j], lo2, hi2);
      bool apart = false;
      for (int a = 0; a < 3; ++a) apart = apart || hi[std::size_t(a)] <= lo2[std::size_t(a)] || hi2[std::size_t(a)] <= lo[std::size_t(a)];
      if (!apart) refuse("its bounding box overlaps that of bodies." + std::to_string(j) + " where they start");
    }
    RigidBody b;
    b.label = label;
    b.sphere = spec.sphere;
    b.motion = spec.prescribed ? BodyMotion::Prescribed : spec.free ? BodyMotion::Free : BodyMotion::Fixed;
    b.amplitude = spec.amplitude;
    b.period = spec.period;
    b.angle = spec.angle;
    b.axis = spec.axis;
    b.pivot = spec.pivot;
    const double pi = 3.14159265358979323846;
    const double ex = hi[0] - lo[0], ey = hi[1] - lo[1], ez = hi[2] - lo[2];
    const double volume = spec.sphere ? 4.0 / 3.0 * pi * spec.radius * spec.radius * spec.radius : ex * ey * ez;
    b.mass = spec.mass > 0.0 ? spec.mass : spec.density * volume;
    if (spec.sphere) {
      const double moment = 0.4 * b.mass * spec.radius * spec.radius;
      b.inertia = {moment, moment, moment};
      b.half_extent = {spec.radius, spec.radius, spec.radius};
      b.centre = spec.center;
    } else {
      b.inertia = {b.mass * (ey * ey + ez * ez) / 12.0, b.mass * (ex * ex + ez * ez) / 12.0, b.mass * (ex * ex + ey * ey) / 12.0};
      b.half_extent = {0.5 * ex, 0.5 * ey, 0.5 * ez};
      b.centre = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    }
    b.start = b.centre;
    if (spec.prescribed) {  // its whole stroke must stay inside the containers: 41 poses over a period
      for (int k = 0; k <= 40; ++k) {
        RigidBody pose = b;
        prescribed_pose(pose, b.period * k / 40.0);
        Vec3d plo, phi;
        pose_bounds(pose, plo, phi);
        const int32_t through = crossed_container(c, plo, phi);
        if (through >= 0)
          refuse("its oscillation carries it through a wall of boundaries." + std::to_string(through) +
                 "; lower the amplitude or angle");
      }
    }
    // Its particles: the body alone as an obstacle (its own volumes), then relative to its centre.
    SimConstants alone = c;
    alone.num_shapes = 1;
    alone.shapes[0] = body_shape(spec);
    std::vector<std::string> notes;
    try {
      b.local = sample_boundary_particles(alone, {}, spacing, max_particles, notes);
      b.spacing = spacing;
    } catch (const std::invalid_argument& e) {
      refuse(e.what());
    }
    if (b.local.size() == 0) refuse("no boundary particle samples it at spacing " + std::to_string(spacing) + " m; make it larger");
    const Vec3 centre{float(b.centre[0]), float(b.centre[1]), float(b.centre[2])};
    for (Vec4& p : b.local.pos_volume) {
      p = with_w(xyz(p) - centre, p.w);
      b.radius = std::max(b.radius, double(length(xyz(p))));
    }
    regrid_boundary_particles(b.local, c.kernel.h);
    std::ostringstream os;
    os << label << ": " << b.local.size() << " boundary particles, mass " << b.mass << " kg, "
       << (spec.prescribed ? "prescribed" : spec.free ? "free" : "fixed");
    report.push_back(os.str());
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace sph
