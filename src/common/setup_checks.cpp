#include "setup_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "boundaries.h"
#include "pbf_coarse.h"
#include "setup_budget.h"

namespace sph {

namespace {

Vec3d d3(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

double length(const Vec3d& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

Vec3d minus(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

double box_clearance(const Shape& s, const Vec3d& p) {
  const Vec3d lo = d3(s.a), hi = d3(s.b);
  if (s.keep_inside) {  // container: nearest wall, negative past any of them
    double c = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      c = std::min(c, p[a] - lo[a]);
      if (!(a == 1 && s.open_top)) c = std::min(c, hi[a] - p[a]);
    }
    return c;
  }
  // Obstacle: Euclidean distance outside, minus the distance to the nearest face inside.
  double out2 = 0.0, in = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double below = lo[a] - p[a], above = p[a] - hi[a];
    const double gap = std::max({below, above, 0.0});
    out2 += gap * gap;
    in = std::min(in, std::min(p[a] - lo[a], hi[a] - p[a]));
  }
  return out2 > 0.0 ? std::sqrt(out2) : -in;
}

// Obstacles keep the fluid outside them; containers, planes (on their normal side) keep it inside.
bool outside_is_allowed(const Shape& s) {
  return (s.type == ShapeType::Box || s.type == ShapeType::Sphere) ? !s.keep_inside : s.type == ShapeType::Quadric;
}

}  // namespace

double boundary_clearance(const Shape& s, const Vec3d& p) {
  switch (s.type) {
    case ShapeType::Box:
      return box_clearance(s, p);
    case ShapeType::Plane: {
      const Vec3d r = minus(p, d3(s.a)), n = d3(s.b);
      return r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
    }
    case ShapeType::Sphere: {
      const double dist = length(minus(p, d3(s.a)));
      return s.keep_inside ? double(s.radius) - dist : dist - double(s.radius);
    }
    case ShapeType::Quadric: {  // first-order distance f / |grad f|, in double (boundaries.h)
      const double f = quadric_form(s.q, p[0], p[1], p[2]);
      double g[3];
      quadric_form_gradient(s.q, p[0], p[1], p[2], g);
      const double gl = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      if (gl > 0.0) return f / gl;
      return f >= 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    }
  }
  return std::numeric_limits<double>::infinity();
}

std::string emitter_label(const std::vector<EmitterSpec>& emitters, std::size_t index) {
  const EmitterType t = emitters[index].type;
  return "emitters." + std::to_string(index) +
         (t == EmitterType::Box ? " (box)" : t == EmitterType::Sphere ? " (sphere)" : " (jet)");
}

std::string boundary_label(const std::vector<BoundarySpec>& boundaries, std::size_t index) {
  const Shape& s = boundaries[index].shape;
  std::string kind;
  switch (s.type) {
    case ShapeType::Box: kind = s.keep_inside ? "box container" : "box obstacle"; break;
    case ShapeType::Plane: kind = s.absorb ? "absorbing plane" : "plane"; break;
    case ShapeType::Sphere: kind = s.keep_inside ? "sphere container" : "sphere obstacle"; break;
    case ShapeType::Quadric: kind = "quadric obstacle"; break;
  }
  return "boundaries." + std::to_string(index) + " (" + kind + ")";
}

void remove_blocked_points(const Scene& scene, double spacing, const std::vector<EmitterFill>& stats,
                           std::vector<FilledPoint>& points, std::vector<std::string>& report) {
  const double min_clearance = kMinWallClearance * spacing;
  std::map<std::pair<int, int>, std::size_t> removed;  // (emitter, boundary) -> points removed
  std::size_t kept = 0;
  for (const FilledPoint& p : points) {
    int blocked_by = -1;
    for (std::size_t b = 0; b < scene.boundaries.size() && blocked_by < 0; ++b)
      if (boundary_clearance(scene.boundaries[b].shape, p.pos) < min_clearance) blocked_by = int(b);
    if (blocked_by >= 0) ++removed[{p.emitter, blocked_by}];
    else points[kept++] = p;
  }
  points.resize(kept);
  for (const auto& [key, count] : removed) {
    const auto [e, b] = key;
    std::ostringstream os;
    os << emitter_label(scene.emitters, std::size_t(e)) << ": " << count << " of its " << stats[std::size_t(e)].created
       << " particles lie " << (outside_is_allowed(scene.boundaries[std::size_t(b)].shape) ? "inside " : "outside ")
       << boundary_label(scene.boundaries, std::size_t(b)) << " or within " << kMinWallClearance
       << " d = " << min_clearance << " m of its surface";
    if (scene.overlap_error)
      throw SceneError(scene.source + ": " + os.str() +
                       "; move the emitter or the boundary (\"on_overlap\": \"error\"; \"remove\" would remove them)");
    // Not an error: an emitter that reaches a wall, or whose whole layers overshoot it, loses those layers.
    report.push_back(os.str() + "; removed, as where an emitter reaches a wall (\"on_overlap\": \"error\" refuses instead)");
  }
}

void check_jet_inlets(const Scene& scene, const std::vector<JetEmitter>& jets, const std::vector<int>& jet_index) {
  for (std::size_t j = 0; j < jets.size(); ++j) {
    const JetEmitter& jet = jets[j];
    for (long l = 0; l < jet.inlet_layers(); ++l)
      for (std::size_t s = 0; s < jet.section_size(); ++s) {
        const Vec3d p = jet.inlet_point(l, s);
        for (std::size_t b = 0; b < scene.boundaries.size(); ++b) {
          if (boundary_clearance(scene.boundaries[b].shape, p) >= 0.0) continue;
          const std::size_t e = std::size_t(jet_index[j]);
          std::ostringstream os;
          os << scene.source << ": " << emitter_label(scene.emitters, e) << ": its inlet, " << jet.inlet_length()
             << " m behind the outlet, crosses " << boundary_label(scene.boundaries, b) << " (the inlet point ("
             << p[0] << ", " << p[1] << ", " << p[2] << ") lies where the fluid may not be); move emitters." << e
             << ".position at least " << jet.inlet_length() << " m plus the jet's radius away from the boundary, or set a shorter emitters."
             << e << ".inlet_length";
          throw SceneError(os.str());
        }
      }
  }
}

// The dense coarse grid takes 52 bytes a cell (coarse_view_bytes): 2^23 cells, 436 MB.
constexpr int64_t kMaxCoarseCells = int64_t(1) << 23;

void check_coarse_grid(const Scene& scene, const GridGeometry& grid, std::vector<std::string>& report) {
  const CoarseGrid g = coarse_grid_of(grid);
  std::ostringstream os;
  os.precision(4);
  os << g.nx << " x " << g.ny << " x " << g.nz << " cells of " << g.size << " m";
  if (coarse_cell_count(g) > kMaxCoarseCells)
    throw SceneError(scene.source + ": pbf.coarse_grid: the domain takes " + os.str() + ", more than " +
                     count_text(double(kMaxCoarseCells)) +
                     ": fit the domain (\"domain\" or the box container) to the fluid, coarsen the resolution, or set "
                     "pbf.coarse_grid false");
  report.push_back("PBF's coarse grid: " + os.str());
}

}  // namespace sph
