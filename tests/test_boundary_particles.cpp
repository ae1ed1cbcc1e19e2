// Boundary particles (issue 13, [AIA12]): the sampling and its volumes, the density a particle reads at a wall,
// in an edge and in a corner, resting columns with WCSPH, DFSPH and PBF, and the thin plate hit at 6 m/s.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <catch2/catch.hpp>

#include "common/metrics.h"
#include "common/setup_checks.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

// The tank of hydrostatic_tank.json: [0, 0.05] x [0, 0.2] x [0, 0.05].
constexpr double kWidth = 0.05, kTankHeight = 0.2;

// Densities after the grid and density phases of the scene's initial lattice on the reference.
sph::ParticleState initial_densities(const sph::Scene& scene, const sph::Setup& setup) {
  sph::CpuBackend b(setup.constants);
  b.set_boundary(setup.boundary);
  b.upload(setup.particles);
  b.build_grid();
  if (scene.solver == sph::Solver::Wcsph) b.step_phase(sph::Phase::Density, 0.0f);
  else b.initialise_forces();  // DFSPH: density (cubic spline) and alpha
  return b.download();
}

// Distance from x to the nearest of the tank's walls other than its open top (the tank is closed here).
double wall_distance(sph::Vec3 x) {
  return std::min({double(x.x), kWidth - x.x, double(x.y), kTankHeight - x.y, double(x.z), kWidth - x.z});
}

