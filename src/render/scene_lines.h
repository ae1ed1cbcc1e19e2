// Lines for the container, obstacles and a floor grid, built once per scene from its boundary shapes.
#pragma once

#include <GL/glew.h>

#include <vector>

#include "../common/boundary_particles.h"
#include "../common/params.h"
#include "../common/rigid_body.h"
#include "gl_program.h"
#include "math3d.h"

namespace sph::render {

class SceneLines {
 public:
  SceneLines();
  ~SceneLines();
  SceneLines(const SceneLines&) = delete;
  SceneLines& operator=(const SceneLines&) = delete;

  // lo, hi: the extent to cover with the floor grid when no floor shape exists. Meshes: each edge once.
  void build(const SimConstants& c, const std::vector<MeshSolid>& meshes, Vec3 lo, Vec3 hi);
  // The rigid bodies where they are now (box edges, a sphere's three great circles), replacing the last ones.
  void set_bodies(const std::vector<RigidBody>& bodies);
  void draw(const Mat4& view, const Mat4& projection) const;

 private:
  struct Vertex {
    Vec3 pos;
    float rgba[4];
  };
  void line(Vec3 a, Vec3 b, const float* rgba);

  GlProgram program_;
  GLuint vao_ = 0, vbo_ = 0;
  void upload();
  std::vector<Vertex> vertices_;
  std::size_t static_count_ = 0;  // vertices of the scene's shapes and meshes; the bodies' follow
};

}  // namespace sph::render
