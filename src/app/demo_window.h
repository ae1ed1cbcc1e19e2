// sph_demo's window: GLFW with an OpenGL 3.3 core context, GLEW, and Dear ImGui on it; shared by the live
// demo and the replay.
#pragma once

#include <GLFW/glfw3.h>

#include "../render/camera.h"
#include "../render/math3d.h"
#include "demo_options.h"

namespace sph {

// Opens the window (o.width x o.height; no vsync for headless --frames runs) and sets up OpenGL (depth test,
// program point size) and Dear ImGui. Returns nullptr, with the reason and what to do on stderr, when there
// is no display, no OpenGL 3.3 core context or GLEW cannot load it (the caller exits 2).
GLFWwindow* open_demo_window(const DemoOptions& o);

// The background (clear colour, 0-1), which the surface also shows through the water.
constexpr float kBackground[3] = {0.11f, 0.12f, 0.14f};

// The start of a drawn frame: the framebuffer's size, the viewport and a clear, and the camera's matrices.
struct FrameView {
  int width = 0, height = 0;  // pixels
  render::Mat4 view{}, projection{};
  Vec3 background() const { return Vec3{kBackground[0], kBackground[1], kBackground[2]}; }
};
FrameView begin_frame(GLFWwindow* window, const render::OrbitCamera& camera);

// The GLFW key of a --keys character (upper-case letters, space, brackets, + and -).
int glfw_key_of(char c);

// Shuts Dear ImGui down and closes the window and GLFW.
void close_demo_window(GLFWwindow* window);

}  // namespace sph
