// sph_demo --replay: playing an sph_run recording (demo_replay.h).
#include <GL/glew.h>

#include "demo_replay.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <stdexcept>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "../common/guided_creation.h"
#include "../common/mesh_ply.h"
#include "../common/setup_budget.h"
#include "../common/scene.h"
#include "../render/camera.h"
#include "../render/fluid_surface.h"
#include "../render/mesh_renderer.h"
#include "../render/occlusion_cull.h"
#include "../render/particle_renderer.h"
#include "../render/scene_lines.h"
#include "../render/screenshot.h"
#include "../render/ui_panel.h"
#include "demo_window.h"

namespace fs = std::filesystem;

namespace sph {

using namespace render;

namespace {

// A frame file stores about this many bytes a particle (frame_writer.h's record).
constexpr double kFrameBytesPerParticle = 60.0;

// --cull auto: cull hidden particles (occlusion_cull.h) while a sphere at the camera's target is at most this
// many pixels across and the particles outnumber a quarter of the view's pixels; above that size a particle
// behind another's centre can still show at its rim, and with fewer particles drawing them all is cheap.
constexpr float kCullDiameterPixels = 2.0f;

}  // namespace

Recording load_recording(const std::string& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw std::runtime_error("--replay " + folder + (fs::exists(folder, ec) ? ": not a folder (give the sph_run output folder)" : ": no such folder"));
  std::vector<std::string> paths;
  std::uintmax_t bytes = 0;
  for (const auto& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("frame_", 0) == 0 && e.path().extension() == ".ply") {
      paths.push_back(e.path().string());
      bytes += e.file_size(ec);
    }
  }
  if (paths.empty())
    throw std::runtime_error("--replay " + folder + ": no frame_NNNNN.ply in it (sph_run --frames-every SECONDS writes them)");
  std::sort(paths.begin(), paths.end());
  // In memory a particle of a frame takes kBytesPerParticle (particle_state.h).
  const double need = double(bytes) / kFrameBytesPerParticle * double(kBytesPerParticle), have = usable_memory_bytes();
  if (need > have) {
    char text[256];
    std::snprintf(text, sizeof text, "--replay %s: its %zu frames need about %.1f GB in memory, more than the %.1f GB a run may use here (half this machine's memory)",
                  folder.c_str(), paths.size(), need / 1e9, have / 1e9);
    throw std::runtime_error(text);
  }
  Recording r;
  r.folder = folder;
  const bool tty = isatty(STDERR_FILENO);
  for (std::size_t k = 0; k < paths.size(); ++k) {
    Frame f = read_ply_frame(paths[k], 1e9);
    if (!r.frames.empty()) {
      const FrameInfo& first = r.frames.front().info;
      if (f.info.scene != first.scene || f.info.spacing != first.spacing)
        throw std::runtime_error(paths[k] + ": a frame of another run (scene " + f.info.scene + ", spacing " +
                                 std::to_string(f.info.spacing) + " m) among frames of scene " + first.scene +
                                 " at spacing " + std::to_string(first.spacing) + " m");
      if (!(f.info.time > r.frames.back().info.time))
        throw std::runtime_error(paths[k] + ": its time " + std::to_string(f.info.time) + " s does not come after " +
                                 r.frames.back().path + "'s " + std::to_string(r.frames.back().info.time) + " s");
    }
    r.frames.push_back(std::move(f));
    if (tty) std::fprintf(stderr, "\rreading %s: frame %zu of %zu   ", folder.c_str(), k + 1, paths.size());
  }
  if (tty) std::fprintf(stderr, "\n");
  std::vector<std::string> meshes;
  for (const auto& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("surface_", 0) == 0 && e.path().extension() == ".ply") meshes.push_back(e.path().string());
  }
  for (const std::string& path : meshes) {
    Recording::Surface s;
    s.path = path;
    s.mesh = read_ply_mesh(path, s.time);
    if (!std::isfinite(s.time)) throw std::runtime_error(path + ": the mesh records no time (comment time T)");
    r.surfaces.push_back(std::move(s));
  }
  std::sort(r.surfaces.begin(), r.surfaces.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  return r;
}

