// Lines for the container, obstacles and a floor grid, built once per scene from its boundary shapes.
#pragma once

#include <GL/glew.h>

#include <vector>

#include "../common/params.h"
#include "gl_program.h"
#include "math3d.h"

namespace sph::render {

class SceneLines {
 public:
  SceneLines();
  ~SceneLines();
  SceneLines(const SceneLines&) = delete;
  SceneLines& operator=(const SceneLines&) = delete;

  // lo, hi: the extent to cover with the floor grid when no floor shape exists.
  void build(const SimConstants& c, Vec3 lo, Vec3 hi);
  void draw(const Mat4& view, const Mat4& projection) const;

 private:
  struct Vertex {
    Vec3 pos;
    float rgba[4];
  };
  void line(Vec3 a, Vec3 b, const float* rgba);

  GlProgram program_;
  GLuint vao_ = 0, vbo_ = 0;
  std::vector<Vertex> vertices_;
};

}  // namespace sph::render
