// sph_demo: the interactive demo. Runs a scene in real time on a back end and draws it with OpenGL; a
// Dear ImGui panel shows live statistics and edits parameters. With --frames N --screenshot FILE it renders
// N frames without input, writes a PNG and exits (headless runs under xvfb-run).
#include <GL/glew.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "../common/metrics.h"
#include "../common/simulation.h"
#include "../render/camera.h"
#include "../render/fluid_surface.h"
#include "../render/particle_renderer.h"
#include "../render/scene_lines.h"
#include "../render/screenshot.h"
#include "../render/ui_panel.h"
#include "backends.h"
#include "demo_controls.h"
#include "demo_options.h"
#include "demo_window.h"
#include "demo_replay.h"
#include "demo_scenes.h"

using namespace sph;
using namespace sph::render;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

class Demo {
 public:
  // Throws when the command line's scene cannot be loaded (main reports it, exit 1); later scene changes
  // never end the program.
  Demo(GLFWwindow* window, const DemoOptions& o) : window_(window), opt_(o), scenes_(o.scene, o.sets) {
    backends_ = available_backends();
    backend_ = o.backend;
    const char* modes[] = {"fluid", "speed", "density_error", "pressure", "cell"};
    for (int i = 0; i < int(ColourMode::Count); ++i)
      if (o.colour == modes[i]) panel_.colour_mode = i;
    start(0, load(0));
    if (o.substeps > 0) panel_.substeps = o.substeps;
    panel_.surface = o.render == "surface";
  }
  // The back end unregisters the vertex buffers (interop) before particles_ deletes them.
  ~Demo() { sim_.reset(); }

  // R: the current scene again, with the command line's overrides. [ and ]: the previous or next scene
  // that loads; the others are skipped with a message (stderr and panel), and the current scene stays
  // when none does.
  void reset() { change_scene(0); }
  void change_scene(int direction) {
    for (int k = direction == 0 ? 0 : 1; k <= (direction == 0 ? 0 : scenes_.size() - 1); ++k) {
      const int index = scenes_.wrap(scene_index_ + direction * k);
      try {
        start(index, load(index));
        return;
      } catch (const std::exception& e) {
        note(std::string("skipped: ") + e.what());
      }
    }
  }

  // Simulation messages once a frame: jets that stopped at the particle limit.
  void check_emission() {
    if (sim_->emission_stopped() && !emission_note_) {
      emission_note_ = true;
      note("emission stopped at t = " + std::to_string(sim_->time()) + " s: the jets would exceed limits.max_particles = " +
           std::to_string(std::llround(sim_->scene().max_particles)) + " (give the jets a lifetime or raise limits.max_particles in the scene)");
    }
  }

 private:
  std::unique_ptr<Simulation> load(int index) {
    return scenes_.load(index, backend_factory(backend_), [this](const std::string& text) { note(text); });
  }

  void start(int index, std::unique_ptr<Simulation> sim) {
    scene_index_ = index;
    sim_ = std::move(sim);
    interop_off_ = false;
    panel_.wall_particles = long(sim_->setup().boundary.size());
    walls_eye_ = Vec3{0.0f, 0.0f, 0.0f};
    emission_note_ = false;
    const Scene& scene = sim_->scene();
    base_ = sim_->setup().constants;
    tilt_x_ = tilt_z_ = 0.0f;
    const FluidConstants& f = base_.fluids[0];
    panel_.viscosity = f.viscosity;
    panel_.speed_of_sound = f.speed_of_sound;
    panel_.near_stiffness = f.near_stiffness;
    panel_.dt_max = float(scene.time_step.mode == TimeStepMode::Fixed ? scene.time_step.dt : scene.time_step.max);
    panel_.scene = scene.name;
    panel_.integrator = scene.solver == Solver::Wcsph ? integrator_name(scene.integrator)
                                                      : std::string("solver ") + solver_name(scene.solver);
    // A frame shows about 1/60 s of simulated time when the back end keeps up.
    panel_.substeps = std::clamp(int(std::ceil((1.0 / 60.0) / std::max(1e-5, double(panel_.dt_max)))), 1, 16);
    // Camera and floor: the grid's domain without its 2h band, or the container.
    const GridGeometry& g = base_.grid;
    const float band = 2.0f * float(sim_->setup().h);
    lo_ = g.origin + Vec3{band, band, band};
    hi_ = g.origin + g.cell_size * Vec3{float(g.nx), float(g.ny), float(g.nz)} - Vec3{band, band, band};
    camera_.frame(lo_, hi_);
    camera_.yaw = 0.0f;
    camera_.pitch = 0.35f;
    lines_.build(base_, sim_->setup().meshes, lo_, hi_);
    lines_.set_bodies(sim_->backend().bodies());
    radius_ = 0.5f * float(sim_->setup().spacing);
    panel_.setup_report = sim_->setup().report;
    panel_.setup_changed = sim_->setup().adjusted;
  }

