// sph_interop_probe: does CUDA-OpenGL interop work on this machine, without a display? (issue 11, Build
// item 8: the stand-in for the demo where it cannot open a window, as on a bare GPU server.)
//
// It opens an OpenGL 3.3 context through EGL on the GPU itself (EGL_EXT_platform_device, a 16x16 pbuffer:
// no X server), runs the dam break a few steps on the cuda back end, lets the back end write two vertex
// buffers through Backend::write_gl_buffers (registration, the device check of cudaGLGetDevices, mapping
// and the render kernel: the demo's path), reads them back with glGetBufferSubData and compares them with
// the host path (render/particle_colours.h) in every colour mode. Then it grows the buffers the demo's way
// (release, glBufferData, register again) and writes once more, and tears down in the demo's order (the
// back end unregisters before the buffers are deleted).
//
// libEGL.so.1 (the GL vendor-neutral dispatch library, glvnd) is opened at run time, so the probe builds
// without EGL libraries and runs wherever the driver's EGL is reachable. Prints one line and exits:
//   RESULT: ... , 0   interop works and gives the host path's positions and colours
//   FAIL: ...,    1   interop fell back or wrote something else
//   SKIP: ...,    77  no GPU, no EGL, or no OpenGL context on the GPU (the reason is named)
// With an argument N it also times one write on the dam break at N particles across (80: about 1M).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "../common/scene.h"
#include "../common/simulation.h"
#include "../cuda/device_backend.h"
#include "../render/particle_colours.h"
#include "backends.h"

namespace {

int skip(const std::string& why) {
  std::printf("SKIP: %s\n", why.c_str());
  return 77;
}
int fail(const std::string& why) {
  std::printf("FAIL: %s\n", why.c_str());
  return 1;
}

// The EGL and OpenGL entry points the probe uses, looked up at run time.
struct Gl {
  PFNEGLGETPROCADDRESSPROC get_proc = nullptr;
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC platform_display = nullptr;
  PFNEGLINITIALIZEPROC initialise = nullptr;
  PFNEGLTERMINATEPROC terminate = nullptr;
  PFNEGLBINDAPIPROC bind_api = nullptr;
  PFNEGLCHOOSECONFIGPROC choose_config = nullptr;
  PFNEGLCREATEPBUFFERSURFACEPROC create_pbuffer = nullptr;
  PFNEGLCREATECONTEXTPROC create_context = nullptr;
  PFNEGLMAKECURRENTPROC make_current = nullptr;
  const GLubyte* (*get_string)(GLenum) = nullptr;
  void (*gen_buffers)(GLsizei, GLuint*) = nullptr;
  void (*bind_buffer)(GLenum, GLuint) = nullptr;
  void (*buffer_data)(GLenum, GLsizeiptr, const void*, GLenum) = nullptr;
  void (*get_buffer_sub_data)(GLenum, GLintptr, GLsizeiptr, void*) = nullptr;
  void (*delete_buffers)(GLsizei, const GLuint*) = nullptr;
  GLenum (*get_error)() = nullptr;

