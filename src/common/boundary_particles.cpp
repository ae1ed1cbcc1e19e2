#include "boundary_particles.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <sstream>
#include <stdexcept>

#include "kernels.h"
#include "mesh.h"
#include "setup_checks.h"

namespace sph {
namespace {

// At most this many cells in the boundary grid: a wider box gets wider cells (a search stays 3 x 3 x 3 cells).
constexpr double kMaxBoundaryCells = 8.0e6;

struct Sample {
  Vec3 x;
  float friction;
  bool keep;  // a boundary particle, in the solid within h of its surface; else a point that only completes
             // the volumes' sums (deeper in the solid, or a virtual point on the fluid's side)
  int32_t solid_index;  // the shape (0 .. num_shapes - 1) or mesh (num_shapes + m) sampled
};

// Coordinates of one axis of a box [lo, hi]: inside, the lattice stretched to fit (n = round(L / d) points);
// outside (containers), `layers` points at spacing d below lo and above hi (not above when open).
std::vector<double> axis_points(double lo, double hi, double d, int layers, bool below, bool above) {
  std::vector<double> v;
  for (int k = layers - 1; below && k >= 0; --k) v.push_back(lo - (k + 0.5) * d);
  const long n = std::max(1L, std::lround((hi - lo) / d));
  const double s = (hi - lo) / double(n);
  for (long k = 0; k < n; ++k) v.push_back(lo + (double(k) + 0.5) * s);
  for (int k = 0; above && k < layers; ++k) v.push_back(hi + (k + 0.5) * d);
  return v;
}

double outside_distance(const Shape& s, double x, double y, double z) {
  const double p[3] = {x, y, z}, lo[3] = {s.a.x, s.a.y, s.a.z}, hi[3] = {s.b.x, s.b.y, s.b.z};
  double d2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double e = std::max({lo[i] - p[i], 0.0, p[i] - hi[i]});
    d2 += e * e;
  }
  return std::sqrt(d2);
}

double inside_depth(const Shape& s, double x, double y, double z) {
  return std::min({x - s.a.x, s.b.x - x, y - s.a.y, s.b.y - y, z - s.a.z, s.b.z - z});
}

// Whether x lies in the solid of box shape s: outside a container (below its open top), inside an obstacle.
bool in_solid(const Shape& s, double x, double y, double z) {
  const bool inside = x > s.a.x && x < s.b.x && y > s.a.y && y < s.b.y && z > s.a.z && z < s.b.z;
  if (!s.keep_inside) return inside;
  return !inside && !(s.open_top && y >= s.b.y);
}

// The walls: the scene's shapes (solid index 0 .. num_shapes - 1) and its meshes (num_shapes + m).
struct Solids {
  const SimConstants& c;
  const std::vector<MeshSolid>& meshes;
};

// A mesh's clearance: positive on the fluid's side (outside an obstacle, inside a container).
double mesh_clearance(const MeshSolid& m, const Vec3d& p) {
  const double sd = mesh_signed_distance(m.mesh, MeshPoint{p[0], p[1], p[2]});
  return m.inside ? -sd : sd;
}

// Clearance of solid `index` (shape or mesh) at p: positive on the fluid's side.
double solid_clearance(const Solids& w, int32_t index, const Vec3d& p) {
  return index < w.c.num_shapes ? boundary_clearance(w.c.shapes[index], p)
                                : mesh_clearance(w.meshes[std::size_t(index - w.c.num_shapes)], p);
}

// The surface near a boundary particle at x of solid `index`: the clearance's gradient (central differences
// of a hundredth of a millimetre) as the normal towards the fluid, and the depth -clearance (boundary_view.h,
// collide_boundary_particles).
Vec4 surface_of(const Solids& w, int32_t index, Vec3 x) {
  const Vec3d p{x.x, x.y, x.z};
  const double e = 1e-5;
  double g[3];
  for (int a = 0; a < 3; ++a) {
    Vec3d hi = p, lo = p;
    hi[std::size_t(a)] += e;
    lo[std::size_t(a)] -= e;
    g[a] = (solid_clearance(w, index, hi) - solid_clearance(w, index, lo)) / (2.0 * e);
  }
  const double len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  const double depth = std::max(0.0, -solid_clearance(w, index, p));
  if (!(len > 0.0)) return Vec4{0.0f, 0.0f, 0.0f, 0.0f};  // no direction: never pushes (n = 0)
  return Vec4{float(g[0] / len), float(g[1] / len), float(g[2] / len), float(depth)};
}

// Whether (x, y, z) lies in the solid of a shape other than shape `index` (absorbing planes have none).
bool in_other_solid(const Solids& w, int32_t index, double x, double y, double z) {
  const SimConstants& c = w.c;
  for (int32_t o = 0; o < c.num_shapes; ++o) {
    const Shape& s = c.shapes[o];
    if (o == index || s.absorb) continue;
    if (s.type == ShapeType::Box ? in_solid(s, x, y, z) : boundary_clearance(s, Vec3d{x, y, z}) < 0.0) return true;
  }
  for (std::size_t m = 0; m < w.meshes.size(); ++m)
    if (c.num_shapes + int32_t(m) != index && mesh_clearance(w.meshes[m], Vec3d{x, y, z}) < 0.0) return true;
  return false;
}

void refuse_budget(const Solids& w, int32_t index, double d, double count, double max_particles) {
  std::ostringstream os;
  os << (index < w.c.num_shapes ? "boundaries." + std::to_string(index) : "meshes." + std::to_string(index - w.c.num_shapes))
     << ": sampling its walls with boundary particles at spacing " << d << " m needs about "
     << count << " points, above the budget of " << max_particles
     << " (limits.max_particles); use a coarser resolution or sph.walls = \"mirror\"";
  throw std::invalid_argument(os.str());
}

// Adds the sample at p of shape `index` whose signed clearance (setup_checks.h: positive on the fluid's
// side) is cl, when within reach (2 h) of the surface.
void add_sample(const Solids& w, int32_t index, float friction, double h, Vec3d p, double cl, std::vector<Sample>& out) {
  if (!(std::fabs(cl) < 2.0 * h)) return;
  const Vec3 x{float(p[0]), float(p[1]), float(p[2])};
  if (cl < 0.0) out.push_back(Sample{x, friction, -cl < h, index});
  else if (!in_other_solid(w, index, p[0], p[1], p[2])) out.push_back(Sample{x, friction, false, index});
}

// A plane: layers parallel to it at (j + 1/2) d on both sides, each a square lattice of spacing d in the
// plane over the domain (grown by 2 h), from the plane's point a.
void sample_plane(const Solids& w, int32_t index, double d, double h, double max_particles, std::vector<Sample>& out) {
  const SimConstants& c = w.c;
  const Shape& s = c.shapes[index];
  const Vec3d n{s.b.x, s.b.y, s.b.z}, a{s.a.x, s.a.y, s.a.z};
  // t1: n x the axis least along n; t2 = n x t1.
  const int least = std::fabs(n[0]) <= std::fabs(n[1]) && std::fabs(n[0]) <= std::fabs(n[2]) ? 0 : std::fabs(n[1]) <= std::fabs(n[2]) ? 1 : 2;
  const Vec3d e{least == 0 ? 1.0 : 0.0, least == 1 ? 1.0 : 0.0, least == 2 ? 1.0 : 0.0};
  const auto cross3 = [](const Vec3d& u, const Vec3d& v) {
    return Vec3d{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  };
  Vec3d t1 = cross3(n, e);
  const double l1 = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (double& v : t1) v /= l1;
  const Vec3d t2 = cross3(n, t1);
  const GridGeometry& g = c.grid;
  const double lo[3] = {g.origin.x - 2.0 * h, g.origin.y - 2.0 * h, g.origin.z - 2.0 * h};
  const double hi[3] = {g.origin.x + double(g.cell_size) * g.nx + 2.0 * h, g.origin.y + double(g.cell_size) * g.ny + 2.0 * h,
                        g.origin.z + double(g.cell_size) * g.nz + 2.0 * h};
  double u0 = HUGE_VAL, u1 = -HUGE_VAL, v0 = HUGE_VAL, v1 = -HUGE_VAL;
  for (int k = 0; k < 8; ++k) {
    const Vec3d q{k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]};
    const double u = (q[0] - a[0]) * t1[0] + (q[1] - a[1]) * t1[1] + (q[2] - a[2]) * t1[2];
    const double v = (q[0] - a[0]) * t2[0] + (q[1] - a[1]) * t2[1] + (q[2] - a[2]) * t2[2];
    u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
  }
  const long ku0 = long(std::floor(u0 / d)), ku1 = long(std::ceil(u1 / d)), kv0 = long(std::floor(v0 / d)), kv1 = long(std::ceil(v1 / d));
  const int layers = int(std::ceil(2.0 * h / d));
  const double count = double(ku1 - ku0 + 1) * double(kv1 - kv0 + 1) * 2.0 * layers;
  if (double(out.size()) + count > max_particles) refuse_budget(w, index, d, count, max_particles);
  for (int j = -layers; j < layers; ++j)
    for (long kv = kv0; kv <= kv1; ++kv)
      for (long ku = ku0; ku <= ku1; ++ku) {
        const double depth = (j + 0.5) * d, u = (double(ku) + 0.5) * d, v = (double(kv) + 0.5) * d;
        const Vec3d p{a[0] + depth * n[0] + u * t1[0] + v * t2[0], a[1] + depth * n[1] + u * t1[1] + v * t2[1],
                      a[2] + depth * n[2] + u * t1[2] + v * t2[2]};
        if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2]) continue;
        add_sample(w, index, 1.0f - s.slip, h, p, depth, out);
      }
}

