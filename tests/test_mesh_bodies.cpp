// Rigid bodies read from triangle meshes (issue 13: "bodies: box, sphere, or mesh"): mass, centre and inertia
// from the surface match the analytic box they describe, in any orientation, and a mesh box floats as the
// box does.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "common/body_math.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

const std::string kBox12 = std::string(SPH_SOURCE_DIR) + "/tests/data/box_12.obj";

sph::BodySpec mesh_body(const std::string& file, sph::Vec3d scale, sph::Vec3d translate, double density) {
  sph::BodySpec b;
  b.mesh = true;
  b.file = file;
  b.scale = scale;
  b.translate = translate;
  b.density = density;
  return b;
}

// floating_box.json's set-up with `body` in place of its box.
std::vector<sph::RigidBody> made(const sph::BodySpec& body) {
  sph::Scene scene = scene_file("floating_box.json");
  scene.bodies = {body};
  sph::Simulation sim(scene, cpu_factory(), 0.01);
  return sim.backend().bodies();
}

// The world inertia tensor R diag(I) R^T of a body [kg m^2].
Eigen::Matrix3d world_inertia(const sph::RigidBody& b) {
  const Eigen::Matrix3d R = sph::quaternion(b.orientation).toRotationMatrix();
  return R * sph::e3(b.inertia).asDiagonal() * R.transpose();
}

}  // namespace

TEST_CASE("mesh bodies: a box of 12 triangles weighs, balances and turns as the box shape", "[bodies][mesh_bodies]") {
  sph::BodySpec box;
  box.min = {0.16, 0.16, 0.06};
  box.max = {0.24, 0.22, 0.14};
  box.density = 500.0;
  const sph::RigidBody a = made(box).at(0);
  const sph::RigidBody m = made(mesh_body(kBox12, {0.08, 0.06, 0.08}, {0.16, 0.16, 0.06}, 500.0)).at(0);
  CHECK(m.mesh);
  CHECK_THAT(m.mass, Catch::Matchers::WithinRel(a.mass, 1e-12));
  CHECK((sph::e3(m.centre) - sph::e3(a.centre)).norm() <= 1e-12);
  CHECK((world_inertia(m) - world_inertia(a)).norm() <= 1e-9 * world_inertia(a).norm());
  // Its particles are the box's (the same sampling through the mesh, boundary_particles tests), in its frame.
  CHECK(m.local.size() == a.local.size());
  CHECK(std::fabs(m.radius - a.radius) <= 1e-6);
  CHECK(m.orientation == a.orientation);  // along the world's axes, as the mesh is
}

TEST_CASE("mesh bodies: turned 30 degrees, the mesh's inertia is the box's turned", "[bodies][mesh_bodies]") {
  // The unit cube scaled to 0.08 x 0.03 x 0.05 m and turned about z by 30 degrees, written as an OBJ here.
  const double pi = 3.14159265358979323846, t = pi / 6.0, sx = 0.08, sy = 0.03, sz = 0.05;
  const std::string path = std::string(SPH_BINARY_DIR) + "/turned_box.obj";
  {
    std::ifstream in(kBox12);
    std::ofstream out(path);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("v ", 0) == 0) {
        double x, y, z;
        std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z);
        x = (x - 0.5) * sx, y = (y - 0.5) * sy, z = (z - 0.5) * sz;
        char buf[128];
        std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g", 0.2 + x * std::cos(t) - y * std::sin(t),
                      0.3 + x * std::sin(t) + y * std::cos(t), 0.1 + z);
        out << buf << "\n";
      } else {
        out << line << "\n";
      }
    }
  }
  // tinyobjloader keeps coordinates in single precision: the vertices carry errors of about 1e-8 m, so mass,
  // centre and inertia agree to float's precision here, not double's.
  const sph::RigidBody m = made(mesh_body(path, {1, 1, 1}, {0, 0, 0}, 800.0)).at(0);
  const double mass = 800.0 * sx * sy * sz;
  CHECK_THAT(m.mass, Catch::Matchers::WithinRel(mass, 1e-6));
  CHECK((sph::e3(m.centre) - Eigen::Vector3d(0.2, 0.3, 0.1)).norm() <= 1e-7);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d box_moments(mass * (sy * sy + sz * sz) / 12.0, mass * (sx * sx + sz * sz) / 12.0,
                                    mass * (sx * sx + sy * sy) / 12.0);
  const Eigen::Matrix3d expected = R * box_moments.asDiagonal() * R.transpose();
  CHECK((world_inertia(m) - expected).norm() <= 1e-6 * expected.norm());
  // Its frame is along its principal axes: its particles, turned back, fill the unturned box.
  double worst = 0.0;
  const Eigen::Vector3d half(0.5 * sx, 0.5 * sy, 0.5 * sz);
  const Eigen::Matrix3d to_world = sph::quaternion(m.orientation).toRotationMatrix();
  for (const sph::Vec4& p : m.local.pos_volume) {
    const Eigen::Vector3d local = R.transpose() * to_world * Eigen::Vector3d(p.x, p.y, p.z);
    worst = std::max(worst, (local.cwiseAbs() - half).maxCoeff());
  }
  CHECK(worst <= 1e-5);  // every particle inside the box (it samples the solid below its surface)
}

TEST_CASE("mesh bodies: a mesh box of density 500 floats half submerged", "[bodies][mesh_bodies]") {
  // As the box test of test_rigid_bodies.cpp, with the box read from tests/data/box_12.obj, at the scene's own
  // spacing (1 cm: 6 x 8 x 8 spacings, where the mesh's sampling, anchored at its corner, and the box's,
  // stretched to fit its sides, are the same particles; at 1.25 cm they differ).
  const double height = 0.06, footprint = 0.08 * 0.08, surface = 0.4 * 0.2 - footprint;
  sph::Scene scene = scene_file("floating_box.json");
  scene.bodies = {mesh_body(kBox12, {0.08, 0.06, 0.08}, {0.16, 0.16, 0.06}, 500.0)};
  sph::Simulation sim(scene, cpu_factory(), 1.5);
  const double mean_centre = mean_body_height(sim, 1.0, 1.5);
  const double submerged_volume = sim.backend().bodies().at(0).mass / 1000.0;
  const double level = 0.15 + submerged_volume / surface;
  const double submerged = (level - (mean_centre - 0.5 * height)) / height;
  INFO("centre " << mean_centre << " m, still-water level " << level << " m: " << submerged << " of its height submerged");
  CHECK(std::fabs(submerged - 0.5) <= 0.05);
}
