#include "mesh_renderer.h"

#include <vector>

namespace sph::render {

MeshRenderer::MeshRenderer() : program_("mesh.vert", "mesh.frag") {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glGenBuffers(1, &ebo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  glBindVertexArray(0);
}

MeshRenderer::~MeshRenderer() {
  glDeleteBuffers(1, &ebo_);
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void MeshRenderer::upload(const TriangleMesh& mesh) {
  std::vector<float> xyz;
  xyz.reserve(3 * mesh.vertices.size());
  for (const MeshPoint& v : mesh.vertices) xyz.insert(xyz.end(), {float(v[0]), float(v[1]), float(v[2])});
  std::vector<GLuint> indices;
  indices.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) indices.insert(indices.end(), {GLuint(t[0]), GLuint(t[1]), GLuint(t[2])});
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(xyz.size() * sizeof(float)), xyz.data(), GL_STATIC_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(GLuint)), indices.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  count_ = GLsizei(indices.size());
}

void MeshRenderer::draw(const Mat4& view, const Mat4& projection, Vec3 colour) const {
  if (count_ == 0) return;
  program_.use();
  glUniformMatrix4fv(program_.uniform("u_view"), 1, GL_FALSE, view.data());
  glUniformMatrix4fv(program_.uniform("u_projection"), 1, GL_FALSE, projection.data());
  glUniform3f(program_.uniform("u_colour"), colour.x, colour.y, colour.z);
  const Vec3 light = normalise(transform_direction(view, Vec3{0.4f, 1.0f, 0.6f}));
  glUniform3f(program_.uniform("u_light"), light.x, light.y, light.z);
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

}  // namespace sph::render
