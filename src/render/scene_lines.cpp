#include "scene_lines.h"

#include <cmath>

namespace sph::render {

namespace {

// Centre of a quadric (where grad f = 0: Q_sub [x; 1] = 0), by Cramer's rule; false when singular.
bool quadric_centre(const float* q, Vec3& centre) {
  const double a[3][3] = {{q[0], q[1], q[2]}, {q[4], q[5], q[6]}, {q[8], q[9], q[10]}};
  const double b[3] = {-q[3], -q[7], -q[11]};
  auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det3(a);
  if (std::fabs(d) < 1e-12) return false;
  double x[3];
  for (int k = 0; k < 3; ++k) {
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = j == k ? b[i] : a[i][j];
    x[k] = det3(m) / d;
  }
  centre = Vec3{float(x[0]), float(x[1]), float(x[2])};
  return true;
}

// Smallest t > 0 with f(c + t d) = 0, f being the quadric p^T Q p.
bool quadric_hit(const float* q, Vec3 c, Vec3 d, float& t) {
  auto f = [&](Vec3 p) {
    const float h[4] = {p.x, p.y, p.z, 1.0f};
    float s = 0.0f;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) s += h[i] * q[4 * i + j] * h[j];
    return s;
  };
  // f(c + t d) = A t^2 + B t + C, from three samples.
  const float f0 = f(c), f1 = f(c + d), fm = f(c - d);
  const float A = 0.5f * (f1 + fm) - f0, B = 0.5f * (f1 - fm), C = f0;
  if (std::fabs(A) < 1e-12f) return false;
  const float disc = B * B - 4.0f * A * C;
  if (disc < 0.0f) return false;
  const float s = std::sqrt(disc);
  const float t1 = (-B - s) / (2.0f * A), t2 = (-B + s) / (2.0f * A);
  t = t1 > 0.0f ? t1 : t2;
  return t > 0.0f;
}

}  // namespace

SceneLines::SceneLines() : program_("lines.vert", "lines.frag") {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), nullptr);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(sizeof(Vec3)));
  glEnableVertexAttribArray(1);
  glBindVertexArray(0);
}

SceneLines::~SceneLines() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void SceneLines::line(Vec3 a, Vec3 b, const float* rgba) {
  Vertex va{a, {rgba[0], rgba[1], rgba[2], rgba[3]}}, vb{b, {rgba[0], rgba[1], rgba[2], rgba[3]}};
  vertices_.push_back(va);
  vertices_.push_back(vb);
}

void SceneLines::build(const SimConstants& c, const std::vector<MeshSolid>& meshes, Vec3 lo, Vec3 hi) {
  vertices_.clear();
  const float wall[4] = {0.85f, 0.85f, 0.9f, 1.0f};
  const float obstacle[4] = {0.95f, 0.55f, 0.25f, 1.0f};
  const float grid[4] = {0.35f, 0.37f, 0.4f, 1.0f};
  float floor_y = lo.y;
  for (int32_t s = 0; s < c.num_shapes; ++s) {
    const Shape& sh = c.shapes[s];
    const float* col = sh.keep_inside ? wall : obstacle;
    if (sh.type == ShapeType::Box) {
      const Vec3 a = sh.a, b = sh.b;
      const Vec3 v[8] = {{a.x, a.y, a.z}, {b.x, a.y, a.z}, {b.x, b.y, a.z}, {a.x, b.y, a.z},
                         {a.x, a.y, b.z}, {b.x, a.y, b.z}, {b.x, b.y, b.z}, {a.x, b.y, b.z}};
      const int e[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
      for (const auto& edge : e) line(v[edge[0]], v[edge[1]], col);
      if (sh.keep_inside) floor_y = a.y;
    } else if (sh.type == ShapeType::Sphere) {
      const int n = 48;
      for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i < n; ++i) {
          const float t0 = 2.0f * kPi * float(i) / n, t1 = 2.0f * kPi * float(i + 1) / n;
          auto pt = [&](float t) {
            const float u = sh.radius * std::cos(t), w = sh.radius * std::sin(t);
            return sh.a + (axis == 0 ? Vec3{0, u, w} : axis == 1 ? Vec3{u, 0, w} : Vec3{u, w, 0});
          };
          line(pt(t0), pt(t1), col);
        }
    } else if (sh.type == ShapeType::Quadric) {
      // Closed quadrics (ellipsoids): latitude and longitude lines found along rays from the centre.
      Vec3 centre;
      if (!quadric_centre(sh.q, centre)) continue;
      const int nu = 12, nv = 24;
      auto surface = [&](int i, int j, Vec3& out) {
        const float th = kPi * float(i) / nu, ph = 2.0f * kPi * float(j) / nv;
        const Vec3 d{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)};
        float t = 0.0f;
        if (!quadric_hit(sh.q, centre, d, t)) return false;
        out = centre + t * d;
        return true;
      };
      for (int i = 0; i <= nu; ++i)
        for (int j = 0; j < nv; ++j) {
          Vec3 a, b, c2;
          if (!surface(i, j, a)) continue;
          if (i > 0 && i < nu && surface(i, j + 1, b)) line(a, b, obstacle);
          if (i < nu && surface(i + 1, j, c2)) line(a, c2, obstacle);
        }
    } else if (sh.type == ShapeType::Plane && std::fabs(sh.b.y) > 0.9f) {
      floor_y = sh.a.y;
    }
  }
  for (const MeshSolid& m : meshes) {
    const auto at = [&](int v) {
      const MeshPoint& p = m.mesh.vertices[std::size_t(v)];
      return Vec3{float(p[0]), float(p[1]), float(p[2])};
    };
    for (const auto& t : m.mesh.triangles)
      for (int k = 0; k < 3; ++k) {
        const int a = t[std::size_t(k)], b = t[std::size_t((k + 1) % 3)];
        if (a < b) line(at(a), at(b), m.inside ? wall : obstacle);  // a closed mesh has each edge both ways
      }
  }
  // Floor grid: 20 x 20 lines over the extent.
  const int n = 20;
  for (int i = 0; i <= n; ++i) {
    const float fx = lo.x + (hi.x - lo.x) * float(i) / n, fz = lo.z + (hi.z - lo.z) * float(i) / n;
    line(Vec3{fx, floor_y, lo.z}, Vec3{fx, floor_y, hi.z}, grid);
    line(Vec3{lo.x, floor_y, fz}, Vec3{hi.x, floor_y, fz}, grid);
  }
  static_count_ = vertices_.size();
  upload();
}

