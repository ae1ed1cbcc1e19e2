#include "screenshot.h"

#include <GL/glew.h>

#include <stdexcept>
#include <vector>

#include <stb_image_write.h>

namespace sph::render {

void write_screenshot(const std::string& path, int width, int height) {
  std::vector<unsigned char> pixels(std::size_t(width) * std::size_t(height) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  stbi_flip_vertically_on_write(1);  // OpenGL's first row is the bottom one
  if (!stbi_write_png(path.c_str(), width, height, 3, pixels.data(), width * 3))
    throw std::runtime_error("cannot write screenshot " + path);
}

}  // namespace sph::render
