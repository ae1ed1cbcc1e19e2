// Fluid surface meshes from particles (issue 14, src/surface/): closed, the fluid's volume, a sphere's area,
// and the options and sizes that are refused.
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "common/mesh.h"
#include "common/mesh_ply.h"
#include "common/setup_budget.h"
#include "physics_helpers.h"
#include "surface/particle_surface.h"

using namespace sph_test;

namespace {

std::vector<sph::Vec3> positions_of(const sph::ParticleState& ps) {
  std::vector<sph::Vec3> out(ps.pos.begin(), ps.pos.end());
  return out;
}

}  // namespace

TEST_CASE("surface: the hydrostatic tank's block is closed and holds the fluid's volume", "[surface]") {
  // The resting block of scenes/hydrostatic_tank.json as the emitter lays it (10 x 20 x 10 layers), and
  // after 0.3 s of settling on the cpu reference: the mesh is closed, manifold and
  // outward (mesh.h's check for solids) and encloses the fluid's volume, mass / rho0, within 3% (issue 14).
  const sph::Scene scene = scene_file("hydrostatic_tank.json");
  sph::Simulation sim(scene, cpu_factory(), 0.3);
  const double d = sim.setup().spacing;
  double mass = 0.0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) mass += sim.setup().constants.fluids[sim.particles().fluid[i]].mass;
  const double volume = mass / scene.fluids.at(0).rest_density;
  sph::SurfaceOptions o;
  o.spacing = d;
  for (const bool settled : {false, true}) {
    if (settled)
      while (sim.time() < 0.3) sim.advance();
    const sph::TriangleMesh mesh = sph::particle_surface(positions_of(sim.particles()), o);
    const double v = sph::mesh_volume(mesh);
    INFO((settled ? "after 0.3 s" : "as laid") << ": " << mesh.triangles.size() << " triangles, volume " << v
                                             << " m^3 against mass / rho0 " << volume << " (" << (v / volume - 1.0) * 100.0 << "%)");
    CHECK(sph::mesh_closure_problem(mesh).empty());
    CHECK(std::fabs(v / volume - 1.0) <= 0.03);
  }
}

TEST_CASE("surface: a settled drop's mesh has the area of the sphere of its volume", "[surface]") {
  // scenes/drop_zero_g.json (a cube of 12^3 particles without gravity, pulled into a ball by its kept
  // negative pressure) after 1.5 s on the cpu reference. The sphere holding the fluid's volume (mass / rho0)
  // has radius r_v; the mesh's area within 5% of 4 pi r_v^2 (issue 14). A lattice cut to a ball is no test of
  // this: its staircase makes the smoothed surface bulge over the cut (measured +5.7% area). Without
  // smoothing the spheres' bumps add area (checked to be larger).
  const sph::Scene scene = scene_file("drop_zero_g.json");
  sph::Simulation sim(scene, cpu_factory(), 1.5);
  while (sim.time() < 1.5) sim.advance();
  const sph::ParticleState& ps = sim.particles();
  double mass = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) mass += sim.setup().constants.fluids[ps.fluid[i]].mass;
  const double volume = mass / scene.fluids.at(0).rest_density;
  const double r = std::cbrt(3.0 * volume / (4.0 * 3.14159265358979));
  const double sphere_area = 4.0 * 3.14159265358979 * r * r;
  sph::SurfaceOptions o;
  o.spacing = sim.setup().spacing;
  const sph::TriangleMesh mesh = sph::particle_surface(positions_of(ps), o);
  o.smoothing = 0;
  const double area = sph::mesh_area(mesh), rough_area = sph::mesh_area(sph::particle_surface(positions_of(ps), o));
  INFO(ps.size() << " particles, r_v " << r << " m: area " << area << " m^2 (unsmoothed " << rough_area
                 << ") against " << sphere_area << "; volume " << sph::mesh_volume(mesh) << " against " << volume);
  CHECK(sph::mesh_closure_problem(mesh).empty());
  CHECK(std::fabs(area / sphere_area - 1.0) <= 0.05);
  CHECK(rough_area > area);
}

