// Reads the framebuffer and writes a PNG (stb_image_write).
#pragma once

#include <string>

namespace sph::render {

// Throws std::runtime_error when the file cannot be written.
void write_screenshot(const std::string& path, int width, int height);

}  // namespace sph::render