// A sphere or a quadric: the lattice of spacing d over the shape's reach (a sphere's box grown by 2 h, a
// quadric's the domain's grown by 2 h), anchored at the domain's origin; the clearance of setup_checks.h
// sorts each point.
void sample_curved(const Solids& w, int32_t index, double d, double h, double max_particles, std::vector<Sample>& out) {
  const SimConstants& c = w.c;
  const Shape& s = c.shapes[index];
  const GridGeometry& g = c.grid;
  const double o[3] = {g.origin.x, g.origin.y, g.origin.z};
  double lo[3] = {o[0] - 2.0 * h, o[1] - 2.0 * h, o[2] - 2.0 * h};
  double hi[3] = {o[0] + double(g.cell_size) * g.nx + 2.0 * h, o[1] + double(g.cell_size) * g.ny + 2.0 * h,
                  o[2] + double(g.cell_size) * g.nz + 2.0 * h};
  if (s.type == ShapeType::Sphere) {
    const double centre[3] = {s.a.x, s.a.y, s.a.z}, r = double(s.radius) + 2.0 * h;
    for (int i = 0; i < 3; ++i) lo[i] = std::max(lo[i], centre[i] - r), hi[i] = std::min(hi[i], centre[i] + r);
  }
  long k0[3], k1[3];
  double candidates = 1.0;
  for (int i = 0; i < 3; ++i) {
    k0[i] = long(std::floor((lo[i] - o[i]) / d));
    k1[i] = long(std::ceil((hi[i] - o[i]) / d));
    candidates *= double(std::max(0L, k1[i] - k0[i] + 1));
  }
  // Every candidate is tested, most are far from the surface: a generous bound on the work.
  if (candidates > 50.0 * max_particles) refuse_budget(w, index, d, candidates, 50.0 * max_particles);
  const std::size_t before = out.size();
  for (long kz = k0[2]; kz <= k1[2]; ++kz)
    for (long ky = k0[1]; ky <= k1[1]; ++ky)
      for (long kx = k0[0]; kx <= k1[0]; ++kx) {
        const Vec3d p{o[0] + (double(kx) + 0.5) * d, o[1] + (double(ky) + 0.5) * d, o[2] + (double(kz) + 0.5) * d};
        add_sample(w, index, 1.0f - s.slip, h, p, boundary_clearance(s, p), out);
        if (double(out.size() - before) > max_particles) refuse_budget(w, index, d, double(out.size() - before), max_particles);
      }
}