namespace {

class Replay {
 public:
  Replay(GLFWwindow* window, const DemoOptions& o, const Recording& r) : window_(window), opt_(o), rec_(r) {
    const char* modes[] = {"fluid", "speed", "density_error", "pressure", "cell"};
    for (int i = 0; i < int(ColourMode::Count); ++i)
      if (o.colour == modes[i]) colour_ = i;
    constants_for_colours();
    camera_.frame(lo_, hi_);
    camera_.yaw = 0.0f;
    camera_.pitch = 0.35f;
    radius_ = 0.5f * float(rec_.frames.front().info.spacing);
    surface_ = o.render == "surface";
    clock_ = rec_.frames.front().info.time;
    show(0);
    mesh_ = o.render == "mesh" && !rec_.surfaces.empty();
    if (o.render == "mesh" && rec_.surfaces.empty())
      std::cerr << "sph_demo: " << rec_.folder << " has no surface_NNNNN.ply meshes (sph_run --surface-every, sph_surface); "
                   "drawing spheres\n";
  }

  // One drawn frame: the playback clock moves by `advance` seconds times the speed (looping or stopping at
  // the end), the frame it has reached is shown, then the panel; wall_seconds since the last frame, for fps.
  void frame(double advance, double wall_seconds) {
    const double t0 = rec_.frames.front().info.time, t1 = rec_.frames.back().info.time;
    if (playing_) {
      clock_ += advance * speed_;
      if (clock_ > t1) {
        if (loop_ && t1 > t0) clock_ = t0 + std::fmod(clock_ - t0, t1 - t0);
        else clock_ = t1, playing_ = false;
      }
      std::size_t k = index_;
      while (k + 1 < rec_.frames.size() && rec_.frames[k + 1].info.time <= clock_) ++k;
      while (k > 0 && rec_.frames[k].info.time > clock_) --k;
      show(k);
    }
    if (colour_ != shown_colour_) show(index_, true);
    if (mesh_) show_mesh();
    const auto d0 = std::chrono::steady_clock::now();
    const FrameView f = begin_frame(window_, camera_);
    upload(f);
    lines_.draw(f.view, f.projection);
    if (mesh_) meshes_.draw(f.view, f.projection, look_.colour);
    else if (surface_)
      surface_renderer_.draw(particles_, f.view, f.projection, radius_, camera_.distance, lo_, hi_, f.width, f.height, look_,
                             f.background());
    else particles_.draw(f.view, f.projection, radius_, f.height, flat_, culled_ ? 2.0f : 1.0f);
    panel();
    glFinish();  // so that the drawing time is the renderer's, not only the commands' submission
    draw_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - d0).count();
    // Frames per second over the last second or so of wall time (the first frame's interval is the set-up's).
    if (frames_ > 0) fps_ = fps_ == 0.0 ? 1.0 / std::max(wall_seconds, 1e-6) : 0.8 * fps_ + 0.2 / std::max(wall_seconds, 1e-6);
    ++frames_;
  }