// How many of the particle's coordinates lie within one spacing of a wall: 1 at a face, 2 in an edge, 3 in
// a corner (the floor's corners: the column is far from the ceiling).
int walls_near(sph::Vec3 x, double d) {
  int n = 0;
  for (const double v : {double(x.x), double(x.y), double(x.z)}) n += v < d ? 1 : 0;
  for (const double v : {kWidth - x.x, kWidth - x.z}) n += v < d ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("boundary particles sample the tank's walls in the solid, within h, with the bulk's volume",
          "[boundary_particles]") {
  const sph::Scene scene = scene_file("hydrostatic_tank.json", {"sph.walls=particles"});
  const sph::Setup setup = sph::create_setup(scene, 1.0);
  const sph::BoundaryParticles& b = setup.boundary;
  REQUIRE(b.size() > 0);
  const double d = setup.spacing, h = setup.h;
  const double v_bulk = setup.constants.fluids[0].mass / setup.constants.fluids[0].rest_density;  // m / rho0
  double worst_face = 0.0, worst = 0.0;
  for (const sph::Vec4& p : b.pos_volume) {
    const sph::Vec3 x{p.x, p.y, p.z};
    const bool inside = x.x > 0 && x.x < kWidth && x.y > 0 && x.y < kTankHeight && x.z > 0 && x.z < kWidth;
    REQUIRE_FALSE(inside);  // in the solid
    const double ex = std::max({-double(x.x), 0.0, x.x - kWidth}), ey = std::max({-double(x.y), 0.0, x.y - kTankHeight}),
                 ez = std::max({-double(x.z), 0.0, x.z - kWidth});
    REQUIRE(std::sqrt(ex * ex + ey * ey + ez * ez) < h);  // within reach of the fluid
    const double e = std::fabs(p.w / v_bulk - 1.0);
    worst = std::max(worst, e);
    // Along the middle of a face the sampling is the fluid's lattice continued: the bulk's volume.
    if ((ex > 0) + (ey > 0) + (ez > 0) == 1) worst_face = std::max(worst_face, e);
  }
  INFO(b.size() << " boundary particles; largest |V_b / (m / rho0) - 1|: " << worst << " (faces: " << worst_face << ")");
  CHECK(worst_face <= 1e-3);
  CHECK(worst <= 1e-3);  // edges and corners too: the lattice continues around them
  // Two layers within h = 1.97 d of each face: 10 x 40 faces of the tank's sides and 10 x 10 of floor and
  // ceiling, at least (edges and corners add more).
  CHECK(b.size() >= std::size_t(2 * (4 * 10 * 40 + 2 * 10 * 10)));
  CHECK(d > 0.0);
}

TEST_CASE("boundary particles: a particle at a wall, in an edge and in a corner reads rest density",
          "[boundary_particles]") {
  // Issue 13: within 1% at a flat wall and 2% in a corner. Penalty walls, the method where it fails: there
  // the kernel reaches past the wall into nothing, and the first layer reads far below rest density.
  for (const char* solver : {"wcsph", "dfsph"}) {
    const auto worst_by_walls = [&](const char* walls) {
      const sph::Scene scene = scene_file("hydrostatic_tank.json", {std::string("solver=") + solver, std::string("sph.walls=") + walls});
      const sph::Setup setup = sph::create_setup(scene, 1.0);
      const sph::ParticleState ps = initial_densities(scene, setup);
      const double d = setup.spacing, rho0 = 1000.0;
      // The bulk's reading (the mass and the walls' volumes are fitted to the run's density kernel).
      double bulk = 0.0;
      long bulk_n = 0;
      std::vector<double> worst(4, 0.0);
      for (std::size_t i = 0; i < ps.size(); ++i) {
        const sph::Vec3 x = ps.pos[i];
        if (x.y > 0.1 - 2.5 * d) continue;  // away from the free surface
        const int n = walls_near(x, d);
        if (n == 0 && wall_distance(x) > 2.0 * d) {
          bulk += ps.density[i];
          ++bulk_n;
        }
        if (n > 0) worst[std::size_t(n)] = std::max(worst[std::size_t(n)], std::fabs(ps.density[i] / rho0 - 1.0));
      }
      REQUIRE(bulk_n > 0);
      INFO(solver << ", walls " << walls << ": bulk rho/rho0 " << bulk / double(bulk_n) / rho0 << "; worst |rho/rho0 - 1| at a face "
                  << worst[1] << ", in an edge " << worst[2] << ", in a corner " << worst[3]);
      CHECK(worst[3] > 0.0);  // the case has corners
      return worst;
    };
    const std::vector<double> particles = worst_by_walls("particles");
    const std::vector<double> penalty = worst_by_walls("penalty");
    // The mass and the walls' volumes are fitted to each solver's density kernel (the cubic spline's under
    // DFSPH, since 2026-12-02), so the bulk reads rho0; the tolerances are the walls'.
    const double tolerance_face = 0.01, tolerance_corner = 0.02;
    CHECK(particles[1] <= tolerance_face);
    CHECK(particles[2] <= tolerance_corner);
    CHECK(particles[3] <= tolerance_corner);
    CHECK(penalty[1] > 0.1);  // the method where it fails
  }
}

TEST_CASE("boundary particles: a floor sampled twice (box and plane) shares its volume", "[boundary_particles]") {
  // [AIA12]'s volumes: where two samplings overlap, each particle's V_b shrinks so that the wall still reads
  // rest density. The tank's floor again as a plane at y = 0.
  sph::Scene scene = scene_file("hydrostatic_tank.json", {"sph.walls=particles"});
  sph::BoundarySpec plane;
  plane.shape = scene.boundaries[0].shape;
  plane.shape.type = sph::ShapeType::Plane;
  plane.shape.keep_inside = 0;
  plane.shape.a = sph::Vec3{0.0f, 0.0f, 0.0f};
  plane.shape.b = sph::Vec3{0.0f, 1.0f, 0.0f};
  scene.boundaries.push_back(plane);
  const sph::Setup twice = sph::create_setup(scene, 1.0);
  scene.boundaries.pop_back();
  const sph::Setup once = sph::create_setup(scene, 1.0);
  REQUIRE(twice.boundary.size() > once.boundary.size());
  const sph::ParticleState a = initial_densities(scene, twice), b = initial_densities(scene, once);
  double worst = 0.0;
  long floor_particles = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const sph::Vec3 x = a.pos[i];
    if (x.y > twice.spacing || walls_near(x, twice.spacing) != 1) continue;  // the floor's first layer, off the sides
    worst = std::max(worst, std::fabs(a.density[i] / 1000.0 - 1.0));
    ++floor_particles;
  }
  INFO(twice.boundary.size() << " boundary particles with the plane, " << once.boundary.size() << " without; worst |rho/rho0 - 1| on the floor "
                             << worst);
  REQUIRE(floor_particles == 64);  // 8 x 8 off the side walls
  CHECK(worst <= 0.01);
}