  template <class F>
  bool egl(void* lib, F& f, const char* name) {
    f = reinterpret_cast<F>(dlsym(lib, name));
    return f != nullptr;
  }
  template <class F>
  bool ext(F& f, const char* name) {
    f = reinterpret_cast<F>(get_proc(name));
    return f != nullptr;
  }
};

// A current OpenGL context on an NVIDIA EGL device, or "" and the reason in why.
std::string open_context(Gl& gl, std::string& why) {
  auto none = [&why](const std::string& reason) {
    why = reason;
    return std::string();
  };
  void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_GLOBAL);
  if (!lib) return none(std::string("no EGL: ") + dlerror());
  if (!gl.egl(lib, gl.get_proc, "eglGetProcAddress") || !gl.egl(lib, gl.initialise, "eglInitialize") ||
      !gl.egl(lib, gl.terminate, "eglTerminate") || !gl.egl(lib, gl.bind_api, "eglBindAPI") ||
      !gl.egl(lib, gl.choose_config, "eglChooseConfig") || !gl.egl(lib, gl.create_pbuffer, "eglCreatePbufferSurface") ||
      !gl.egl(lib, gl.create_context, "eglCreateContext") || !gl.egl(lib, gl.make_current, "eglMakeCurrent"))
    return none("libEGL.so.1 lacks EGL 1.4 entry points");
  if (!gl.ext(gl.query_devices, "eglQueryDevicesEXT") || !gl.ext(gl.platform_display, "eglGetPlatformDisplayEXT"))
    return none("EGL has no device platform (EGL_EXT_device_enumeration, EGL_EXT_platform_device): no EGL driver found");
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!gl.query_devices(16, devices, &count) || count == 0) return none("EGL lists no device");
  std::string seen;
  for (EGLint k = 0; k < count; ++k) {
    EGLDisplay display = gl.platform_display(EGL_PLATFORM_DEVICE_EXT, devices[k], nullptr);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !gl.initialise(display, &major, &minor) || !gl.bind_api(EGL_OPENGL_API)) continue;
    const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    const EGLint pbuffer_attributes[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLConfig config{};
    EGLint configs = 0;
    EGLSurface surface = EGL_NO_SURFACE;
    EGLContext context = EGL_NO_CONTEXT;
    if (gl.choose_config(display, config_attributes, &config, 1, &configs) && configs > 0 &&
        (surface = gl.create_pbuffer(display, config, pbuffer_attributes)) != EGL_NO_SURFACE &&
        (context = gl.create_context(display, config, EGL_NO_CONTEXT, context_attributes)) != EGL_NO_CONTEXT &&
        gl.make_current(display, surface, surface, context) && gl.ext(gl.get_string, "glGetString")) {
      const std::string vendor = reinterpret_cast<const char*>(gl.get_string(GL_VENDOR));
      const std::string renderer = reinterpret_cast<const char*>(gl.get_string(GL_RENDERER));
      if (vendor.find("NVIDIA") != std::string::npos) return renderer;
      seen += (seen.empty() ? "" : ", ") + renderer;
    }
    gl.terminate(display);
  }
  return none("no EGL device gives an OpenGL 3.3 context on an NVIDIA GPU" + (seen.empty() ? std::string() : " (found: " + seen + ")"));
}

// The largest difference between what the back end wrote into the buffers and the host path, over
// positions (which must be bit-identical: -1 when they are not) and the colours of every colour mode.
double compare_modes(sph::Backend& b, const sph::SimConstants& c, const Gl& gl, const GLuint vbo[2], std::size_t capacity,
                     uint32_t generation, std::string& why) {
  const sph::ParticleState ps = b.download();
  std::vector<sph::Vec3> positions(ps.size()), colours(ps.size()), expected;
  double worst = 0.0;
  for (int m = 0; m < int(sph::render::ColourMode::Count); ++m) {
    const auto mode = sph::render::ColourMode(m);
    const sph::render::ColourRange range = sph::render::colour_range(ps, mode);
    sph::render::colour_particles(ps, c, mode, range, expected);
    sph::GlBuffers req;
    req.position_vbo = vbo[0];
    req.colour_vbo = vbo[1];
    req.capacity = capacity;
    req.generation = generation;
    req.colouring = sph::RenderColouring{m, range.lo, range.hi};
    if (!b.write_gl_buffers(req, why)) {
      if (why.empty()) why = "the cuda back end was built without OpenGL interop (no GL/glew.h)";
      why = "interop fell back: " + why;
      return -1.0;
    }
    const GLsizeiptr bytes = GLsizeiptr(ps.size() * sizeof(sph::Vec3));
    gl.bind_buffer(GL_ARRAY_BUFFER, vbo[0]);
    gl.get_buffer_sub_data(GL_ARRAY_BUFFER, 0, bytes, positions.data());
    gl.bind_buffer(GL_ARRAY_BUFFER, vbo[1]);
    gl.get_buffer_sub_data(GL_ARRAY_BUFFER, 0, bytes, colours.data());
    gl.bind_buffer(GL_ARRAY_BUFFER, 0);
    if (std::memcmp(positions.data(), ps.pos.data(), std::size_t(bytes)) != 0) {
      why = "positions read back differ from the back end's";
      return -1.0;
    }
    for (std::size_t i = 0; i < ps.size(); ++i)
      worst = std::max({worst, double(std::fabs(colours[i].x - expected[i].x)), double(std::fabs(colours[i].y - expected[i].y)),
                        double(std::fabs(colours[i].z - expected[i].z))});
  }
  return worst;
}

// Milliseconds of one interop write (speed colours, the demo's default), averaged over 20; -1 when the
// back end falls back.
double write_ms(sph::Backend& b, const sph::GlBuffers& req, std::string& why) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < 20; ++i)
    if (!b.write_gl_buffers(req, why)) return -1.0;
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / 20.0;
}