  // Space: play or pause; N, B: the next or previous frame (pausing); L: loop; C: colour; V: flat points;
  // S: surface; M: the exported meshes; + and -: twice or half the speed; Escape: quit.
  void key(int k) {
    switch (k) {
      case GLFW_KEY_SPACE: playing_ = !playing_; break;
      case GLFW_KEY_N: step(+1); break;
      case GLFW_KEY_B: step(-1); break;
      case GLFW_KEY_L: loop_ = !loop_; break;
      case GLFW_KEY_C: colour_ = (colour_ + 1) % int(ColourMode::Count); break;
      case GLFW_KEY_V: flat_ = !flat_; break;
      case GLFW_KEY_S: surface_ = !surface_; break;
      case GLFW_KEY_M: mesh_ = !mesh_ && !rec_.surfaces.empty(); break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD: speed_ = std::min(64.0, speed_ * 2.0); break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT: speed_ = std::max(1.0 / 64.0, speed_ / 2.0); break;
      case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, 1); break;
      default: break;
    }
  }
  void scroll(double dy) { camera_.zoom(std::pow(0.9f, float(dy))); }
  // Mouse: left drag orbits, right drag pans.
  void mouse() {
    double mx = 0.0, my = 0.0;
    glfwGetCursorPos(window_, &mx, &my);
    const float dx = float(mx - last_x_), dy = float(my - last_y_);
    last_x_ = mx, last_y_ = my;
    if (ImGui::GetIO().WantCaptureMouse) return;
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) camera_.orbit(0.005f * dx, 0.005f * dy);
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
      int w = 0, h = 0;
      glfwGetWindowSize(window_, &w, &h);
      camera_.pan(dx / float(std::max(h, 1)), dy / float(std::max(h, 1)));
    }
  }

  bool idle() const { return !playing_; }
  long frames() const { return frames_; }
  void summary() const {
    std::cout << "replay: " << rec_.folder << "\nscene: " << rec_.frames.front().info.scene << "\nframes: " << frames_
              << "\nrecorded_frames: " << rec_.frames.size() << "\nshown_frame: " << index_
              << "\nparticles: " << rec_.frames[index_].particles.size() << "\nreplay_time: " << clock_
              << "\ndrawn_particles: " << particles_.count() << "\nfps: " << fps_ << "\ndraw_ms_per_frame: " << draw_ms_ << "\n";
    if (mesh_) std::cout << "mesh: " << rec_.surfaces[shown_mesh_].path << "\nmesh_triangles: " << meshes_.triangles() << "\n";
  }

 private:
  // Rest densities and grid for the colours, and the container's lines: from the recording's scene
  // (NAME.json beside the command line's scene), else rest density 1000 kg/m^3 and a grid over the frames.
  void constants_for_colours() {
    const FrameInfo& info = rec_.frames.front().info;
    const fs::path scene_file = fs::path(opt_.scene).parent_path() / (info.scene + ".json");
    Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    int32_t fluids = 1;
    for (const Frame& f : rec_.frames)
      for (std::size_t i = 0; i < f.particles.size(); ++i) {
        const Vec3 x = f.particles.pos[i];
        lo = Vec3{std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
        hi = Vec3{std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
        fluids = std::max(fluids, int32_t(f.particles.fluid[i]) + 1);
      }
    if (!(lo.x <= hi.x)) lo = hi = Vec3{0.0f, 0.0f, 0.0f};  // frames without particles
    lo_ = lo, hi_ = hi;
    try {
      const Scene scene = load_scene(scene_file.string(), {});
      const Setup setup = create_setup(scene, 0.0);
      if (setup.constants.num_fluids < fluids) throw std::runtime_error("its fluids are fewer than the frames name");
      if (std::fabs(setup.spacing - info.spacing) > 1e-9 * info.spacing)
        std::cerr << "sph_demo: " << scene_file.string() << " has spacing " << setup.spacing << " m, the recording "
                  << info.spacing << " m (sph_run's --set overrides are not recorded): its container may differ from the run's\n";
      constants_ = setup.constants;
      // The camera frames the container as the live demo does: the grid's domain without its 2h band.
      const GridGeometry& g = constants_.grid;
      const float band = 2.0f * float(setup.h);
      lo_ = g.origin + Vec3{band, band, band};
      hi_ = g.origin + g.cell_size * Vec3{float(g.nx), float(g.ny), float(g.nz)} - Vec3{band, band, band};
      lines_.build(constants_, setup.meshes, lo_, hi_);
      note_ = "colours and container from " + scene_file.string();
      return;
    } catch (const std::exception& e) {
      note_ = "scene " + scene_file.string() + " not used (" + e.what() + "): rest density 1000 kg/m^3 for the colours";
      std::cerr << "sph_demo: " << note_ << "\n";
    }
    const float d = float(info.spacing);
    constants_ = SimConstants{};
    constants_.num_fluids = std::min<int32_t>(fluids, kMaxFluids);
    for (int32_t f = 0; f < constants_.num_fluids; ++f) {
      constants_.fluids[f].rest_density = 1000.0f;
      constants_.fluids[f].tait_b = 1000.0f * 20.0f * 20.0f / 7.0f;
    }
    constants_.grid.origin = lo_;
    constants_.grid.cell_size = d;
    constants_.grid.reach = 2;
    constants_.grid.nx = int32_t((hi_.x - lo_.x) / d) + 1;
    constants_.grid.ny = int32_t((hi_.y - lo_.y) / d) + 1;
    constants_.grid.nz = int32_t((hi_.z - lo_.z) / d) + 1;
    lines_.build(constants_, {}, lo_, hi_);
  }

  void show(std::size_t k, bool always = false) {
    if (k == index_ && !always && shown_colour_ >= 0) return;
    index_ = k;
    shown_colour_ = colour_;
    stale_ = true;
  }
  // Uploads the shown frame for this view: every particle, or, where --cull auto finds it gives the same
  // picture (kCullDiameterPixels), only the nearest of each pixel (occlusion_cull.h), culled again whenever
  // the frame, the colour, the view or the window's size changes. The surface needs every particle (its
  // thickness pass).
  void upload(const FrameView& f) {
    const ParticleState& ps = rec_.frames[index_].particles;
    const bool cull = opt_.cull == "auto" && !surface_ && !mesh_ && f.width > 0 && f.height > 0 &&
                      ps.size() > std::size_t(f.width) * std::size_t(f.height) / 4 &&
                      projected_diameter(f.projection, f.height, radius_, camera_.distance) <= kCullDiameterPixels;
    if (!cull) {
      if (stale_ || culled_) legend_ = particles_.upload(ps, constants_, ColourMode(colour_));
      stale_ = culled_ = false;
      return;
    }
    if (!stale_ && culled_ && f.view == cull_view_ && f.projection == cull_projection_ && f.width == cull_width_ &&
        f.height == cull_height_)
      return;
    front_particles(ps.pos, f.view, f.projection, f.width, f.height, cull_buffers_, front_);
    legend_ = particles_.upload(ps, constants_, ColourMode(colour_), &front_);
    cull_view_ = f.view;
    cull_projection_ = f.projection;
    cull_width_ = f.width;
    cull_height_ = f.height;
    stale_ = false;
    culled_ = true;
  }
  // The latest mesh at or before the shown frame's time (the first one before any).
  void show_mesh() {
    const double t = rec_.frames[index_].info.time + 1e-9;
    std::size_t k = 0;
    while (k + 1 < rec_.surfaces.size() && rec_.surfaces[k + 1].time <= t) ++k;
    if (k == shown_mesh_ && meshes_.triangles() > 0) return;
    shown_mesh_ = k;
    meshes_.upload(rec_.surfaces[k].mesh);
  }
  void step(int direction) {
    playing_ = false;
    const long k = std::clamp(long(index_) + direction, 0L, long(rec_.frames.size()) - 1);
    show(std::size_t(k));
    clock_ = rec_.frames[index_].info.time;
  }

  void panel() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::Begin("replay", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    const Frame& f = rec_.frames[index_];
    ImGui::Text("%s: scene %s", rec_.folder.c_str(), f.info.scene.c_str());
    ImGui::Text("frame index %zu (0 to %zu), t = %.4f s, %zu particles", index_, rec_.frames.size() - 1, f.info.time,
                f.particles.size());
    if (ImGui::Button(playing_ ? "pause (space)" : "play (space)")) playing_ = !playing_;
    ImGui::SameLine();
    if (ImGui::Button("< (B)")) step(-1);
    ImGui::SameLine();
    if (ImGui::Button("> (N)")) step(+1);
    ImGui::SameLine();
    ImGui::Checkbox("loop (L)", &loop_);
    int k = int(index_);
    if (ImGui::SliderInt("frame index", &k, 0, int(rec_.frames.size()) - 1)) {
      show(std::size_t(k));
      clock_ = rec_.frames[index_].info.time;
    }
    float speed = float(speed_);
    if (ImGui::SliderFloat("speed (+ -)", &speed, 1.0f / 64.0f, 64.0f, "%.3g x real time", ImGuiSliderFlags_Logarithmic))
      speed_ = speed;
    const char* names[] = {"fluid", "speed", "density error", "pressure", "grid cell"};
    ImGui::Combo("colour (C)", &colour_, names, int(ColourMode::Count));
    ImGui::Checkbox("flat points (V)", &flat_);
    surface_controls(surface_, look_);
    if (!rec_.surfaces.empty()) {
      ImGui::Checkbox("exported meshes (M)", &mesh_);
      if (mesh_) ImGui::Text("%s, t = %.4f s", rec_.surfaces[shown_mesh_].path.c_str(), rec_.surfaces[shown_mesh_].time);
    }
    if (!surface_ && legend_.unit && *legend_.unit) ImGui::Text("colour scale: %.3g to %.3g %s", legend_.lo, legend_.hi, legend_.unit);
    ImGui::Text("%.1f fps, drawing %.1f ms", fps_, draw_ms_);
    if (culled_) ImGui::Text("drawing the nearest %d of %zu particles (--cull)", int(particles_.count()),
                             rec_.frames[index_].particles.size());
    ImGui::TextWrapped("%s", note_.c_str());
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

  GLFWwindow* window_;
  DemoOptions opt_;
  const Recording& rec_;
  SimConstants constants_{};
  ParticleRenderer particles_;
  FluidSurfaceRenderer surface_renderer_;
  MeshRenderer meshes_;
  std::size_t shown_mesh_ = 0;
  SurfaceLook look_;
  SceneLines lines_;
  OrbitCamera camera_;
  ColourRange legend_{0.0f, 1.0f, ""};
  Vec3 lo_{}, hi_{};
  std::string note_;
  std::size_t index_ = 0;
  double clock_ = 0.0, speed_ = 1.0, fps_ = 0.0, draw_ms_ = 0.0, last_x_ = 0.0, last_y_ = 0.0;
  int colour_ = int(ColourMode::Speed), shown_colour_ = -1;
  bool stale_ = true, culled_ = false;  // the upload is not the shown frame's; it holds only the culled set
  CullBuffers cull_buffers_;
  std::vector<uint32_t> front_;
  Mat4 cull_view_{}, cull_projection_{};
  int cull_width_ = 0, cull_height_ = 0;
  float radius_ = 0.01f;
  bool playing_ = true, loop_ = true, flat_ = false, surface_ = false, mesh_ = false;
  long frames_ = 0;
};

void on_replay_key(GLFWwindow* w, int key, int, int action, int) {
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  static_cast<Replay*>(glfwGetWindowUserPointer(w))->key(key);
}
void on_replay_scroll(GLFWwindow* w, double, double dy) {
  if (ImGui::GetIO().WantCaptureMouse) return;
  static_cast<Replay*>(glfwGetWindowUserPointer(w))->scroll(dy);
}

}  // namespace

int run_replay(GLFWwindow* window, const DemoOptions& o, const Recording& recording) {
  Replay replay(window, o, recording);
  glfwSetWindowUserPointer(window, &replay);
  glfwSetKeyCallback(window, on_replay_key);
  glfwSetScrollCallback(window, on_replay_scroll);
  // Headless runs (--frames) advance the clock by 1/30 s a frame, so what they show does not depend on how
  // fast this machine draws; interactive ones by the wall clock.
  auto last = std::chrono::steady_clock::now();
  while (!glfwWindowShouldClose(window)) {
    if (replay.idle()) glfwWaitEventsTimeout(0.1);
    else glfwPollEvents();
    if (std::size_t(replay.frames()) < o.keys.size()) replay.key(glfw_key_of(o.keys[std::size_t(replay.frames())]));
    replay.mouse();
    const auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - last).count();
    last = now;
    replay.frame(o.frames > 0 ? 1.0 / 30.0 : wall, wall);
    if (o.frames > 0 && replay.frames() >= o.frames) {
      if (!o.screenshot.empty()) {
        int w = 0, h = 0;
        glfwGetFramebufferSize(window, &w, &h);
        write_screenshot(o.screenshot, w, h);
        std::cout << "screenshot: " << o.screenshot << "\n";
      }
      replay.summary();
      break;
    }
    glfwSwapBuffers(window);
  }
  return 0;
}

}  // namespace sph
