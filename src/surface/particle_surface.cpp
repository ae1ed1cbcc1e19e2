// OpenVDB's particle rasteriser, level-set filter and mesher put together (particle_surface.h says what and why).
#include "particle_surface.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>

#include "../common/kernels.h"
#include "../common/setup_budget.h"

namespace sph {
namespace {

// The narrow band's half width [voxels] on each side of the surface (OpenVDB's default level set).
constexpr double kHalfWidth = 3.0;

// The particle list ParticlesToLevelSet reads (its documented interface: size and getPos).
struct ParticleList {
  using PosType = openvdb::Vec3R;
  const std::vector<Vec3>* positions;
  std::size_t size() const { return positions->size(); }
  void getPos(std::size_t n, openvdb::Vec3R& xyz) const {
    const Vec3& p = (*positions)[n];
    xyz = openvdb::Vec3R(p.x, p.y, p.z);
  }
};

// The level set of the particles' spheres, smoothed (no erosion yet).
openvdb::FloatGrid::Ptr smoothed_spheres(const std::vector<Vec3>& positions, const SurfaceOptions& o) {
  const double d = o.spacing, voxel = d / o.voxels_per_spacing;
  openvdb::FloatGrid::Ptr grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, kHalfWidth);
  openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
  raster.rasterizeSpheres(ParticleList{&positions}, o.radius * d);
  raster.finalize(true);
  openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*grid);
  for (int i = 0; i < o.smoothing; ++i) filter.meanCurvature();
  return grid;
}

// The seed's colour field Phi (SurfaceOptions::colour_field) on voxels of d / voxels_per_spacing: every
// particle adds d^3 W to the voxels within h = 2 d of it (kernels.h's cubic spline).
openvdb::FloatGrid::Ptr colour_field(const std::vector<Vec3>& positions, const SurfaceOptions& o) {
  const double d = o.spacing, voxel = d / o.voxels_per_spacing, h = 2.0 * d;
  const KernelCoeffs k = make_kernel_coeffs(h);
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  auto acc = grid->getAccessor();
  const int reach = int(std::ceil(h / voxel));
  const float volume = float(d * d * d);
  for (const Vec3& p : positions) {
    const openvdb::Coord c = grid->transform().worldToIndexCellCentered(openvdb::Vec3d(p.x, p.y, p.z));
    for (int i = -reach; i <= reach; ++i)
      for (int j = -reach; j <= reach; ++j)
        for (int l = -reach; l <= reach; ++l) {
          const openvdb::Coord v = c.offsetBy(i, j, l);
          const openvdb::Vec3d x = grid->transform().indexToWorld(v);
          const double dx = x.x() - p.x, dy = x.y() - p.y, dz = x.z() - p.z;
          const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
          if (r < h) acc.setValue(v, acc.getValue(v) + volume * cubic_spline(k, float(r)));
        }
  }
  return grid;
}

TriangleMesh mesh_of(const openvdb::FloatGrid& grid, double isovalue = 0.0) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, isovalue, 0.0);
  TriangleMesh mesh;
  mesh.vertices.reserve(points.size());
  for (const openvdb::Vec3s& p : points) mesh.vertices.push_back({double(p.x()), double(p.y()), double(p.z())});
  mesh.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const openvdb::Vec3I& t : triangles) mesh.triangles.push_back({int(t.x()), int(t.y()), int(t.z())});
  for (const openvdb::Vec4I& q : quads) {
    mesh.triangles.push_back({int(q[0]), int(q[1]), int(q[2])});
    mesh.triangles.push_back({int(q[0]), int(q[2]), int(q[3])});
  }
  // volumeToMesh's winding is not documented: make it counter-clockwise seen from outside.
  if (mesh_volume(mesh) < 0.0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

// The erosion [m] that puts a lattice's flat faces half a spacing beyond its outer particles: found on a 16 x
// 16 x 8 lattice slab with the same options, as the offset whose mesh encloses the slab's N d^3 (secant
// iterations from the first guess (V0 - N d^3) / area; eroding also shrinks the rounded edges, so the
// guess alone over-erodes by about 6% of a spacing). The rasterised spheres bulge between their centres and
// smoothing shrinks the bulges and rounds edges, so the erosion is measured rather than derived.
double measured_erosion(const SurfaceOptions& o) {
  const double d = o.spacing;
  const int nx = 16, ny = 16, nz = 8;
  std::vector<Vec3> slab;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) slab.push_back({float((i + 0.5) * d), float((j + 0.5) * d), float((k + 0.5) * d)});
  const double volume = double(slab.size()) * d * d * d;
  const double area = 2.0 * (nx * ny + ny * nz + nz * nx) * d * d;
  const openvdb::FloatGrid::Ptr spheres = smoothed_spheres(slab, o);
  auto excess = [&](double erosion) {  // enclosed volume minus N d^3 after eroding by `erosion`
    openvdb::FloatGrid::Ptr g = spheres->deepCopy();
    openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*g);
    if (erosion != 0.0) filter.offset(float(erosion));
    return mesh_volume(mesh_of(*g)) - volume;
  };
  double x0 = 0.0, f0 = excess(x0);
  double x1 = f0 / area, f1 = excess(x1);
  for (int it = 0; it < 4 && std::fabs(f1) > 1e-4 * volume && f1 != f0; ++it) {
    const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
    x0 = x1, f0 = f1;
    x1 = x2, f1 = excess(x1);
  }
  return x1;
}