TEST_CASE("boundary particles of spheres and quadrics lie in their solids, within h of the surface",
          "[boundary_particles]") {
  const sph::Scene scene = scene_file("obstacles.json", {"sph.walls=particles"});
  const sph::Setup setup = sph::create_setup(scene, 1.0);
  const sph::SimConstants& c = setup.constants;
  std::vector<long> per_shape(std::size_t(c.num_shapes), 0);
  for (const sph::Vec4& p : setup.boundary.pos_volume) {
    const sph::Vec3d x{p.x, p.y, p.z};
    bool in_some = false;
    for (int32_t s = 0; s < c.num_shapes; ++s) {
      const double cl = sph::boundary_clearance(c.shapes[s], x);
      if (cl < 0.0 && cl > -setup.h * (1.0 + 1e-6)) {
        in_some = true;
        ++per_shape[std::size_t(s)];
        break;
      }
    }
    REQUIRE(in_some);
    REQUIRE(p.w > 0.0f);
  }
  INFO("boundary particles per shape: tank " << per_shape[0] << ", sphere " << per_shape[1] << ", ellipsoid " << per_shape[2]);
  // A shell of thickness h: about its area times h / d^3 points.
  const double d3 = setup.spacing * setup.spacing * setup.spacing;
  const double sphere_shell = 0.5 * 4.0 * 3.14159265 * 0.06 * 0.06 * setup.h / d3;  // half above the floor
  CHECK(double(per_shape[1]) == Approx(sphere_shell).epsilon(0.3));
  CHECK(per_shape[2] > 0);
}

namespace {

struct ColumnResult {
  double top0 = 0.0, top = 0.0, interior = 0.0;
  long interior_n = 0;
};

// Mean height of the 100 highest particles, and the mean rho/rho0 - 1 of those at least h from every wall and
// from the free surface.
ColumnResult run_column(const std::vector<std::string>& overrides, double run_time) {
  std::vector<std::string> o = overrides;
  o.push_back("sph.walls=particles");
  const sph::Scene scene = scene_file("hydrostatic_tank.json", o);
  sph::Simulation sim(scene, cpu_factory(), run_time);
  const auto top_layer = [](const sph::ParticleState& ps) {
    std::vector<float> y = std::vector<float>(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) y[i] = ps.pos[i].y;
    std::partial_sort(y.begin(), y.begin() + 100, y.end(), std::greater<float>());
    double s = 0.0;
    for (int i = 0; i < 100; ++i) s += y[std::size_t(i)];
    return s / 100.0;
  };
  ColumnResult r;
  r.top0 = top_layer(sim.particles());
  while (sim.time() < run_time - 1e-9) sim.advance();
  const sph::ParticleState& ps = sim.particles();
  r.top = top_layer(ps);
  const double h = sim.setup().h;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const sph::Vec3 x = ps.pos[i];
    if (wall_distance(x) < h || x.y > r.top - h) continue;
    r.interior += ps.density[i] / 1000.0 - 1.0;
    ++r.interior_n;
  }
  if (r.interior_n > 0) r.interior /= double(r.interior_n);
  return r;
}

}  // namespace

TEST_CASE("boundary particles hold a resting column: height within a spacing, interior within 0.5%",
          "[boundary_particles]") {
  // Issue 13, for WCSPH and DFSPH over 1 s at the scene's steps. (PBF at 4 ms and 4 iterations compresses
  // the column by 3% whatever the walls, docs/results.md.)
  const double d = 0.005;
  for (const auto& o : std::vector<std::vector<std::string>>{{"solver=wcsph"}, {"solver=dfsph"}}) {
    const ColumnResult r = run_column(o, 1.0);
    INFO(o[0] << ": top layer " << r.top0 << " -> " << r.top << " m; interior (" << r.interior_n << ") mean rho/rho0 - 1 "
              << r.interior);
    REQUIRE(r.interior_n > 300);
    CHECK(std::fabs(r.top - r.top0) <= d);
    CHECK(std::fabs(r.interior) <= 0.005);
  }
}

TEST_CASE("boundary particles: a block hitting a 1 mm plate at 6 m/s stays above it", "[boundary_particles]") {
  // tests/data/thin_plate.json with the plate sampled by boundary particles (one layer: the plate is
  // thinner than a spacing); the continuous collision of boundaries.h stays on as the last line of defence.
  sph::Scene scene = sph::load_scene(std::string(SPH_SOURCE_DIR) + "/tests/data/thin_plate.json");
  scene.mirror_walls = false;
  scene.boundary_particles = true;
  sph::Simulation sim(scene, cpu_factory(), scene.run_time);
  REQUIRE(sim.setup().boundary.size() > 0);
  const sph::Shape& p = sim.setup().constants.shapes[0];
  int through = 0;
  float lowest = 1.0f;
  while (sim.time() < scene.run_time) {
    sim.advance();
    for (const sph::Vec3& x : sim.particles().pos) {
      lowest = std::min(lowest, x.y);
      if (x.y < p.a.y) ++through;
    }
  }
  INFO(sim.steps() << " steps; lowest particle at y = " << lowest << " m (plate top " << p.b.y << " m)");
  CHECK(through == 0);
  CHECK(lowest >= p.b.y);
}

