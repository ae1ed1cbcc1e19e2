// The driver shared by the runner, the tests, the benchmark and the demo: guided creation, time step
// choice, emission, and the blow-up check around a back end's step().
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "backend.h"
#include "frame_reader.h"
#include "guided_creation.h"
#include "scene.h"
#include "time_step.h"

namespace sph {

// The simulation became unstable: NaN, or a speed above the blow-up bound. The message names the time,
// the step and the particle, and suggests what to change.
struct BlowUp : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What the relaxation phase did (thesis 4.1.6), for the runner's report.
struct RelaxationReport {
  bool ran = false;
  bool converged = false;
  long steps = 0;
  double final_speed = 0.0;
  double threshold = 0.0;
};

class Simulation {
 public:
  // restart: a frame of an earlier run of this scene (frame_reader.h) to continue from, bit for bit: its
  // particles (with their accelerations), time, step, next id and jet accumulators replace the start-up
  // state; no relaxation, no initialise_forces. Throws SceneError when the frame does not fit the scene.
  Simulation(const Scene& scene, const BackendFactory& factory, double run_time, const Frame* restart = nullptr);

  // One time step; throws BlowUp when the state has become unphysical.
  void advance();

  double time() const { return time_; }
  long steps() const { return steps_; }
  double last_dt() const { return last_dt_; }
  StepLimit last_limit() const { return last_limit_; }
  const Setup& setup() const { return setup_; }
  const Scene& scene() const { return scene_; }
  const RelaxationReport& relaxation() const { return relaxation_; }
  TimeStepSpec& time_step() { return scene_.time_step; }  // live edits (the demo)
  Backend& backend() { return *backend_; }
  const ParticleState& particles() { return backend_->download(); }

  // Live changes between steps (the demo): new constants (same grid), or a new back end that carries on
  // from the current state.
  void set_constants(const SimConstants& constants);
  void switch_backend(const BackendFactory& factory);

  // The header of a frame of the current state (write_ply_frame), numbered frame_index.
  FrameInfo frame_info(int frame_index) const;

  // A run without an end (the demo): when the jets would exceed limits.max_particles, emission stops and
  // emission_stopped() says so, instead of the SceneError a run of fixed length gets.
  void stop_emission_at_limit(bool on) { stop_emission_at_limit_ = on; }
  bool emission_stopped() const { return emission_stopped_; }

 private:
  Scene scene_;
  Setup setup_;
  std::unique_ptr<Backend> backend_;
  Diagnostics diag_;
  RelaxationReport relaxation_;

  void relax(const BackendFactory& factory);
  void continue_from(const Frame& frame);  // simulation_restart.cpp
  double time_ = 0.0;
  long steps_ = 0;
  double last_dt_ = 0.0;
  StepLimit last_limit_ = StepLimit::Fixed;
  bool stop_emission_at_limit_ = false, emission_stopped_ = false;
};

}  // namespace sph
