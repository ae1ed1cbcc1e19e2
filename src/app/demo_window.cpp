// The demo's window (demo_window.h).
#include <GL/glew.h>

#include "demo_window.h"

#include <cstdlib>
#include <iostream>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

namespace sph {
namespace {

void on_glfw_error(int code, const char* text) { std::cerr << "GLFW error " << code << ": " << text << "\n"; }

}  // namespace

GLFWwindow* open_demo_window(const DemoOptions& o) {
  glfwSetErrorCallback(on_glfw_error);
  const char* display = std::getenv("DISPLAY");
  if (!glfwInit() || !display || !*display) {
    std::cerr << "error: no display: sph_demo opens a window and needs an X server (DISPLAY is "
              << (display && *display ? display : "unset") << ").\n"
              << "For a picture without a screen run it under Xvfb, for example\n"
              << "  xvfb-run -a -s '-screen 0 1280x720x24' build/sph_demo --frames 120 --screenshot out/demo.png\n"
              << "or simulate without drawing with build/sph_run.\n";
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GL_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 4);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, "sph_demo", nullptr, nullptr);
  if (!window) {
    std::cerr << "error: cannot create an OpenGL 3.3 core window on this display\n";
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(o.frames > 0 ? 0 : 1);
  glewExperimental = GL_TRUE;
  if (glewInit() != GLEW_OK) {
    std::cerr << "error: GLEW could not load OpenGL functions\n";
    glfwDestroyWindow(window);
    glfwTerminate();
    return nullptr;
  }
  while (glGetError() != GL_NO_ERROR) {
  }  // glewInit leaves a harmless GL_INVALID_ENUM on core profiles
  std::cout << "OpenGL " << glGetString(GL_VERSION) << " on " << glGetString(GL_RENDERER) << "\n";
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_PROGRAM_POINT_SIZE);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  return window;
}

FrameView begin_frame(GLFWwindow* window, const render::OrbitCamera& camera) {
  FrameView f;
  glfwGetFramebufferSize(window, &f.width, &f.height);
  glViewport(0, 0, f.width, f.height);
  glClearColor(kBackground[0], kBackground[1], kBackground[2], 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  f.view = camera.view();
  f.projection = camera.projection(float(f.width) / float(f.height > 1 ? f.height : 1));
  return f;
}

int glfw_key_of(char c) {
  switch (c) {
    case '[': return GLFW_KEY_LEFT_BRACKET;
    case ']': return GLFW_KEY_RIGHT_BRACKET;
    case '+': return GLFW_KEY_EQUAL;
    case '-': return GLFW_KEY_MINUS;
    default: return int(c);  // GLFW_KEY_SPACE and GLFW_KEY_A..Z are the ASCII codes
  }
}

void close_demo_window(GLFWwindow* window) {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
}

}  // namespace sph