namespace {

// hydrostatic_tank with walls of boundary particles and a 0.03 m box obstacle at (0.01, 0.02, 0.01): as a
// box shape, or as tests/data/box_12.obj scaled and moved there.
sph::Scene tank_with_obstacle(bool as_mesh) {
  sph::Scene scene = scene_file("hydrostatic_tank.json", {"sph.walls=particles"});
  if (as_mesh) {
    sph::MeshSpec m;
    m.file = std::string(SPH_SOURCE_DIR) + "/tests/data/box_12.obj";
    m.scale = {0.03, 0.03, 0.03};
    m.translate = {0.01, 0.02, 0.01};
    scene.meshes.push_back(m);
  } else {
    sph::BoundarySpec box;
    box.shape = scene.boundaries[0].shape;
    box.shape.keep_inside = 0;
    box.shape.a = sph::Vec3{0.01f, 0.02f, 0.01f};
    box.shape.b = sph::Vec3{0.04f, 0.05f, 0.04f};
    scene.boundaries.push_back(box);
  }
  return scene;
}

}  // namespace

TEST_CASE("boundary particles: a box read as 12 triangles from an OBJ file gives the box shape's boundary",
          "[boundary_particles][mesh]") {
  const sph::Setup shape = sph::create_setup(tank_with_obstacle(false), 1.0);
  const sph::Setup mesh = sph::create_setup(tank_with_obstacle(true), 1.0);
  REQUIRE(mesh.meshes.size() == 1);
  REQUIRE(mesh.meshes[0].mesh.triangles.size() == 12);
  // The same fluid: the particles inside the obstacle removed alike.
  CHECK(mesh.particles.size() == shape.particles.size());
  const auto sorted = [](const sph::BoundaryParticles& b) {
    std::vector<sph::Vec4> v = b.pos_volume;
    std::sort(v.begin(), v.end(), [](const sph::Vec4& p, const sph::Vec4& q) {
      const auto key = [](const sph::Vec4& a) { return std::make_tuple(std::lround(a.z * 1e5), std::lround(a.y * 1e5), std::lround(a.x * 1e5)); };
      return key(p) < key(q);
    });
    return v;
  };
  const std::vector<sph::Vec4> a = sorted(shape.boundary), b = sorted(mesh.boundary);
  REQUIRE(a.size() == b.size());
  double worst_x = 0.0, worst_v = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst_x = std::max({worst_x, std::fabs(double(a[i].x - b[i].x)), std::fabs(double(a[i].y - b[i].y)), std::fabs(double(a[i].z - b[i].z))});
    worst_v = std::max(worst_v, std::fabs(double(a[i].w / b[i].w) - 1.0));
  }
  INFO(a.size() << " boundary particles; largest position difference " << worst_x << " m, volume " << worst_v);
  CHECK(worst_x <= 1e-6);
  CHECK(worst_v <= 1e-4);
}

TEST_CASE("meshes: a missing, open, inside-out or empty OBJ file, or a mesh too small to sample, is refused by name",
          "[boundary_particles][mesh]") {
  const auto refusal = [](const std::string& file, const std::string& walls, double scale = 0.03) {
    sph::Scene scene = scene_file("hydrostatic_tank.json", {"sph.walls=" + walls});
    sph::MeshSpec m;
    m.file = std::string(SPH_SOURCE_DIR) + "/tests/data/" + file;
    m.scale = {scale, scale, scale};
    m.translate = {0.01, 0.02, 0.01};
    scene.meshes.push_back(m);
    try {
      (void)sph::create_setup(scene, 1.0);
    } catch (const sph::SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string missing = refusal("no_such_mesh.obj", "particles");
  CHECK(missing.find("meshes.0") != std::string::npos);
  CHECK(missing.find("no_such_mesh.obj") != std::string::npos);
  const std::string open = refusal("open_box.obj", "particles");
  CHECK(open.find("meshes.0") != std::string::npos);
  CHECK(open.find("open") != std::string::npos);
  const std::string empty = refusal("no_faces.obj", "particles");
  CHECK(empty.find("no triangle") != std::string::npos);
  const std::string inverted = refusal("inverted_box.obj", "particles");
  CHECK(inverted.find("clockwise") != std::string::npos);
  const std::string tiny = refusal("box_12.obj", "particles", 0.001);  // a millimetre: no lattice point inside
  CHECK(tiny.find("meshes.0") != std::string::npos);
  CHECK(tiny.find("no boundary particle") != std::string::npos);
  CHECK(refusal("box_12.obj", "particles").empty());
}
