#include "scene_lines.h"

#include <cmath>

namespace sph::render {

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

void SceneLines::build(const SimConstants& c, Vec3 lo, Vec3 hi) {
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
    } else if (sh.type == ShapeType::Plane && std::fabs(sh.b.y) > 0.9f) {
      floor_y = sh.a.y;
    }
  }
  // Floor grid: 20 x 20 lines over the extent.
  const int n = 20;
  for (int i = 0; i <= n; ++i) {
    const float fx = lo.x + (hi.x - lo.x) * float(i) / n, fz = lo.z + (hi.z - lo.z) * float(i) / n;
    line(Vec3{fx, floor_y, lo.z}, Vec3{fx, floor_y, hi.z}, grid);
    line(Vec3{lo.x, floor_y, fz}, Vec3{hi.x, floor_y, fz}, grid);
  }
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
