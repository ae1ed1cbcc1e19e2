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

std::vector<RigidBody> place_rigid_bodies(const Scene& scene, const SimConstants& c, double spacing) {
  std::vector<RigidBody> out;
  std::vector<std::pair<Vec3d, Vec3d>> boxes;  // each body's bounding box where it starts
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& spec = scene.bodies[i];
    const std::string label =
        "bodies." + std::to_string(i) + (spec.mesh ? " (mesh)" : spec.sphere ? " (sphere)" : " (box)");
    const auto refuse = [&](const std::string& why) { throw SceneError(scene.source + ": " + label + ": " + why); };
    MeshSolid solid;  // a mesh body's surface where it starts
    Vec3d lo, hi;
    if (spec.mesh) {
      try {
        solid.mesh = load_obj_mesh(spec.file, MeshPoint{spec.scale[0], spec.scale[1], spec.scale[2]},
                                   MeshPoint{spec.translate[0], spec.translate[1], spec.translate[2]});
      } catch (const std::exception& e) {
        refuse(e.what());
      }
      const std::string problem = mesh_closure_problem(solid.mesh);
      if (!problem.empty()) refuse(spec.file + ": " + problem + "; a body's mesh must bound a solid");
      solid.slip = float(spec.slip);
      lo = solid.mesh.lo;
      hi = solid.mesh.hi;
    } else {
      bounds(spec, lo, hi);
    }
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
      const auto& [lo2, hi2] = boxes[j];
      bool apart = false;
      for (int a = 0; a < 3; ++a) apart = apart || hi[std::size_t(a)] <= lo2[std::size_t(a)] || hi2[std::size_t(a)] <= lo[std::size_t(a)];
      if (!apart) refuse("its bounding box overlaps that of bodies." + std::to_string(j) + " where they start");
    }
    boxes.emplace_back(lo, hi);
    RigidBody b;
    b.label = label;
    b.sphere = spec.sphere;
    b.mesh = spec.mesh;
    b.motion = spec.prescribed ? BodyMotion::Prescribed : spec.free ? BodyMotion::Free : BodyMotion::Fixed;
    b.amplitude = spec.amplitude;
    b.period = spec.period;
    b.angle = spec.angle;
    b.axis = spec.axis;
    b.pivot = spec.pivot;
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // its principal axes in the world (columns)
    const double pi = 3.14159265358979323846;
    const double ex = hi[0] - lo[0], ey = hi[1] - lo[1], ez = hi[2] - lo[2];
    double volume = ex * ey * ez;  // [m^3]
    if (spec.sphere) {
      volume = 4.0 / 3.0 * pi * spec.radius * spec.radius * spec.radius;
      b.mass = spec.mass > 0.0 ? spec.mass : spec.density * volume;
      const double moment = 0.4 * b.mass * spec.radius * spec.radius;
      b.inertia = {moment, moment, moment};
      b.half_extent = {spec.radius, spec.radius, spec.radius};
      b.centre = spec.center;
    } else if (spec.mesh) {  // mass properties from the surface; its frame along the principal axes
      const MeshMassProperties props = mesh_mass_properties(solid.mesh);
      if (!(props.volume > 0.0)) refuse(spec.file + ": it encloses no volume");
      volume = props.volume;
      b.mass = spec.mass > 0.0 ? spec.mass : spec.density * props.volume;
      Eigen::Matrix3d inertia;
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) inertia(r, k) = props.inertia[std::size_t(r)][std::size_t(k)] * b.mass / props.volume;
      // Already diagonal (a mesh along the world's axes, or one whose moments are equal in a plane, where any
      // axes of that plane are principal): keep the world's axes, so that the body's frame and its bounding
      // box for contact are the mesh's own.
      const Eigen::Matrix3d off = inertia - Eigen::Matrix3d(inertia.diagonal().asDiagonal());
      if (off.norm() <= 1e-9 * inertia.trace()) {
        b.inertia = b3(inertia.diagonal());
      } else {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(inertia);
        axes = principal.eigenvectors();
        if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
        b.inertia = b3(principal.eigenvalues());
      }
      b.centre = props.centroid;
      const Eigen::Quaterniond q(axes);
      b.orientation = {q.w(), q.x(), q.y(), q.z()};
      b.surface = solid.mesh;
      Eigen::Vector3d reach = Eigen::Vector3d::Zero();
      for (MeshPoint& v : b.surface.vertices) {
        const Eigen::Vector3d local = axes.transpose() * (e3(v) - e3(b.centre));
        v = b3(local);
        b.hull.push_back(v);
        reach = reach.cwiseMax(local.cwiseAbs());
      }
      b.surface.lo = b3(-reach);
      b.surface.hi = b3(reach);
      b.half_extent = b3(reach);
    } else {
      b.mass = spec.mass > 0.0 ? spec.mass : spec.density * ex * ey * ez;
      b.inertia = {b.mass * (ey * ey + ez * ez) / 12.0, b.mass * (ex * ex + ez * ez) / 12.0, b.mass * (ex * ex + ey * ey) / 12.0};
      b.half_extent = {0.5 * ex, 0.5 * ey, 0.5 * ez};
      b.centre = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
      for (int k = 0; k < 8; ++k)
        b.hull.push_back({(k & 1 ? 0.5 : -0.5) * ex, (k & 2 ? 0.5 : -0.5) * ey, (k & 4 ? 0.5 : -0.5) * ez});
    }
    if (!(b.mass > 0.0)) refuse("its mass is not positive");
    // The coupling is explicit: a body far lighter than the fluid it displaces is accelerated by the fluid's
    // added mass faster than a step can follow, and the run blows up (a 1e-9 kg box reached 1e9 m/s).
    double lightest = 1e300;
    for (int32_t f = 0; f < c.num_fluids; ++f) lightest = std::min(lightest, double(c.fluids[f].rest_density));
    if (b.mass / volume < 0.01 * lightest) {
      std::ostringstream os;
      os << "its density, " << b.mass / volume << " kg/m^3 (mass " << b.mass << " kg over " << volume
         << " m^3), is below 1% of the fluid's (" << lightest << " kg/m^3): the explicit coupling cannot move a body "
         << "that light (it blows up); allowed: at least " << 0.01 * lightest << " kg/m^3";
      refuse(os.str());
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
    out.push_back(std::move(b));
  }
  return out;
}

