#include "simulation.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sph {

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::Predict: return "predict";
    case Phase::BuildGrid: return "build_grid";
    case Phase::Density: return "density";
    case Phase::Pressure: return "pressure";
    case Phase::Forces: return "forces";
    case Phase::Correct: return "correct";
    case Phase::Boundaries: return "boundaries";
    case Phase::Recycle: return "recycle";
    case Phase::Emit: return "emit";
    case Phase::Count: break;
  }
  return "?";
}

Simulation::Simulation(const Scene& scene, const BackendFactory& factory, double run_time, const Frame* restart)
    : scene_(scene), setup_(create_setup(scene, run_time)), backend_(factory(setup_.constants)) {
  if (restart) {
    continue_from(*restart);
  } else {
    if (scene_.relaxation.enabled) relax(factory);
    backend_->upload(setup_.particles);
    backend_->initialise_forces();
  }
  diag_ = backend_->diagnose();
}

// Thesis 4.1.6: steps that do not advance the simulated time, without gravity and with a large viscosity,
// until the largest speed (and the speed one step of the largest acceleration adds) stays below the
// threshold for three steps. The relaxed positions (and, for the
// continuity method, densities) become the initial state, at rest.
void Simulation::relax(const BackendFactory& factory) {
  const RelaxationSpec& spec = scene_.relaxation;
  SimConstants rc = setup_.constants;
  rc.gravity = Vec3{0.0f, 0.0f, 0.0f};
  rc.viscosity = ViscosityModel::Mueller;
  for (int32_t f = 0; f < rc.num_fluids; ++f) {
    FluidConstants& fc = rc.fluids[f];
    const double mu = spec.viscosity > 0.0 ? spec.viscosity : fc.rest_density * 0.03 * setup_.h * fc.speed_of_sound;
    fc.viscosity = float(mu);
  }
  const double rate = viscous_rate(rc, setup_.spacing, setup_.h, setup_.lattice_density);
  relaxation_.ran = true;
  relaxation_.threshold = spec.speed_threshold > 0.0 ? spec.speed_threshold : 1e-3 * setup_.max_speed_of_sound;
  std::unique_ptr<Backend> relaxing = factory(rc);
  relaxing->upload(setup_.particles);
  relaxing->initialise_forces();
  Diagnostics d = relaxing->diagnose();
  TimeStepSpec ts = scene_.time_step;
  int quiet = 0;
  while (relaxation_.steps < spec.max_steps) {
    const StepChoice choice = choose_time_step(ts, setup_.h, setup_.max_speed_of_sound, rate, d.max_speed, d.max_accel);
    relaxing->step(float(choice.dt));
    ++relaxation_.steps;
    d = relaxing->diagnose();
    if (d.non_finite >= 0) throw BlowUp(scene_.source + ": the relaxation phase became unstable after " +
                                        std::to_string(relaxation_.steps) + " steps; lower relaxation.viscosity or the time step");
    // At rest means slow and in balance: a lattice released from rest is slow at first, but its
    // unbalanced forces (a dt) would soon make it fast.
    relaxation_.final_speed = std::max(double(d.max_speed), double(d.max_accel) * choice.dt);
    quiet = relaxation_.final_speed < relaxation_.threshold ? quiet + 1 : 0;
    if (quiet >= 3) {
      relaxation_.converged = true;
      break;
    }
  }
  ParticleState relaxed = relaxing->download();
  for (std::size_t i = 0; i < relaxed.size(); ++i) {
    relaxed.vel[i] = relaxed.vel_force[i] = relaxed.acc[i] = Vec3{0.0f, 0.0f, 0.0f};
  }
  setup_.particles = std::move(relaxed);
}

void Simulation::set_constants(const SimConstants& constants) {
  setup_.constants = constants;
  double c_max = 0.0;
  for (int32_t f = 0; f < constants.num_fluids; ++f)
    c_max = std::max(c_max, double(constants.fluids[f].speed_of_sound));
  setup_.max_speed_of_sound = c_max;
  setup_.viscous_rate = viscous_rate(constants, setup_.spacing, setup_.h, setup_.lattice_density);
  backend_->set_constants(constants);
}

void Simulation::switch_backend(const BackendFactory& factory) {
  const ParticleState state = backend_->download();
  std::unique_ptr<Backend> next = factory(setup_.constants);
  next->upload(state);
  next->initialise_forces();
  backend_ = std::move(next);
  diag_ = backend_->diagnose();
}

void Simulation::advance() {
  const StepChoice choice = choose_time_step(scene_.time_step, setup_.h, setup_.max_speed_of_sound,
                                             setup_.viscous_rate, diag_.max_speed, diag_.max_accel);
  const double dt = choice.dt;
  backend_->step(float(dt));
  for (JetEmitter& jet : setup_.jets) {
    if (emission_stopped_) break;
    std::vector<Spawn> spawns = jet.advance(time_, dt, setup_.next_id);
    if (spawns.empty()) continue;
    if (double(backend_->size() + spawns.size()) > scene_.max_particles) {
      if (stop_emission_at_limit_) {
        emission_stopped_ = true;
        break;
      }
      std::ostringstream os;
      os << scene_.source << ": at t = " << time_ << " s the jets would exceed limits.max_particles = "
         << std::llround(scene_.max_particles) << "; give the jets a lifetime or raise the limit";
      throw SceneError(os.str());
    }
    backend_->emit(spawns);
  }
  time_ += dt;
  ++steps_;
  last_dt_ = dt;
  last_limit_ = choice.limit;

  diag_ = backend_->diagnose();
  const bool nan = diag_.non_finite >= 0;
  if (nan || !(diag_.max_speed <= setup_.blowup_speed)) {
    const ParticleState& ps = backend_->download();
    const int32_t i = nan ? diag_.non_finite : diag_.fastest;
    std::ostringstream os;
    os << "simulation became unstable at t = " << time_ << " s (step " << steps_ << ", dt = " << dt << " s): particle id "
       << (i >= 0 ? ps.id[std::size_t(i)] : -1);
    if (i >= 0) {
      const Vec3 x = ps.pos[std::size_t(i)], v = ps.vel[std::size_t(i)];
      os << " at (" << x.x << ", " << x.y << ", " << x.z << ") has "
         << (nan ? "a non-finite position or velocity" : "speed " + std::to_string(length(v)) + " m/s") << "";
    }
    if (!nan) os << ", above the blow-up bound " << setup_.blowup_speed << " m/s";
    os << ". Try a smaller time step (time_step.dt, time_step.max or the CFL factors), a stabler integrator "
          "(modified_velocity_verlet), or more viscosity.";
    throw BlowUp(os.str());
  }
}

}  // namespace sph
