#include "gl_program.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace sph::render {

std::string shader_dir() {
  const char* env = std::getenv("SPH_SHADER_DIR");
  return env ? env : SPH_DEFAULT_SHADER_DIR;
}

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read shader " + path + " (set SPH_SHADER_DIR to the shaders/ folder)");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

GLuint compile(GLenum type, const std::string& path) {
  const std::string source = read_file(path);
  const GLuint s = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(std::size_t(len > 0 ? len : 1));
    glGetShaderInfoLog(s, GLsizei(log.size()), nullptr, log.data());
    glDeleteShader(s);
    throw std::runtime_error("shader " + path + " does not compile:\n" + std::string(log.data()));
  }
  return s;
}

}  // namespace

GlProgram::GlProgram(const std::string& vertex_file, const std::string& fragment_file) {
  const std::string dir = shader_dir() + "/";
  const GLuint vs = compile(GL_VERTEX_SHADER, dir + vertex_file);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, dir + fragment_file);
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(id_, sizeof log, nullptr, log);
    glDeleteProgram(id_);
    throw std::runtime_error("shaders " + vertex_file + " + " + fragment_file + " do not link:\n" + log);
  }
}

GlProgram::~GlProgram() {
  if (id_) glDeleteProgram(id_);
}

}  // namespace sph::render