void sample_rigid_bodies(const Scene& scene, const SimConstants& c, double spacing, double max_particles,
                         std::vector<RigidBody>& bodies, std::vector<std::string>& report) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    RigidBody& b = bodies[i];
    const BodySpec& spec = scene.bodies[i];
    const auto refuse = [&](const std::string& why) { throw SceneError(scene.source + ": " + b.label + ": " + why); };
    const Eigen::Matrix3d axes = quaternion(b.orientation).toRotationMatrix();
    // Its particles: the body alone as an obstacle (its own volumes), then in its frame (relative to its
    // centre of mass, along its axes).
    SimConstants alone = c;
    std::vector<MeshSolid> meshes;
    if (b.mesh) {  // its surface back where it is
      MeshSolid solid;
      solid.mesh = b.surface;
      solid.slip = float(spec.slip);
      for (std::size_t v = 0; v < solid.mesh.vertices.size(); ++v)
        solid.mesh.vertices[v] = b3(e3(b.centre) + axes * e3(b.surface.vertices[v]));
      update_bounds(solid.mesh);
      alone.num_shapes = 0;
      meshes.push_back(std::move(solid));
    } else {
      alone.num_shapes = 1;
      alone.shapes[0] = body_shape(spec);
    }
    std::vector<std::string> notes;
    try {
      b.local = sample_boundary_particles(alone, meshes, spacing, max_particles, notes);
      b.spacing = spacing;
    } catch (const std::invalid_argument& e) {
      refuse(e.what());
    }
    if (b.local.size() == 0) refuse("no boundary particle samples it at spacing " + std::to_string(spacing) + " m; make it larger");
    const Eigen::Matrix3f to_body = axes.transpose().cast<float>();
    const Eigen::Vector3f centre = e3(b.centre).cast<float>();
    const auto local = [&](const Vec3& x, bool point) {
      const Eigen::Vector3f v = to_body * (point ? Eigen::Vector3f(x.x, x.y, x.z) - centre : Eigen::Vector3f(x.x, x.y, x.z));
      return Vec3{v.x(), v.y(), v.z()};
    };
    b.radius = 0.0;
    for (std::size_t k = 0; k < b.local.size(); ++k) {
      Vec4& p = b.local.pos_volume[k];
      p = with_w(local(xyz(p), true), p.w);
      Vec4& nd = b.local.normal_depth[k];
      nd = with_w(local(xyz(nd), false), nd.w);
      b.radius = std::max(b.radius, double(length(xyz(p))));
    }
    regrid_boundary_particles(b.local, c.kernel.h);
    std::ostringstream os;
    os << b.label << ": " << b.local.size() << " boundary particles, mass " << b.mass << " kg, "
       << (spec.prescribed ? "prescribed" : spec.free ? "free" : "fixed");
    report.push_back(os.str());
  }
}

std::vector<RigidBody> make_rigid_bodies(const Scene& scene, const SimConstants& c, double spacing, double max_particles,
                                         std::vector<std::string>& report) {
  std::vector<RigidBody> bodies = place_rigid_bodies(scene, c, spacing);
  sample_rigid_bodies(scene, c, spacing, max_particles, bodies, report);
  return bodies;
}

}  // namespace sph
