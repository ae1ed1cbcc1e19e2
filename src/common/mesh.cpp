#include "mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

namespace sph {
namespace {

MeshPoint sub(const MeshPoint& a, const MeshPoint& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const MeshPoint& a, const MeshPoint& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
MeshPoint cross(const MeshPoint& a, const MeshPoint& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const MeshPoint& a) { return std::sqrt(dot(a, a)); }

// Squared distance from p to triangle (a, b, c): the closest point by the triangle's Voronoi regions
// (Ericson, Real-Time Collision Detection, 5.1.5).
double triangle_distance2(const MeshPoint& p, const MeshPoint& a, const MeshPoint& b, const MeshPoint& c) {
  const MeshPoint ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  const auto at = [&](const MeshPoint& q) {
    const MeshPoint e = sub(p, q);
    return dot(e, e);
  };
  if (d1 <= 0.0 && d2 <= 0.0) return at(a);
  const MeshPoint bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return at(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return at({a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]});
  }
  const MeshPoint cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return at(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return at({a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    const MeshPoint bc = sub(c, b);
    return at({b[0] + w * bc[0], b[1] + w * bc[1], b[2] + w * bc[2]});
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return at({a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w});
}

// Solid angle of triangle (a, b, c) seen from p, signed by orientation [Van Oosterom and Strackee 1983].
double solid_angle(const MeshPoint& p, const MeshPoint& a, const MeshPoint& b, const MeshPoint& c) {
  const MeshPoint x = sub(a, p), y = sub(b, p), z = sub(c, p);
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double numerator = dot(x, cross(y, z));
  const double denominator = lx * ly * lz + dot(x, y) * lz + dot(y, z) * lx + dot(z, x) * ly;
  return 2.0 * std::atan2(numerator, denominator);
}

}  // namespace

TriangleMesh load_obj_mesh(const std::string& path, const MeshPoint& scale, const MeshPoint& translate) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";  // materials are not read: a missing .mtl must not fail the geometry
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string why = reader.Error();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    throw std::runtime_error(path + ": cannot read this OBJ mesh" + (why.empty() ? std::string() : ": " + why));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  TriangleMesh m;
  const std::size_t nv = attrib.vertices.size() / 3;
  m.vertices.resize(nv);
  for (std::size_t i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = double(attrib.vertices[3 * i + std::size_t(k)]) * scale[std::size_t(k)] + translate[std::size_t(k)];
      if (!std::isfinite(v)) throw std::runtime_error(path + ": vertex " + std::to_string(i + 1) + " is not finite");
      m.vertices[i][std::size_t(k)] = v;
    }
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::vector<tinyobj::index_t>& idx = shape.mesh.indices;
    std::size_t offset = 0;
    for (const unsigned char count : shape.mesh.num_face_vertices) {
      if (count != 3 || offset + 3 > idx.size()) {
        std::ostringstream os;
        os << path << ": face with " << int(count) << " vertices after triangulation (shape \"" << shape.name << "\")";
        throw std::runtime_error(os.str());
      }
      std::array<int, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const int v = idx[offset + std::size_t(k)].vertex_index;
        if (v < 0 || std::size_t(v) >= nv)
          throw std::runtime_error(path + ": a face refers to vertex " + std::to_string(v + 1) + ", but the file has " +
                                   std::to_string(nv) + " vertices");
        t[std::size_t(k)] = v;
      }
      m.triangles.push_back(t);
      offset += 3;
    }
  }
  if (m.triangles.empty()) throw std::runtime_error(path + ": the mesh has no triangle (no \"f\" lines)");
  update_bounds(m);
  return m;
}

void update_bounds(TriangleMesh& m) {
  if (m.triangles.empty()) return;
  m.lo = m.hi = m.vertices[std::size_t(m.triangles[0][0])];
  for (const auto& t : m.triangles)
    for (const int v : t)
      for (int k = 0; k < 3; ++k) {
        m.lo[std::size_t(k)] = std::min(m.lo[std::size_t(k)], m.vertices[std::size_t(v)][std::size_t(k)]);
        m.hi[std::size_t(k)] = std::max(m.hi[std::size_t(k)], m.vertices[std::size_t(v)][std::size_t(k)]);
      }
}

std::string mesh_closure_problem(const TriangleMesh& mesh) {
  // Each directed edge (a, b) must appear once, and its reverse (b, a) once.
  std::map<std::pair<int, int>, int> directed;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const MeshPoint& a = mesh.vertices[std::size_t(t[0])];
    const MeshPoint n = cross(sub(mesh.vertices[std::size_t(t[1])], a), sub(mesh.vertices[std::size_t(t[2])], a));
    if (!(norm(n) > 0.0)) return "triangle " + std::to_string(i + 1) + " has zero area";
    for (int k = 0; k < 3; ++k) ++directed[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}];
  }
  double volume6 = 0.0;  // six times the signed volume: positive when the faces turn counter-clockwise outside
  for (const auto& t : mesh.triangles)
    volume6 += dot(mesh.vertices[std::size_t(t[0])], cross(mesh.vertices[std::size_t(t[1])], mesh.vertices[std::size_t(t[2])]));
  for (const auto& e : directed) {
    const auto edge = "edge between vertices " + std::to_string(e.first.first + 1) + " and " + std::to_string(e.first.second + 1);
    if (e.second > 1) return edge + " is used " + std::to_string(e.second) + " times in the same direction (not manifold, or faces inconsistently oriented)";
    const auto back = directed.find({e.first.second, e.first.first});
    if (back == directed.end()) return edge + " borders one triangle only (the mesh is open)";
  }
  if (!(volume6 > 0.0))
    return "its faces turn clockwise seen from outside (its signed volume is negative): list each face's vertices "
           "counter-clockwise seen from outside, or reverse them all";
  return "";
}

