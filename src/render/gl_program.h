// GLSL programs from files in shaders/ (never strings in C++). Compile and link errors throw with the log.
#pragma once

#include <GL/glew.h>

#include <string>

namespace sph::render {

// The folder holding the .vert / .frag files: $SPH_SHADER_DIR, else the source tree's shaders/.
std::string shader_dir();

class GlProgram {
 public:
  GlProgram(const std::string& vertex_file, const std::string& fragment_file);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  void use() const { glUseProgram(id_); }
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  GLuint id_ = 0;
};

}  // namespace sph::render
