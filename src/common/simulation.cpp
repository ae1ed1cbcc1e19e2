#include "simulation.h"

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

Simulation::Simulation(const Scene& scene, const BackendFactory& factory, double run_time)
    : scene_(scene), setup_(create_setup(scene, run_time)), backend_(factory(setup_.constants)) {
  backend_->upload(setup_.particles);
  backend_->initialise_forces();
  diag_ = backend_->diagnose();
}

void Simulation::advance() {
  const StepChoice choice = choose_time_step(scene_.time_step, setup_.h, setup_.max_speed_of_sound,
                                             setup_.max_kinematic_viscosity, diag_.max_speed, diag_.max_accel);
  const double dt = choice.dt;
  backend_->step(float(dt));
  for (JetEmitter& jet : setup_.jets) {
    std::vector<Spawn> spawns = jet.advance(time_, dt, setup_.next_id);
    if (spawns.empty()) continue;
    if (double(backend_->size() + spawns.size()) > scene_.max_particles) {
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
