// Triangle meshes drawn flat-shaded (shaders/mesh.*): the replay's exported surface meshes.
#pragma once

#include <GL/glew.h>

#include "../common/mesh.h"
#include "gl_program.h"
#include "math3d.h"

namespace sph::render {

class MeshRenderer {
 public:
  MeshRenderer();
  ~MeshRenderer();
  MeshRenderer(const MeshRenderer&) = delete;
  MeshRenderer& operator=(const MeshRenderer&) = delete;

  // Replaces what is drawn by this mesh (vertices [m] as floats, triangles as indices).
  void upload(const TriangleMesh& mesh);
  void draw(const Mat4& view, const Mat4& projection, Vec3 colour) const;
  GLsizei triangles() const { return count_ / 3; }

 private:
  GlProgram program_;
  GLuint vao_ = 0, vbo_ = 0, ebo_ = 0;
  GLsizei count_ = 0;  // indices
};

}  // namespace sph::render
