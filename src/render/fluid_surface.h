// Screen-space fluid rendering (van der Laan, Green and Sainz 2009; thesis section 4.3's third way to draw
// a fluid): the particles of a ParticleRenderer (the same VBOs the CUDA path writes by interop) are drawn
// as spheres into an eye-depth texture, the depth is smoothed by a few bilateral-filter passes, a thickness
// texture is accumulated, and a full-screen pass shades the surface (normals from the smoothed depth,
// Fresnel reflection of a sky, absorption through the thickness, a highlight). GLSL in shaders/surface_*.
#pragma once

#include <GL/glew.h>

#include "gl_program.h"
#include "math3d.h"
#include "particle_renderer.h"

namespace sph::render {

// What the panel edits.
struct SurfaceLook {
  int smoothing_iterations = 4;  // bilateral passes, 0 to 20
  float radius_scale = 1.5f;     // sphere radius over the particle radius (d/2): 1 to 3
  Vec3 colour{0.25f, 0.55f, 0.85f};
  float absorption = 12.0f;      // [1/m], scaled per channel by how little of it the colour transmits
};

class FluidSurfaceRenderer {
 public:
  FluidSurfaceRenderer();
  ~FluidSurfaceRenderer();
  FluidSurfaceRenderer(const FluidSurfaceRenderer&) = delete;
  FluidSurfaceRenderer& operator=(const FluidSurfaceRenderer&) = delete;

  // Draws the particles' surface into the bound framebuffer (viewport width x height pixels; depth test on,
  // it writes depth), radius: the particles' radius [m], distance: the camera's to what it looks at [m] (the
  // filter's width follows a sphere's size there), lo and hi: a box [m] the fluid stays in (the domain; the
  // screen-space passes only run over its image), background: the clear colour seen through the water.
  // Throws std::runtime_error where float framebuffers are not supported.
  void draw(const ParticleRenderer& particles, const Mat4& view, const Mat4& projection, float radius, float distance,
            Vec3 lo, Vec3 hi, int width, int height, const SurfaceLook& look, Vec3 background);

 private:
  void resize(int width, int height);

  GlProgram depth_, thickness_, smooth_, shade_;
  GLuint empty_vao_ = 0;                   // the full-screen triangle needs a bound VAO, not a buffer
  GLuint fbo_depth_ = 0, fbo_ping_ = 0, fbo_pong_ = 0, fbo_thickness_ = 0;
  GLuint tex_depth_ = 0, tex_ping_ = 0, tex_pong_ = 0, tex_thickness_ = 0, depth_buffer_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace sph::render