// timing_across > 0: also times the write on the dam break with that many particles across the column
// (80: about 1M particles, the demo's target of 60 fps).
int probe(int timing_across) {
  std::string why;
  if (!sph::cuda_device_available(&why)) return skip("no GPU: " + why);
  Gl gl;
  const std::string renderer = open_context(gl, why);
  if (renderer.empty()) return skip(why);
  if (!gl.ext(gl.gen_buffers, "glGenBuffers") || !gl.ext(gl.bind_buffer, "glBindBuffer") ||
      !gl.ext(gl.buffer_data, "glBufferData") || !gl.ext(gl.get_buffer_sub_data, "glGetBufferSubData") ||
      !gl.ext(gl.delete_buffers, "glDeleteBuffers") || !gl.ext(gl.get_error, "glGetError"))
    return fail("the OpenGL context lacks buffer functions");
  const std::string scene_path = std::string(SPH_SOURCE_DIR) + "/scenes/dam_break.json";
  auto sim = std::make_unique<sph::Simulation>(sph::load_scene(scene_path, {}), sph::backend_factory("cuda"), 1.0);
  for (int i = 0; i < 20; ++i) sim->advance();
  sph::Backend& b = sim->backend();
  GLuint vbo[2] = {0, 0};
  gl.gen_buffers(2, vbo);
  auto allocate = [&](std::size_t particles) {
    for (GLuint v : vbo) {
      gl.bind_buffer(GL_ARRAY_BUFFER, v);
      gl.buffer_data(GL_ARRAY_BUFFER, GLsizeiptr(particles * sizeof(sph::Vec3)), nullptr, GL_DYNAMIC_DRAW);
    }
    gl.bind_buffer(GL_ARRAY_BUFFER, 0);
  };
  const std::size_t n = b.size();
  allocate(n);
  const double first = compare_modes(b, sim->setup().constants, gl, vbo, n, 1, why);
  if (first < 0.0) return fail("on " + renderer + ": " + why);
  // The demo's growth: unregister, reallocate, register again (a new generation).
  b.release_gl_buffers();
  allocate(2 * n);
  const double second = compare_modes(b, sim->setup().constants, gl, vbo, 2 * n, 2, why);
  if (second < 0.0) return fail("after reallocation, on " + renderer + ": " + why);
  const double ms = write_ms(b, sph::GlBuffers{vbo[0], vbo[1], 2 * n, 2, sph::RenderColouring{1, 0.0f, 1.0f}}, why);
  if (ms < 0.0) return fail("interop fell back after working: " + why);
  std::string large;
  if (timing_across > 0) {
    b.release_gl_buffers();  // the 16k back end lets go before the buffers grow for the large one
    sim = std::make_unique<sph::Simulation>(
        sph::load_scene(scene_path, {"resolution.particles_across=" + std::to_string(timing_across)}),
        sph::backend_factory("cuda"), 1.0);
    const std::size_t big = sim->backend().size();
    allocate(big);
    const double big_ms = write_ms(sim->backend(), sph::GlBuffers{vbo[0], vbo[1], big, 3, sph::RenderColouring{1, 0.0f, 1.0f}}, why);
    if (big_ms < 0.0) return fail("interop fell back at " + std::to_string(big) + " particles: " + why);
    large = "; " + std::to_string(big) + " particles: " + std::to_string(big_ms) + " ms per write";
  }
  sim.reset();  // the back end unregisters the buffers before they are deleted
  gl.delete_buffers(2, vbo);
  if (const GLenum e = gl.get_error(); e != GL_NO_ERROR) return fail("OpenGL error " + std::to_string(e) + " on " + renderer);
  const double tolerance = 1e-5;  // colours in [0, 1]; nvcc may fuse multiply-adds where g++ does not
  if (std::max(first, second) > tolerance)
    return fail("colours differ from the host path by " + std::to_string(std::max(first, second)) + " on " + renderer);
  std::printf("RESULT: interop on %s: %zu particles, positions bit-identical, colours within %.1e of the host path "
              "(5 modes, also after reallocation), %.3f ms per write%s\n",
              renderer.c_str(), n, std::max(first, second), ms, large.c_str());
  return 0;
}

}  // namespace

// Usage: sph_interop_probe [PARTICLES_ACROSS], the dam break resolution at which the write is also timed.
int main(int argc, char** argv) {
  char* end = nullptr;
  const long timing_across = argc > 1 ? std::strtol(argv[1], &end, 10) : 0;
  if (argc > 2 || (argc > 1 && (*end != '\0' || end == argv[1])) || timing_across < 0 || timing_across > 1000)
    return fail("usage: sph_interop_probe [PARTICLES_ACROSS, 0 to 1000]");
  try {
    return probe(int(timing_across));
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}
