// Particles drawn from two VBOs (positions, colours) with the sphere-impostor shader. The cpu and host
// back ends upload into the VBOs; a CUDA back end can register the same VBOs for interop (vbo ids below).
#pragma once

#include <GL/glew.h>

#include <vector>

#include "../common/particle_state.h"
#include "../common/params.h"
#include "colour_map.h"
#include "particle_colours.h"
#include "gl_program.h"
#include "math3d.h"

namespace sph::render {

class ParticleRenderer {
 public:
  ParticleRenderer();
  ~ParticleRenderer();
  ParticleRenderer(const ParticleRenderer&) = delete;
  ParticleRenderer& operator=(const ParticleRenderer&) = delete;

  // Colours the particles on the host and uploads positions and colours; with `subset`, only the particles
  // of those indices (occlusion_cull.h), coloured on the range of all of them. Returns the colour range used
  // (for the legend).
  ColourRange upload(const ParticleState& ps, const SimConstants& c, ColourMode mode,
                     const std::vector<uint32_t>* subset = nullptr);
  // Uploads points of one colour (the walls' boundary particles).
  void upload_points(const std::vector<Vec3>& positions, Vec3 colour);
  // min_size: the least point size in pixels: 1, or 2 for a set culled to one particle per pixel
  // (occlusion_cull.h), whose sprites must cover their own pixel alone even where the culling's rounding of a
  // centre on a pixel's edge and OpenGL's differ (1 left rows of holes on a lattice's face).
  void draw(const Mat4& view, const Mat4& projection, float radius, int viewport_height, bool flat,
            float min_size = 1.0f) const;
  // The particles as GL_POINTS with the program in use (the fluid surface's passes).
  void draw_points() const;
  GLsizei count() const { return count_; }

  // For interop: make both VBOs hold at least n particles (growing by doubling; every reallocation
  // changes generation()), then let the back end write them and set the count to draw. A reallocation
  // (fits(n) false) needs the back end to have unregistered the VBOs first (Backend::release_gl_buffers).
  void reserve(std::size_t n);
  bool fits(std::size_t n) const { return n <= capacity_ && capacity_ > 0; }
  void set_count(std::size_t n) { count_ = GLsizei(n); }
  GLuint position_vbo() const { return vbo_[0]; }
  GLuint colour_vbo() const { return vbo_[1]; }
  std::size_t capacity() const { return capacity_; }
  uint32_t generation() const { return generation_; }

 private:
  GlProgram program_;
  GLuint vao_ = 0;
  GLuint vbo_[2] = {0, 0};
  GLsizei count_ = 0;
  std::size_t capacity_ = 0;  // particles the VBOs hold
  uint32_t generation_ = 0;
  std::vector<Vec3> colours_;
  std::vector<Vec3> positions_;  // the subset's positions
};

}  // namespace sph::render
