#include "fluid_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace sph::render {
namespace {

GLuint float_texture(GLenum format, int width, int height) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(format), width, height, 0, GL_RED, GL_FLOAT, nullptr);
  // Nearest: the filter and the normals read exact texels, and no depth is ever blended with the empty 0.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  return t;
}

GLuint framebuffer(GLuint texture, GLuint depth_buffer) {
  GLuint f = 0;
  glGenFramebuffers(1, &f);
  glBindFramebuffer(GL_FRAMEBUFFER, f);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
  if (depth_buffer) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("the fluid surface's float framebuffer is not supported by this OpenGL");
  return f;
}

// The pixels [x0, x1) x [y0, y1) the box lo..hi covers on screen, grown by `margin` pixels; the whole
// viewport when a corner is behind the camera.
std::array<int, 4> screen_rect(const Mat4& view, const Mat4& projection, Vec3 lo, Vec3 hi, int width, int height, int margin) {
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (int c = 0; c < 8; ++c) {
    const Vec3 p{(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z};
    float clip[4];
    for (int row = 0; row < 4; ++row) {
      float e = 0.0f;  // (view p)_row, then the projection of it
      for (int k = 0; k < 4; ++k) {
        float v = 0.0f;
        for (int j = 0; j < 4; ++j) v += view[j * 4 + k] * (j == 0 ? p.x : j == 1 ? p.y : j == 2 ? p.z : 1.0f);
        e += projection[k * 4 + row] * v;
      }
      clip[row] = e;
    }
    if (clip[3] <= 1e-6f) return {0, 0, width, height};
    const float sx = (0.5f * clip[0] / clip[3] + 0.5f) * float(width), sy = (0.5f * clip[1] / clip[3] + 0.5f) * float(height);
    x0 = std::min(x0, sx), x1 = std::max(x1, sx), y0 = std::min(y0, sy), y1 = std::max(y1, sy);
  }
  const int ix0 = std::clamp(int(std::floor(x0)) - margin, 0, width), ix1 = std::clamp(int(std::ceil(x1)) + margin, 0, width);
  const int iy0 = std::clamp(int(std::floor(y0)) - margin, 0, height), iy1 = std::clamp(int(std::ceil(y1)) + margin, 0, height);
  return {ix0, iy0, ix1, iy1};
}

}  // namespace

FluidSurfaceRenderer::FluidSurfaceRenderer()
    : depth_("particles.vert", "surface_depth.frag"),
      thickness_("particles.vert", "surface_thickness.frag"),
      smooth_("fullscreen.vert", "surface_smooth.frag"),
      shade_("fullscreen.vert", "surface_shade.frag") {
  glGenVertexArrays(1, &empty_vao_);
}

FluidSurfaceRenderer::~FluidSurfaceRenderer() {
  resize(0, 0);
  glDeleteVertexArrays(1, &empty_vao_);
}

void FluidSurfaceRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  const GLuint fbos[] = {fbo_depth_, fbo_ping_, fbo_pong_, fbo_thickness_};
  const GLuint textures[] = {tex_depth_, tex_ping_, tex_pong_, tex_thickness_};
  glDeleteFramebuffers(4, fbos);
  glDeleteTextures(4, textures);
  glDeleteRenderbuffers(1, &depth_buffer_);
  fbo_depth_ = fbo_ping_ = fbo_pong_ = fbo_thickness_ = tex_depth_ = tex_ping_ = tex_pong_ = tex_thickness_ = depth_buffer_ = 0;
  width_ = width, height_ = height;
  if (width <= 0 || height <= 0) return;
  glGenRenderbuffers(1, &depth_buffer_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  tex_depth_ = float_texture(GL_R32F, width, height);
  tex_ping_ = float_texture(GL_R32F, width, height);
  tex_pong_ = float_texture(GL_R32F, width, height);
  tex_thickness_ = float_texture(GL_R16F, width, height);
  fbo_depth_ = framebuffer(tex_depth_, depth_buffer_);
  fbo_ping_ = framebuffer(tex_ping_, 0);
  fbo_pong_ = framebuffer(tex_pong_, 0);
  fbo_thickness_ = framebuffer(tex_thickness_, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void FluidSurfaceRenderer::draw(const ParticleRenderer& particles, const Mat4& view, const Mat4& projection, float radius,
                                float distance, Vec3 lo, Vec3 hi, int width, int height, const SurfaceLook& look,
                                Vec3 background) {
  if (particles.count() == 0 || width <= 0 || height <= 0) return;
  GLint target = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &target);
  resize(width, height);
  const float r = radius * look.radius_scale;
  auto sprite_uniforms = [&](const GlProgram& p) {
    p.use();
    glUniformMatrix4fv(p.uniform("u_view"), 1, GL_FALSE, view.data());
    glUniformMatrix4fv(p.uniform("u_projection"), 1, GL_FALSE, projection.data());
    glUniform1f(p.uniform("u_radius"), r);
    glUniform1f(p.uniform("u_viewport_height"), float(height));
    glUniform1f(p.uniform("u_min_size"), 1.0f);
  };

  // 1. Eye depth of the nearest sphere surface.
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_depth_);
  glViewport(0, 0, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  sprite_uniforms(depth_);
  particles.draw_points();

  // 2. Thickness: every sphere's chord, added up.
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_thickness_);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  sprite_uniforms(thickness_);
  particles.draw_points();
  glDisable(GL_BLEND);

  // 3. Bilateral smoothing of the depth, separable, ping-pong. The spatial scale follows a particle's size on screen
  // at the median distance, so the bumps of one sphere are smoothed at any zoom.
  const float focal_px = projection[5] * 0.5f * float(height);
  const float sphere_px = std::clamp(focal_px * r / std::max(distance, 1e-6f), 1.0f, 12.0f);
  // The full-screen passes run over the domain's image only (on a software rasteriser they cost as much as
  // the spheres); ping and pong are cleared first, since a pass reads up to its reach beyond the rectangle.
  const int reach = int(std::ceil(1.5f * sphere_px));
  const Vec3 grow{r, r, r};
  const std::array<int, 4> rect = screen_rect(view, projection, lo - grow, hi + grow, width, height, reach + 2);
  for (GLuint f : {fbo_ping_, fbo_pong_}) {
    glBindFramebuffer(GL_FRAMEBUFFER, f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glEnable(GL_SCISSOR_TEST);
  glScissor(rect[0], rect[1], rect[2] - rect[0], rect[3] - rect[1]);
  GLuint source = tex_depth_;
  glBindVertexArray(empty_vao_);
  smooth_.use();
  glUniform1f(smooth_.uniform("u_sigma_px"), sphere_px);
  glUniform1f(smooth_.uniform("u_sigma_depth"), 2.0f * r);
  glUniform1i(smooth_.uniform("u_radius_px"), reach);
  glUniform1i(smooth_.uniform("u_depth"), 0);
  glActiveTexture(GL_TEXTURE0);
  for (int pass = 0; pass < 2 * look.smoothing_iterations; ++pass) {  // horizontal, then vertical
    const bool to_ping = source != tex_ping_;
    glBindFramebuffer(GL_FRAMEBUFFER, to_ping ? fbo_ping_ : fbo_pong_);
    glBindTexture(GL_TEXTURE_2D, source);
    if (pass % 2 == 0) glUniform2f(smooth_.uniform("u_step"), 1.0f / float(width), 0.0f);
    else glUniform2f(smooth_.uniform("u_step"), 0.0f, 1.0f / float(height));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    source = to_ping ? tex_ping_ : tex_pong_;
  }

  // 4. Shading into the caller's framebuffer, with depth.
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  shade_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, source);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, tex_thickness_);
  glUniform1i(shade_.uniform("u_depth"), 0);
  glUniform1i(shade_.uniform("u_thickness"), 1);
  glUniform2f(shade_.uniform("u_texel"), 1.0f / float(width), 1.0f / float(height));
  glUniformMatrix4fv(shade_.uniform("u_projection"), 1, GL_FALSE, projection.data());
  glUniformMatrix4fv(shade_.uniform("u_view"), 1, GL_FALSE, view.data());
  const Vec3 light = normalise(transform_direction(view, Vec3{0.4f, 1.0f, 0.6f}));
  glUniform3f(shade_.uniform("u_light"), light.x, light.y, light.z);
  glUniform3f(shade_.uniform("u_colour"), look.colour.x, look.colour.y, look.colour.z);
  glUniform1f(shade_.uniform("u_absorption"), look.absorption);
  glUniform3f(shade_.uniform("u_background"), background.x, background.y, background.z);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_SCISSOR_TEST);
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace sph::render