  // A message for the user: on stderr, and in the panel (the last few).
  void note(const std::string& text) {
    std::cerr << "sph_demo: " << text << "\n";
    panel_.messages.push_back(text);
    if (panel_.messages.size() > 4) panel_.messages.erase(panel_.messages.begin());
  }

 public:
  // One frame: input, simulation substeps within the budget, upload, draw, panel.
  void frame() {
    const auto t0 = Clock::now();
    process_held_input();
    const double sim_t0 = sim_->time();
    const auto s0 = Clock::now();
    const PhaseTimes before = sim_->backend().phase_times();
    if (!panel_.paused || single_step_) {
      const int n = single_step_ ? 1 : panel_.substeps;
      for (int i = 0; i < n; ++i) {
        sim_->advance();
        if (!single_step_ && ms_since(s0) > opt_.budget_ms) break;  // frame budget: stay interactive
      }
      single_step_ = false;
      check_emission();
    }
    panel_.sim_ms = ms_since(s0);
    const PhaseTimes& after = sim_->backend().phase_times();
    const long steps = after.steps - before.steps;
    if (steps > 0)
      for (std::size_t p = 0; p < after.seconds.size(); ++p)
        panel_.phase_per_step.seconds[p] = 1e3 * (after.seconds[p] - before.seconds[p]) / double(steps);

    const auto d0 = Clock::now();
    const bool interop = write_by_interop();
    if (!interop || frames_ % 30 == 0) stats_ = sim_->particles();  // with interop: statistics now and then
    if (!interop) panel_.legend = particles_.upload(stats_, sim_->setup().constants, ColourMode(panel_.colour_mode));
    const ParticleState& ps = stats_;
    const FrameView f = begin_frame(window_, camera_);
    if (!sim_->backend().bodies().empty()) lines_.set_bodies(sim_->backend().bodies());
    lines_.draw(f.view, f.projection);
    if (panel_.show_walls && panel_.wall_particles > 0) {
      upload_walls();
      walls_.draw(f.view, f.projection, radius_, f.height, panel_.flat_points);
    }
    if (panel_.surface)
      surface_.draw(particles_, f.view, f.projection, radius_, camera_.distance, lo_, hi_, f.width, f.height, panel_.look,
                    f.background());
    else particles_.draw(f.view, f.projection, radius_, f.height, panel_.flat_points);
    draw_ui(ps);
    glFinish();  // the drawing time is the renderer's, not only the commands' submission
    panel_.draw_ms = ms_since(d0);

    // Frames per second from one frame's start to the next, so waiting (paused) and swapping count too.
    const double frame_ms = frames_ > 0 ? std::chrono::duration<double, std::milli>(t0 - last_frame_start_).count() : ms_since(t0);
    last_frame_start_ = t0;
    fps_ = frames_ > 0 ? 0.9 * fps_ + 0.1 * (1e3 / std::max(frame_ms, 1e-3)) : 1e3 / std::max(frame_ms, 1e-3);
    panel_.fps = fps_;
    panel_.realtime_ratio = (sim_->time() - sim_t0) / (frame_ms * 1e-3);
    ++frames_;
  }

  // The walls' boundary particles whose surface faces the camera (its normal towards the fluid points at
  // the eye): the back walls, the floor and the near sides of obstacles, not the walls in front of the
  // fluid. Uploaded again when the camera has moved.
  void upload_walls() {
    const Vec3 eye = camera_.eye();
    if (length(eye - walls_eye_) < 1e-6f) return;
    walls_eye_ = eye;
    const BoundaryParticles& walls = sim_->setup().boundary;
    wall_points_.clear();
    for (std::size_t i = 0; i < walls.size(); ++i) {
      const Vec3 x = xyz(walls.pos_volume[i]);
      if (dot(xyz(walls.normal_depth[i]), eye - x) > 0.0f) wall_points_.push_back(x);
    }
    walls_.upload_points(wall_points_, Vec3{0.55f, 0.55f, 0.58f});
  }