// A mesh: the lattice of spacing d anchored half a spacing inside its bounding box's low corner (a box mesh
// whose sides are whole multiples of d is then sampled exactly as the box shape), over the box grown by 2 h;
// the signed distance sorts each point.
void sample_mesh(const Solids& w, std::size_t m, double d, double h, double max_particles, std::vector<Sample>& out) {
  const MeshSolid& ms = w.meshes[m];
  const int32_t index = w.c.num_shapes + int32_t(m);
  long k0[3], k1[3];
  double candidates = 1.0;
  for (int i = 0; i < 3; ++i) {
    k0[i] = -long(std::ceil(2.0 * h / d)) - 1;
    k1[i] = long(std::ceil((ms.mesh.hi[std::size_t(i)] - ms.mesh.lo[std::size_t(i)] + 2.0 * h) / d)) + 1;
    candidates *= double(k1[i] - k0[i] + 1);
  }
  if (candidates > 50.0 * max_particles) refuse_budget(w, index, d, candidates, 50.0 * max_particles);
  const float friction = 1.0f - ms.slip;
  const std::size_t before = out.size();
  for (long kz = k0[2]; kz <= k1[2]; ++kz)
    for (long ky = k0[1]; ky <= k1[1]; ++ky)
      for (long kx = k0[0]; kx <= k1[0]; ++kx) {
        const Vec3d p{ms.mesh.lo[0] + (double(kx) + 0.5) * d, ms.mesh.lo[1] + (double(ky) + 0.5) * d,
                      ms.mesh.lo[2] + (double(kz) + 0.5) * d};
        add_sample(w, index, friction, h, p, mesh_clearance(ms, p), out);
        if (double(out.size() - before) > max_particles) refuse_budget(w, index, d, double(out.size() - before), max_particles);
      }
}