double mesh_signed_distance(const TriangleMesh& mesh, const MeshPoint& p) {
  double best = std::numeric_limits<double>::infinity(), angle = 0.0;
  for (const auto& t : mesh.triangles) {
    const MeshPoint& a = mesh.vertices[std::size_t(t[0])];
    const MeshPoint& b = mesh.vertices[std::size_t(t[1])];
    const MeshPoint& c = mesh.vertices[std::size_t(t[2])];
    best = std::min(best, triangle_distance2(p, a, b, c));
    angle += solid_angle(p, a, b, c);
  }
  const double winding = angle / (4.0 * 3.14159265358979323846);
  return winding > 0.5 ? -std::sqrt(best) : std::sqrt(best);
}

MeshMassProperties mesh_mass_properties(const TriangleMesh& mesh) {
  MeshMassProperties out;
  double second[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // sum of x_i x_j dV about the origin
  double first[3] = {0, 0, 0};
  for (const auto& t : mesh.triangles) {
    const MeshPoint& a = mesh.vertices[std::size_t(t[0])];
    const MeshPoint& b = mesh.vertices[std::size_t(t[1])];
    const MeshPoint& c = mesh.vertices[std::size_t(t[2])];
    const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    out.volume += det / 6.0;
    for (int i = 0; i < 3; ++i) first[i] += det / 24.0 * (a[i] + b[i] + c[i]);
    // integral over the tetrahedron (0, a, b, c) of x_i x_j = det / 120 (sum_k p_ki p_kj + (sum_k p_ki)(sum_k p_kj))
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double s_i = a[i] + b[i] + c[i], s_j = a[j] + b[j] + c[j];
        second[i][j] += det / 120.0 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s_i * s_j);
      }
  }
  if (!(out.volume > 0.0)) return out;
  for (int i = 0; i < 3; ++i) out.centroid[std::size_t(i)] = first[i] / out.volume;
  double about[3][3];  // second moments about the centroid
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) about[i][j] = second[i][j] - out.volume * out.centroid[std::size_t(i)] * out.centroid[std::size_t(j)];
  const double trace = about[0][0] + about[1][1] + about[2][2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.inertia[std::size_t(i)][std::size_t(j)] = (i == j ? trace : 0.0) - about[i][j];
  return out;
}

}  // namespace sph