// measured_erosion in units of the spacing, measured once per radius, resolution and smoothing (the geometry
// scales with d; it costs about 0.17 s, a tenth of a 100k-particle frame).
double calibrated_erosion(const SurfaceOptions& o) {
  static std::mutex mutex;
  static std::map<std::tuple<double, double, int>, double> per_spacing;
  const auto key = std::make_tuple(o.radius, o.voxels_per_spacing, o.smoothing);
  std::lock_guard<std::mutex> lock(mutex);
  auto it = per_spacing.find(key);
  if (it == per_spacing.end()) {
    SurfaceOptions unit = o;
    unit.spacing = 1.0;
    it = per_spacing.emplace(key, measured_erosion(unit)).first;
  }
  return it->second * o.spacing;
}

}  // namespace

void check_surface_options(const SurfaceOptions& o) {
  auto refuse = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!(o.spacing > 0.0) || !std::isfinite(o.spacing)) refuse("surface: the particle spacing must be a positive number of metres");
  if (!(o.voxels_per_spacing >= 1.0 && o.voxels_per_spacing <= 8.0))
    refuse("surface resolution (voxels per particle spacing) must be between 1 and 8");
  if (!(o.radius >= 0.9 && o.radius <= 3.0))
    refuse("surface particle radius must be between 0.9 and 3 spacings (spheres of a lattice must overlap: > 0.87)");
  if (o.smoothing < 0 || o.smoothing > 20) refuse("surface smoothing must be between 0 and 20 iterations");
  if (o.radius * o.voxels_per_spacing < 1.5)
    refuse("surface particle radius times resolution must be at least 1.5 voxels (OpenVDB ignores smaller spheres)");
}

double surface_memory_estimate(std::size_t particles, const SurfaceOptions& o) {
  // Voxels within the band of one sphere: the shell between radius - w and radius + w voxels, 4 bytes of
  // value and about 4 of topology each; three copies live at once in the filter.
  const double r = o.radius * o.voxels_per_spacing, w = kHalfWidth;
  const double outer = r + w, inner = std::max(0.0, r - w);
  const double shell = 4.0 / 3.0 * 3.14159265358979 * (outer * outer * outer - inner * inner * inner);
  return double(particles) * shell * 8.0 * 3.0;
}

TriangleMesh particle_surface(const std::vector<Vec3>& positions, const SurfaceOptions& o) {
  check_surface_options(o);
  TriangleMesh mesh;
  if (positions.empty()) return mesh;
  const double need = surface_memory_estimate(positions.size(), o), have = usable_memory_bytes();
  if (need > have) {
    std::ostringstream os;
    os << "surface: " << positions.size() << " particles at " << o.voxels_per_spacing
       << " voxels per spacing need up to " << need / 1e9 << " GB (estimate), more than the " << have / 1e9
       << " GB a run may use here (half this machine's memory); lower the resolution";
    throw std::runtime_error(os.str());
  }
  openvdb::initialize();
  if (o.colour_field) {
    mesh = mesh_of(*colour_field(positions, o), 0.5);
    update_bounds(mesh);
    return mesh;
  }
  openvdb::FloatGrid::Ptr grid = smoothed_spheres(positions, o);
  // Erode back to where the particles' volume ends (a positive offset moves the zero crossing inwards).
  openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*grid);
  filter.offset(float(calibrated_erosion(o)));
  mesh = mesh_of(*grid);
  update_bounds(mesh);
  return mesh;
}

double mesh_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const MeshPoint &a = mesh.vertices[std::size_t(t[0])], &b = mesh.vertices[std::size_t(t[1])], &c = mesh.vertices[std::size_t(t[2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return area;
}

double mesh_volume(const TriangleMesh& mesh) {
  double six = 0.0;  // six times the signed volume: the tetrahedra the triangles span with the origin
  for (const auto& t : mesh.triangles) {
    const MeshPoint &a = mesh.vertices[std::size_t(t[0])], &b = mesh.vertices[std::size_t(t[1])], &c = mesh.vertices[std::size_t(t[2])];
    six += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six / 6.0;
}

}  // namespace sph