void SceneLines::set_bodies(const std::vector<RigidBody>& bodies) {
  const float colour[4] = {0.95f, 0.8f, 0.2f, 1.0f};
  vertices_.resize(static_count_);
  for (const RigidBody& b : bodies) {
    const BodyView v = b.view(BoundaryView{}, 0.0f);
    const auto world = [&](Vec3 local) { return v.centre + body_to_world(v, local); };
    if (b.sphere) {
      const float r = float(b.half_extent[0]);
      const int n = 32;
      for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i < n; ++i) {
          const auto pt = [&](int j) {
            const float t = 2.0f * kPi * float(j) / n, u = r * std::cos(t), w = r * std::sin(t);
            return world(axis == 0 ? Vec3{0, u, w} : axis == 1 ? Vec3{u, 0, w} : Vec3{u, w, 0});
          };
          line(pt(i), pt(i + 1), colour);
        }
      continue;
    }
    if (b.mesh) {  // its triangles' edges
      const auto vertex = [&](int k) {
        const MeshPoint& p = b.surface.vertices[std::size_t(k)];
        return world(Vec3{float(p[0]), float(p[1]), float(p[2])});
      };
      for (const auto& t : b.surface.triangles)
        for (int e = 0; e < 3; ++e)
          if (t[std::size_t(e)] < t[std::size_t((e + 1) % 3)]) line(vertex(t[std::size_t(e)]), vertex(t[std::size_t((e + 1) % 3)]), colour);
      continue;
    }
    const float hx = float(b.half_extent[0]), hy = float(b.half_extent[1]), hz = float(b.half_extent[2]);
    Vec3 corner[8];
    for (int k = 0; k < 8; ++k) corner[k] = world(Vec3{k & 1 ? hx : -hx, k & 2 ? hy : -hy, k & 4 ? hz : -hz});
    for (int k = 0; k < 8; ++k)
      for (const int bit : {1, 2, 4})
        if (!(k & bit)) line(corner[k], corner[k | bit], colour);
  }
  upload();
}

void SceneLines::upload() {
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices_.size() * sizeof(Vertex)), vertices_.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void SceneLines::draw(const Mat4& view, const Mat4& projection) const {
  program_.use();
  glUniformMatrix4fv(program_.uniform("u_view"), 1, GL_FALSE, view.data());
  glUniformMatrix4fv(program_.uniform("u_projection"), 1, GL_FALSE, projection.data());
  glBindVertexArray(vao_);
  glDrawArrays(GL_LINES, 0, GLsizei(vertices_.size()));
  glBindVertexArray(0);
}

}  // namespace sph::render