// The samples of box shape s within `layers` spacings of its walls, on both sides: on the solid's side
// (outside a container, inside an obstacle) the boundary particles, kept within h; on the fluid's side
// virtual points, which only complete the volumes' sums (and are dropped where another shape's solid is).
void sample_box(const Solids& w, int32_t index, double d, double h, int layers, double max_particles,
                std::vector<Sample>& out) {
  const SimConstants& c = w.c;
  const Shape& s = c.shapes[index];
  const std::vector<double> xs = axis_points(s.a.x, s.b.x, d, layers, true, true);
  const std::vector<double> ys = axis_points(s.a.y, s.b.y, d, layers, true, !(s.keep_inside && s.open_top));
  const std::vector<double> zs = axis_points(s.a.z, s.b.z, d, layers, true, true);
  const double reach = 2.0 * h;
  // The shell of points within reach of the walls, on both sides: at most the candidates less the inner core.
  const auto core = [&](double lo, double hi) { return std::max(0.0, double(std::lround((hi - lo) / d)) - 2.0 * layers); };
  const double shell = double(xs.size()) * double(ys.size()) * double(zs.size()) -
                       core(s.a.x, s.b.x) * core(s.a.y, s.b.y) * core(s.a.z, s.b.z);
  if (double(out.size()) + shell > max_particles) refuse_budget(w, index, d, shell, max_particles);
  const float friction = 1.0f - s.slip;
  for (const double z : zs)
    for (const double y : ys)
      for (const double x : xs) {
        const bool solid = in_solid(s, x, y, z);
        const bool outside = !(x > s.a.x && x < s.b.x && y > s.a.y && y < s.b.y && z > s.a.z && z < s.b.z);
        const double dist = outside ? outside_distance(s, x, y, z) : inside_depth(s, x, y, z);
        if (dist >= reach) continue;
        if (!solid) {
          // Fluid side: a virtual point, unless it lies in another shape's solid (a wall an obstacle stands on).
          if (!in_other_solid(w, index, x, y, z)) out.push_back(Sample{Vec3{float(x), float(y), float(z)}, friction, false, index});
          continue;
        }
        out.push_back(Sample{Vec3{float(x), float(y), float(z)}, friction, dist < h, index});
      }
}