  // D: a box of density 500 kg/m^3, 6 spacings wide, dropped from the upper part of the domain, in turn left
  // of, at and right of its middle (a rigid body: it floats; bodies do not touch each other yet).
  void drop_box() {
    const float side = 6.0f * float(sim_->setup().spacing), mid_z = 0.5f * (lo_.z + hi_.z);
    const float mid_x = 0.5f * (lo_.x + hi_.x) + float(drops_++ % 3 - 1) * 0.25f * (hi_.x - lo_.x);
    const float top = hi_.y - 0.5f * side;
    BodySpec b;
    b.min = {mid_x - 0.5 * side, top - side, mid_z - 0.5 * side};
    b.max = {mid_x + 0.5 * side, top, mid_z + 0.5 * side};
    b.density = 500.0;
    const std::string why = sim_->add_body(b);
    note(why.empty() ? "dropped a box of density 500 kg/m^3" : "no box dropped: " + why);
  }

  // Keys that act once per press.
  void key(int k, int mods) {
    switch (k) {
      case GLFW_KEY_SPACE: panel_.paused = !panel_.paused; break;
      case GLFW_KEY_N: single_step_ = true; break;
      case GLFW_KEY_R: reset(); break;
      case GLFW_KEY_RIGHT_BRACKET: change_scene(+1); break;
      case GLFW_KEY_LEFT_BRACKET: change_scene(-1); break;
      case GLFW_KEY_B: next_backend(); break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD: panel_.substeps = std::min(64, panel_.substeps * 2); break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT: panel_.substeps = std::max(1, panel_.substeps / 2); break;
      case GLFW_KEY_C: panel_.colour_mode = (panel_.colour_mode + 1) % int(ColourMode::Count); break;
      case GLFW_KEY_V: panel_.flat_points = !panel_.flat_points; break;
      case GLFW_KEY_S: panel_.surface = !panel_.surface; break;
      case GLFW_KEY_G: panel_.show_walls = !panel_.show_walls; break;
      case GLFW_KEY_D: drop_box(); break;
      case GLFW_KEY_P: screenshot_requested_ = true; break;
      case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, 1); break;
      default: break;
    }
    (void)mods;
  }

  void scroll(double dy) { camera_.zoom(std::pow(0.9f, float(dy))); }

  void write_screenshot_now(const std::string& path) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    write_screenshot(path, w, h);
    std::cout << "screenshot: " << path << "\n";
  }
  bool take_screenshot_request() {
    const bool r = screenshot_requested_;
    screenshot_requested_ = false;
    return r;
  }
  long frames() const { return frames_; }
  // Paused without a pending single step: nothing moves until an input event.
  bool idle() const { return panel_.paused && !single_step_; }
  const PanelModel& panel() const { return panel_; }
  Simulation& simulation() { return *sim_; }

 private:
  void next_backend() {
    for (std::size_t i = 1; i <= backends_.size(); ++i) {
      const std::string& candidate = backends_[(index_of(backend_) + i) % backends_.size()];
      try {
        sim_->switch_backend(backend_factory(candidate));  // the state carries over
        backend_ = candidate;
        interop_off_ = false;
        return;
      } catch (const std::exception& e) {
        note("back end " + candidate + " skipped: " + e.what());
      }
    }
  }
  std::size_t index_of(const std::string& b) const {
    for (std::size_t i = 0; i < backends_.size(); ++i)
      if (backends_[i] == b) return i;
    return 0;
  }

  // Held keys and mouse: gravity tilt, sideways push, camera, mouse force.
  void process_held_input() {
    const bool ui_mouse = ImGui::GetIO().WantCaptureMouse;
    const float step = 0.02f;
    if (glfwGetKey(window_, GLFW_KEY_LEFT) == GLFW_PRESS) tilt_z_ = std::min(tilt_z_ + step, 0.8f);
    if (glfwGetKey(window_, GLFW_KEY_RIGHT) == GLFW_PRESS) tilt_z_ = std::max(tilt_z_ - step, -0.8f);
    if (glfwGetKey(window_, GLFW_KEY_UP) == GLFW_PRESS) tilt_x_ = std::min(tilt_x_ + step, 0.8f);
    if (glfwGetKey(window_, GLFW_KEY_DOWN) == GLFW_PRESS) tilt_x_ = std::max(tilt_x_ - step, -0.8f);
    float push = 0.0f;  // seed 000, section 5: push the water sideways
    if (glfwGetKey(window_, GLFW_KEY_J) == GLFW_PRESS) push -= 1.0f;
    if (glfwGetKey(window_, GLFW_KEY_L) == GLFW_PRESS) push += 1.0f;

    double mx = 0.0, my = 0.0;
    glfwGetCursorPos(window_, &mx, &my);
    const float dx = float(mx - last_x_), dy = float(my - last_y_);
    last_x_ = mx;
    last_y_ = my;
    const bool ctrl = glfwGetKey(window_, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                      glfwGetKey(window_, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && !ui_mouse;
    const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS && !ui_mouse;
    SimConstants c = base_;
    apply_panel(panel_, base_, c, sim_->time_step());
    const float g = length(base_.gravity);
    const Vec3 gr = tilted_gravity(base_.gravity, tilt_x_, tilt_z_);
    c.gravity = gr + Vec3{push * 0.5f * std::max(g, 9.81f), 0.0f, 0.0f};
    c.user_force.strength = 0.0f;
    if (ctrl && (left || right)) {
      int w = 0, h = 0;
      glfwGetWindowSize(window_, &w, &h);
      c.user_force.point = cursor_point(camera_, w, h, mx, my);
      c.user_force.radius = 0.15f * length(hi_ - lo_);
      c.user_force.strength = (left ? 3.0f : -3.0f) * std::max(g, 9.81f);
    } else if (left) {
      camera_.orbit(0.005f * dx, 0.005f * dy);
    } else if (right) {
      int w = 0, h = 0;
      glfwGetWindowSize(window_, &w, &h);
      camera_.pan(dx / float(std::max(h, 1)), dy / float(std::max(h, 1)));
    }
    sim_->set_constants(c);
  }

  // CUDA back end: the kernels write the VBOs through CUDA-OpenGL interop, no copy through the host. Where
  // the back end cannot (no interop, or the OpenGL context is not on its GPU) the demo says why once and
  // uploads from the host until the back end changes.
  bool write_by_interop() {
    Backend& b = sim_->backend();
    if (interop_off_) return false;
    const ColourMode mode = ColourMode(panel_.colour_mode);
    if (!particles_.fits(b.size())) b.release_gl_buffers();  // unregistered before glBufferData reallocates
    particles_.reserve(b.size());
    GlBuffers req;
    req.position_vbo = particles_.position_vbo();
    req.colour_vbo = particles_.colour_vbo();
    req.capacity = particles_.capacity();
    req.generation = particles_.generation();
    ColourRange range{0.0f, 1.0f, ""};
    if (mode == ColourMode::Speed) range = {0.0f, std::max(b.diagnose().max_speed, 1e-6f), "m/s"};
    if (mode == ColourMode::DensityError) range = {-5.0f, 5.0f, "% of rho0"};
    if (mode == ColourMode::Pressure) range = {0.0f, 0.05f * sim_->setup().constants.fluids[0].tait_b, "Pa"};
    req.colouring = RenderColouring{int(mode), range.lo, range.hi};
    std::string why;
    if (!b.write_gl_buffers(req, why)) {
      interop_off_ = true;
      if (!why.empty()) note("interop off, drawing through host memory: " + why);
      return false;
    }
    particles_.set_count(b.size());
    panel_.legend = range;
    return true;
  }

  void draw_ui(const ParticleState& ps) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    panel_.backend = backend_;
    panel_.backends = backends_;
    panel_.particles = long(ps.size());
    panel_.sim_time = sim_->time();
    panel_.dt = sim_->last_dt();
    panel_.density_error = measure(sim_->setup().constants, ps).density_error_mean;
    if (sim_->scene().solver != Solver::Wcsph) {
      panel_.solver_iterations = sim_->solver_stats().density_iterations;
      panel_.solver_error = sim_->solver_stats().density_error;
    }
    draw_panel(panel_);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

  GLFWwindow* window_;
  DemoOptions opt_;
  DemoScenes scenes_;
  std::vector<std::string> backends_;
  std::string backend_;
  int scene_index_ = 0;
  std::unique_ptr<Simulation> sim_;
  ParticleState stats_;  // last downloaded state (every frame, or every 30th with interop)
  SimConstants base_{};
  ParticleRenderer particles_;
  FluidSurfaceRenderer surface_;  // the screen-space surface (S), drawn from particles_' buffers
  ParticleRenderer walls_;  // the walls' boundary particles (G)
  std::vector<Vec3> wall_points_;
  int drops_ = 0;  // boxes dropped with D
  Vec3 walls_eye_{0.0f, 0.0f, 0.0f};  // the camera's eye when walls_ was last uploaded
  SceneLines lines_;
  OrbitCamera camera_;
  PanelModel panel_;
  Vec3 lo_{}, hi_{};
  float radius_ = 0.01f;
  float tilt_x_ = 0.0f, tilt_z_ = 0.0f;
  double last_x_ = 0.0, last_y_ = 0.0, fps_ = 0.0;
  Clock::time_point last_frame_start_{};
  bool single_step_ = false, screenshot_requested_ = false, emission_note_ = false, interop_off_ = false;
  long frames_ = 0;
};

void on_key(GLFWwindow* w, int key, int, int action, int mods) {
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  static_cast<Demo*>(glfwGetWindowUserPointer(w))->key(key, mods);
}
void on_scroll(GLFWwindow* w, double, double dy) {
  if (ImGui::GetIO().WantCaptureMouse) return;
  static_cast<Demo*>(glfwGetWindowUserPointer(w))->scroll(dy);
}

// The window, OpenGL and Dear ImGui, then the live demo, or the replay of `recording` when there is one.
int run(const DemoOptions& o, const Recording* recording) {
  GLFWwindow* window = open_demo_window(o);
  if (!window) return 2;
  int status = 0;
  try {
    if (recording) {
      status = run_replay(window, o, *recording);
    } else {
    Demo demo(window, o);
    glfwSetWindowUserPointer(window, &demo);
    glfwSetKeyCallback(window, on_key);
    glfwSetScrollCallback(window, on_scroll);
    double report_at = 2.0;
    const auto start = Clock::now();
    while (!glfwWindowShouldClose(window)) {
      // Paused, the demo sleeps until an input event (or 0.1 s) instead of redrawing as fast as it can.
      if (demo.idle()) glfwWaitEventsTimeout(0.1);
      else glfwPollEvents();
      if (std::size_t(demo.frames()) < o.keys.size()) demo.key(glfw_key_of(o.keys[std::size_t(demo.frames())]), 0);
      demo.frame();
      if (o.frames > 0 && demo.frames() >= o.frames) {
        if (!o.screenshot.empty()) demo.write_screenshot_now(o.screenshot);
        const PanelModel& m = demo.panel();
        std::cout << "scene: " << m.scene << "\nframes: " << demo.frames() << "\nparticles: " << m.particles << "\nfps: " << m.fps
                  << "\nsim_ms_per_frame: " << m.sim_ms << "\ndraw_ms_per_frame: " << m.draw_ms
                  << "\nsimulated_time: " << demo.simulation().time() << "\n";
        break;
      }
      if (demo.take_screenshot_request()) {
        char name[64];
        std::snprintf(name, sizeof name, "sph_screenshot_%05ld.png", demo.frames());
        demo.write_screenshot_now(name);
      }
      glfwSwapBuffers(window);
      if (o.frames == 0 && std::chrono::duration<double>(Clock::now() - start).count() > report_at) {
        report_at += 2.0;
        const PanelModel& m = demo.panel();
        std::printf("\r  %.1f fps  sim %.1f ms  draw %.1f ms  t = %.3f s  ", m.fps, m.sim_ms, m.draw_ms, m.sim_time);
        std::fflush(stdout);
      }
    }
    }
  } catch (const BlowUp& e) {  // exit statuses as sph_run: 3 unstable, 1 bad input (a scene's limits)
    std::cerr << "\nerror: " << e.what() << "\n";
    status = 3;
  } catch (const std::exception& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    status = 1;
  }
  close_demo_window(window);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  DemoOptions o;
  if (const int status = parse_demo_options(argc, argv, o); status >= 0) return status;
  try {
    if (o.render == "mesh" && o.replay.empty()) {
      std::cerr << "error: --render mesh draws a recording's surface meshes: it goes with --replay DIR\n";
      return 1;
    }
    if (!o.replay.empty()) {  // a recording that cannot be played is refused before any window opens
      if (!o.sets.empty()) std::cerr << "sph_demo: --set is ignored with --replay (the frames are what was simulated)\n";
      const Recording recording = load_recording(o.replay);
      return run(o, &recording);
    }
    // A bad scene or back end: a clear message before any window opens, the set-up's checks included (a
    // setting the solver cannot hold, a resolution beyond the particle budget).
    const Scene scene = load_scene(o.scene, o.sets);
    (void)create_setup(scene, scene.run_time);
    (void)backend_factory(o.backend);
    return run(o, nullptr);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