TEST_CASE("surface: options out of range and sizes beyond the machine are refused by name", "[surface]") {
  const std::vector<sph::Vec3> one{{0.0f, 0.0f, 0.0f}};
  sph::SurfaceOptions o;
  o.spacing = 0.01;
  CHECK_NOTHROW(sph::particle_surface(one, o));  // a lone particle: a small closed sphere
  CHECK(sph::mesh_closure_problem(sph::particle_surface(one, o)).empty());
  CHECK(sph::particle_surface({}, o).triangles.empty());
  auto refused = [&](sph::SurfaceOptions bad, const char* word) {
    try {
      sph::particle_surface(one, bad);
    } catch (const std::invalid_argument& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(word) != std::string::npos);
      return;
    }
    FAIL("accepted " << word);
  };
  sph::SurfaceOptions bad = o;
  bad.voxels_per_spacing = 0.5;
  refused(bad, "resolution");
  bad = o;
  bad.radius = 0.5;
  refused(bad, "radius");
  bad = o;
  bad.spacing = std::nan("");
  refused(bad, "spacing");
  bad = o;
  bad.smoothing = -1;
  refused(bad, "smoothing");
  // The estimate grows with the particles and the resolution cubed, and a billion particles at 8 voxels per
  // spacing are beyond any machine this runs on.
  bad = o;
  bad.voxels_per_spacing = 8.0;
  CHECK(sph::surface_memory_estimate(1000000000, bad) > sph::usable_memory_bytes());
  CHECK(sph::surface_memory_estimate(2000, o) * 8.0 < sph::surface_memory_estimate(2000, bad) * 1.01);
}

TEST_CASE("surface: a mesh written as PLY reads back, and a damaged file is refused by name", "[surface]") {
  sph::SurfaceOptions o;
  o.spacing = 0.01;
  const sph::TriangleMesh mesh = sph::particle_surface({{0.0f, 0.0f, 0.0f}, {0.01f, 0.0f, 0.0f}}, o);
  const std::string path = std::string(SPH_BINARY_DIR) + "/surface_roundtrip.ply";
  sph::write_ply_mesh(path, mesh, 0.125);
  double time = 0.0;
  const sph::TriangleMesh back = sph::read_ply_mesh(path, time);
  CHECK(time == 0.125);
  REQUIRE(back.triangles == mesh.triangles);
  REQUIRE(back.vertices.size() == mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) CHECK(back.vertices[i][k] == double(float(mesh.vertices[i][k])));
  // Cut short: the size check names the file.
  {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() - 5);
  }
  try {
    sph::read_ply_mesh(path, time);
    FAIL("a truncated mesh was read");
  } catch (const std::runtime_error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("surface_roundtrip.ply") != std::string::npos);
  }
}

TEST_CASE("surface: the seed's colour field Phi meshes the block and the drop as well", "[surface]") {
  // SurfaceOptions::colour_field: Phi = sum d^3 W(r, 2 d) at 1/2, uncalibrated. The same checks as the
  // spheres' meshes: closed, the hydrostatic tank's block within 3% of mass / rho0 as laid, the settled drop's
  // area within 5% of its sphere's.
  sph::SurfaceOptions o;
  o.colour_field = true;
  {
    const sph::Scene scene = scene_file("hydrostatic_tank.json");
    sph::Simulation sim(scene, cpu_factory(), 0.1);
    o.spacing = sim.setup().spacing;
    double mass = 0.0;
    for (std::size_t i = 0; i < sim.particles().size(); ++i) mass += sim.setup().constants.fluids[sim.particles().fluid[i]].mass;
    const double volume = mass / scene.fluids.at(0).rest_density;
    const sph::TriangleMesh mesh = sph::particle_surface(positions_of(sim.particles()), o);
    INFO("block: volume " << sph::mesh_volume(mesh) << " m^3 against " << volume);
    CHECK(sph::mesh_closure_problem(mesh).empty());
    CHECK(std::fabs(sph::mesh_volume(mesh) / volume - 1.0) <= 0.03);
  }
  const sph::Scene scene = scene_file("drop_zero_g.json");
  sph::Simulation sim(scene, cpu_factory(), 1.5);
  while (sim.time() < 1.5) sim.advance();
  double mass = 0.0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) mass += sim.setup().constants.fluids[sim.particles().fluid[i]].mass;
  const double r = std::cbrt(3.0 * mass / scene.fluids.at(0).rest_density / (4.0 * 3.14159265358979));
  o.spacing = sim.setup().spacing;
  const sph::TriangleMesh mesh = sph::particle_surface(positions_of(sim.particles()), o);
  INFO("drop: area " << sph::mesh_area(mesh) << " m^2 against " << 4.0 * 3.14159265358979 * r * r);
  CHECK(sph::mesh_closure_problem(mesh).empty());
  CHECK(std::fabs(sph::mesh_area(mesh) / (4.0 * 3.14159265358979 * r * r) - 1.0) <= 0.05);
}