// Sorts the points by cell of a grid over their bounding box (cells of at least h) and fills the table.
void build_cells(BoundaryParticles& b, double h) {
  const std::size_t n = b.pos_volume.size();
  if (n == 0) return;
  Vec3 lo = xyz(b.pos_volume[0]), hi = lo;
  for (const Vec4& p : b.pos_volume) {
    lo = Vec3{std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = Vec3{std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double ex = double(hi.x - lo.x), ey = double(hi.y - lo.y), ez = double(hi.z - lo.z);
  double cell = h;
  while ((std::floor(ex / cell) + 1.0) * (std::floor(ey / cell) + 1.0) * (std::floor(ez / cell) + 1.0) > kMaxBoundaryCells)
    cell *= 1.25;
  b.cell = float(cell);
  b.origin = lo;
  const float inv = 1.0f / b.cell;
  b.nx = int32_t(std::floor(ex * inv)) + 1;
  b.ny = int32_t(std::floor(ey * inv)) + 1;
  b.nz = int32_t(std::floor(ez * inv)) + 1;
  const auto cell_of = [&](const Vec4& p) {
    // The same float arithmetic as for_each_boundary, clamped into the grid.
    const int32_t x = std::min(b.nx - 1, std::max(0, int32_t(std::floor((p.x - b.origin.x) * inv))));
    const int32_t y = std::min(b.ny - 1, std::max(0, int32_t(std::floor((p.y - b.origin.y) * inv))));
    const int32_t z = std::min(b.nz - 1, std::max(0, int32_t(std::floor((p.z - b.origin.z) * inv))));
    return (int64_t(z) * b.ny + y) * b.nx + x;
  };
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::vector<int64_t> key(n);
  for (std::size_t i = 0; i < n; ++i) key[i] = cell_of(b.pos_volume[i]);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return key[i] < key[j]; });
  std::vector<Vec4> pos(n), normal_depth(n);
  std::vector<float> friction(n);
  std::vector<int32_t> solid(n);
  for (std::size_t i = 0; i < n; ++i) {
    pos[i] = b.pos_volume[order[i]];
    friction[i] = b.friction[order[i]];
    normal_depth[i] = b.normal_depth[order[i]];
    solid[i] = b.solid[order[i]];
  }
  b.pos_volume.swap(pos);
  b.friction.swap(friction);
  b.normal_depth.swap(normal_depth);
  b.solid.swap(solid);
  const std::size_t cells = std::size_t(b.nx) * std::size_t(b.ny) * std::size_t(b.nz);
  b.cell_start.assign(cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++b.cell_start[std::size_t(key[order[i]]) + 1];
  for (std::size_t c = 0; c < cells; ++c) b.cell_start[c + 1] += b.cell_start[c];
}

}  // namespace

void regrid_boundary_particles(BoundaryParticles& b, double h) { build_cells(b, h); }

BoundaryView BoundaryParticles::view() const {
  return BoundaryView{int32_t(pos_volume.size()), pos_volume.data(), friction.data(), normal_depth.data(), solid.data(), cell_start.data(),
                      origin, cell > 0.0f ? 1.0f / cell : 0.0f, nx, ny, nz};
}

BoundaryParticles sample_boundary_particles(const SimConstants& c, const std::vector<MeshSolid>& meshes, double spacing,
                                            double max_particles, std::vector<std::string>& notes) {
  const Solids w{c, meshes};
  const double d = spacing, h = c.kernel.h;
  // Points within 2 h of a wall on either side: every point within h of a boundary particle (itself within
  // h of the fluid's side) is in its volume's sum.
  const int layers = int(std::ceil(2.0 * h / d));
  std::vector<Sample> samples;
  for (int32_t i = 0; i < c.num_shapes; ++i) {
    const Shape& s = c.shapes[i];
    if (s.absorb) continue;  // an outflow, not a wall
    const std::size_t before = samples.size();
    if (s.type == ShapeType::Box) sample_box(w, i, d, h, layers, max_particles, samples);
    else if (s.type == ShapeType::Plane) sample_plane(w, i, d, h, max_particles, samples);
    else sample_curved(w, i, d, h, max_particles, samples);
    const long kept = long(std::count_if(samples.begin() + std::ptrdiff_t(before), samples.end(), [](const Sample& x) { return x.keep; }));
    notes.push_back("boundaries." + std::to_string(i) + ": " + std::to_string(kept) + " boundary particles");
    if (kept == 0) notes.back() += " (the shape lies outside the domain: no wall there)";
  }
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const std::size_t before = samples.size();
    sample_mesh(w, m, d, h, max_particles, samples);
    const long kept = long(std::count_if(samples.begin() + std::ptrdiff_t(before), samples.end(), [](const Sample& x) { return x.keep; }));
    if (kept == 0) {
      std::ostringstream os;
      os << "meshes." << m << ": no boundary particle samples it at spacing " << d
         << " m: it is thinner than a spacing or lies outside the domain; scale it up or refine the resolution";
      throw std::invalid_argument(os.str());
    }
    notes.push_back("meshes." + std::to_string(m) + ": " + std::to_string(kept) + " boundary particles (" +
                    std::to_string(meshes[m].mesh.triangles.size()) + " triangles)");
  }
  // Every sample, for the volumes [AIA12] eq. 4.
  BoundaryParticles all;
  all.pos_volume.reserve(samples.size());
  all.friction.reserve(samples.size());
  all.normal_depth.reserve(samples.size());
  for (const Sample& s : samples) {
    all.pos_volume.push_back(with_w(s.x, s.keep ? 1.0f : 0.0f));  // w: keep, for now
    all.friction.push_back(s.friction);
    all.normal_depth.push_back(s.keep ? surface_of(w, s.solid_index, s.x) : Vec4{0.0f, 0.0f, 0.0f, 0.0f});
    all.solid.push_back(s.solid_index);
  }
  build_cells(all, h);
  const BoundaryView view = all.view();
  BoundaryParticles kept;
  for (int32_t i = 0; i < view.n; ++i) {
    if (all.pos_volume[std::size_t(i)].w == 0.0f) continue;
    double sum = 0.0;
    for_each_boundary(view, xyz(all.pos_volume[std::size_t(i)]), c.kernel.h2,
                      [&](int32_t, Vec3, float r2, float) { sum += double(density_kernel(c.kernel, density_cubic_spline(c), r2)); });
    kept.pos_volume.push_back(with_w(xyz(all.pos_volume[std::size_t(i)]), float(1.0 / sum)));
    kept.friction.push_back(all.friction[std::size_t(i)]);
    kept.normal_depth.push_back(all.normal_depth[std::size_t(i)]);
    kept.solid.push_back(all.solid[std::size_t(i)]);
  }
  build_cells(kept, h);
  return kept;
}

}  // namespace sph
