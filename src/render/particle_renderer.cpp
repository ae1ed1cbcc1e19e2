#include "particle_renderer.h"

#include <algorithm>

namespace sph::render {

ParticleRenderer::ParticleRenderer() : program_("particles.vert", "particles.frag") {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(2, vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[0]);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[1]);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
  glEnableVertexAttribArray(1);
  glBindVertexArray(0);
}

ParticleRenderer::~ParticleRenderer() {
  glDeleteBuffers(2, vbo_);
  glDeleteVertexArrays(1, &vao_);
}

ColourRange ParticleRenderer::upload(const ParticleState& ps, const SimConstants& c, ColourMode mode,
                                     const std::vector<uint32_t>* subset) {
  const ColourRange range = colour_range(ps, mode);
  const Vec3* positions = ps.pos.data();
  std::size_t n = ps.size();
  if (subset) {
    n = subset->size();
    positions_.resize(n);
    colours_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = (*subset)[k];
      positions_[k] = ps.pos[i];
      colours_[k] = colour_of(ps, c, mode, range, i);
    }
    positions = positions_.data();
  } else {
    colour_particles(ps, c, mode, range, colours_);
  }
  count_ = GLsizei(n);
  reserve(n);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[0]);
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(n * sizeof(Vec3)), positions);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[1]);
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(n * sizeof(Vec3)), colours_.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return range;
}

void ParticleRenderer::upload_points(const std::vector<Vec3>& positions, Vec3 colour) {
  const std::size_t n = positions.size();
  colours_.assign(n, colour);
  count_ = GLsizei(n);
  reserve(n);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[0]);
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(n * sizeof(Vec3)), positions.data());
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[1]);
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(n * sizeof(Vec3)), colours_.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void ParticleRenderer::reserve(std::size_t n) {
  if (fits(n)) return;
  capacity_ = std::max<std::size_t>(std::max<std::size_t>(n, 1024), 2 * capacity_);
  for (GLuint vbo : vbo_) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(capacity_ * sizeof(Vec3)), nullptr, GL_DYNAMIC_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  ++generation_;
}

void ParticleRenderer::draw(const Mat4& view, const Mat4& projection, float radius, int viewport_height, bool flat,
                            float min_size) const {
  if (count_ == 0) return;
  program_.use();
  glUniformMatrix4fv(program_.uniform("u_view"), 1, GL_FALSE, view.data());
  glUniformMatrix4fv(program_.uniform("u_projection"), 1, GL_FALSE, projection.data());
  glUniform1f(program_.uniform("u_radius"), radius);
  glUniform1f(program_.uniform("u_viewport_height"), float(viewport_height));
  glUniform1f(program_.uniform("u_min_size"), min_size);
  const Vec3 light = normalise(transform_direction(view, Vec3{0.4f, 1.0f, 0.6f}));
  glUniform3f(program_.uniform("u_light"), light.x, light.y, light.z);
  glUniform1i(program_.uniform("u_flat"), flat ? 1 : 0);
  draw_points();
}

void ParticleRenderer::draw_points() const {
  glBindVertexArray(vao_);
  glDrawArrays(GL_POINTS, 0, count_);
  glBindVertexArray(0);
}

}  // namespace sph::render
