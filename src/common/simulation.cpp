#include "simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "cohesion_energy.h"
#include "equation_of_state.h"
#include "metrics.h"
#include "rigid_body_setup.h"
#include "setup_budget.h"

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
    case Phase::DensitySolve: return "density_solve";
    case Phase::DivergenceSolve: return "divergence_solve";
    case Phase::ConstraintSolve: return "constraint_solve";
    case Phase::Emit: return "emit";
    case Phase::Count: break;
  }
  return "?";
}

void SolverTotals::add(const SolverStats& s) {
  ++steps;
  density_iterations += s.density_iterations;
  divergence_iterations += s.divergence_iterations;
  max_density_iterations = std::max(max_density_iterations, s.density_iterations);
  max_divergence_iterations = std::max(max_divergence_iterations, s.divergence_iterations);
  density_capped_steps += s.density_capped ? 1 : 0;
  divergence_capped_steps += s.divergence_capped ? 1 : 0;
  max_density_error = std::max(max_density_error, s.density_error);
  substepped_steps += s.viscous_substeps > 1 ? 1 : 0;
  max_viscous_substeps = std::max(max_viscous_substeps, s.viscous_substeps);
  coarse_iterations += s.coarse_iterations;
  max_coarse_iterations = std::max(max_coarse_iterations, s.coarse_iterations);
  coarse_capped_steps += s.coarse_capped ? 1 : 0;
}

Simulation::Simulation(const Scene& scene, const BackendFactory& factory, double run_time, const Frame* restart)
    : scene_(scene), setup_(create_setup(scene, run_time)), backend_(factory(setup_.constants)) {
  backend_->set_boundary(setup_.boundary);
  backend_->set_bodies(setup_.bodies);
  backend_->set_springs(setup_.springs);
  if (restart) {
    continue_from(*restart);
  } else {
    if (scene_.relaxation.enabled) relax(factory);
    backend_->upload(setup_.particles);
    backend_->initialise_forces();
  }
  diag_ = backend_->diagnose();
  if (!restart) rebase_energy(backend_->download());  // with its densities; the jets' prefilled inlets too
}

void Simulation::add_energy(Vec3 x, Vec3 v, int32_t fluid, double internal) {
  const double m = setup_.constants.fluids[fluid].mass;
  const double e =
      0.5 * (double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z) + specific_potential(setup_.constants, x) + internal;
  energy_in_ += m * e;
  mass_in_ += m;
  max_specific_in_ = std::max(max_specific_in_, e);
  if (!floor_bounded_) potential_reference_ = std::min(potential_reference_, specific_potential(setup_.constants, x));
}

void Simulation::rebase_energy(const ParticleState& ps) {
  const SimConstants& c = setup_.constants;
  const PotentialFloor floor = lowest_reachable_potential(c);
  floor_bounded_ = floor.bounded;
  potential_reference_ = floor.level;
  if (!floor_bounded_) {  // nothing holds the fluid against gravity: start from the grid's lowest corner
    const GridGeometry& gg = c.grid;
    const Vec3 size{gg.cell_size * float(gg.nx), gg.cell_size * float(gg.ny), gg.cell_size * float(gg.nz)};
    potential_reference_ = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 x = gg.origin + Vec3{corner & 1 ? size.x : 0.0f, corner & 2 ? size.y : 0.0f, corner & 4 ? size.z : 0.0f};
      potential_reference_ = std::min(potential_reference_, specific_potential(c, x));
    }
  }
  energy_in_ = mass_in_ = 0.0;
  max_specific_in_ = -std::numeric_limits<double>::infinity();
  // Surface tension's share: the surface energy the cohesion can release (cohesion_energy.h); under the
  // continuum surface force with no solid about the fluid, sigma times the start's area less the ball's
  // sigma A it cannot go below (a cube of water at sigma = 1000 N/m gained 16 J in 10 steps where it can
  // release 11.7 J, then flew apart with the budget's margin still unspent: docs/results.md).
  const std::optional<double> least = least_surface_energy(scene_, c, ps);
  const std::vector<double> surface =
      least ? lattice_surface_energy(scene_, c, ps, setup_.spacing) : cohesion_excess_energy(c, ps, setup_.spacing);
  // The adhesion's share: what a particle releases by reaching a wall, under either model (cohesion_energy.h).
  double adhesion[kMaxFluids] = {};
  for (int32_t k = 0; k < c.num_fluids; ++k) {
    const FluidConstants& f = c.fluids[k];
    const FluidSpec& spec = scene_.fluids[std::size_t(k)];
    if (f.adhesion > 0.0f)
      adhesion[k] = adhesion_first_layer_energy(f.adhesion, f.mass, setup_.spacing, c.kernel.h);
    else if (f.csf_contact)
      adhesion[k] = csf_contact_energy(spec.surface_tension, spec.contact_angle, setup_.spacing, f.mass);
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.age[i] >= kRemovedAge) continue;
    const FluidConstants& f = c.fluids[ps.fluid[i]];
    const double u = specific_internal_energy(c, f, ps.density[i]) + surface[i] + adhesion[ps.fluid[i]] +
                     (c.near_enabled ? near_internal_energy(f, ps.near_density[i], ps.density[i]) : 0.0);
    add_energy(ps.pos[i], ps.vel[i], ps.fluid[i], u);
  }
  surface_in_ = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.age[i] < kRemovedAge) surface_in_ += double(c.fluids[ps.fluid[i]].mass) * surface[i];
  if (least) {
    const double never = std::min(*least, surface_in_);
    energy_in_ -= never;
    surface_in_ -= never;
  }
}

double Simulation::energy_floor() const {
  const double c0 = setup_.max_speed_of_sound;
  return 0.5 * mass_in_ * (0.01 * c0) * (0.01 * c0);
}

double Simulation::speed_bound() const {
  if (scene_.blowup_speed > 0.0) return scene_.blowup_speed;
  if (!energy_check_active()) return setup_.blowup_speed;  // the user force does work: 10 c0 (guided creation)
  const double e_max = std::max(0.0, max_specific_in_ - potential_reference_);
  return std::max(setup_.max_speed_of_sound, 2.0 * std::sqrt(e_max));
}

// Thesis 4.1.6: steps that do not advance the simulated time, without gravity and with a large viscosity,
// until the largest speed (and the speed one step of the largest acceleration adds) stays below the
// threshold for three steps. The relaxed positions (and, for the
// continuity method, densities) become the initial state, at rest.
void Simulation::relax(const BackendFactory& factory) {
  const RelaxationSpec& spec = scene_.relaxation;
  SimConstants rc = setup_.constants;
  rc.solver = Solver::Wcsph;  // the thesis's procedure, whatever solver the run then uses
  rc.mirror_walls = scene_.mirror_walls;
  rc.gravity = Vec3{0.0f, 0.0f, 0.0f};
  rc.viscosity = ViscosityModel::Mueller;
  // Negative pressure is kept while relaxing: without gravity it is all that holds the fluid together. With
  // it clamped the fluid only expands (drop_zero_g with the volume mass rule: 79% below rest density after
  // 5000 steps); the large viscosity damps the tensile instability that keeping it risks in a run.
  rc.clamp_negative_pressure = 0;
  // The fluids' artificial viscosity as WCSPH has it (PBF's constants leave it off without
  // pbf.artificial_viscosity).
  rc.artificial_enabled = 0;
  for (int32_t f = 0; f < rc.num_fluids; ++f) {
    FluidConstants& fc = rc.fluids[f];
    if (fc.artificial_alpha > 0.0f) rc.artificial_enabled = 1;
    const double mu = spec.viscosity > 0.0 ? spec.viscosity : fc.rest_density * 0.03 * setup_.h * fc.speed_of_sound;
    fc.viscosity = float(mu);
  }
  const double rate = viscous_rate(rc, setup_.spacing, setup_.h, setup_.lattice_density);
  relaxation_.ran = true;
  relaxation_.threshold = spec.speed_threshold > 0.0 ? spec.speed_threshold : 1e-3 * setup_.max_speed_of_sound;
  std::unique_ptr<Backend> relaxing = factory(rc);
  relaxing->set_boundary(setup_.boundary);
  std::vector<RigidBody> held = setup_.bodies;  // relaxation moves the fluid only
  for (RigidBody& b : held) b.motion = BodyMotion::Fixed;
  relaxing->set_bodies(held);
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
  // Near rest density? The bulk decides: summation density reads low within h of a free surface.
  std::vector<double> ratio;
  ratio.reserve(relaxed.size());
  for (std::size_t i = 0; i < relaxed.size(); ++i)
    if (relaxed.age[i] >= 0.0f) ratio.push_back(double(relaxed.density[i]) / rc.fluids[relaxed.fluid[i]].rest_density);
  if (!ratio.empty()) {
    const auto p90 = ratio.begin() + std::ptrdiff_t(0.9 * double(ratio.size() - 1));
    std::nth_element(ratio.begin(), p90, ratio.end());
    relaxation_.bulk_density_error = *p90 - 1.0;
  }
  relaxation_.at_rest_density = std::fabs(relaxation_.bulk_density_error) <= kRelaxedDensityTolerance;
  relaxation_.converged = relaxation_.converged && relaxation_.at_rest_density;
  for (std::size_t i = 0; i < relaxed.size(); ++i) {
    relaxed.vel[i] = relaxed.vel_force[i] = relaxed.acc[i] = Vec3{0.0f, 0.0f, 0.0f};
  }
  setup_.particles = std::move(relaxed);
}

std::string RelaxationReport::summary() const {
  std::ostringstream os;
  os << "relaxation: " << steps << " steps, ";
  if (converged) {
    os << "converged";
  } else if (!at_rest_density) {
    os << "did NOT reach rest density";
  } else {
    os << "NOT converged (max_steps reached)";
  }
  os << ": final speed measure " << final_speed << " m/s (threshold " << threshold << "), bulk density "
     << 100.0 * bulk_density_error << "% from rest density (tolerance " << 100.0 * kRelaxedDensityTolerance << "%)";
  if (!at_rest_density)
    os << ". The fluid is not at rest density: the lattice is too far from it for relaxation.max_steps, or the "
          "fluid has room to spread; use resolution.mass = \"rest_density\", raise relaxation.max_steps or "
          "relax without it (relaxation.enabled = false)";
  return os.str();
}

void Simulation::set_constants(const SimConstants& constants) {
  // Gravity and the user force change the energy the scene can hold: a new gravity re-bases the budget on
  // the present state, and while the user force is on (it does work) the energy check is suspended and the
  // speed bound is guided creation's 10 c0; it re-bases when the force is released.
  const Vec3 g0 = setup_.constants.gravity, g1 = constants.gravity;
  const bool gravity_changed = g0.x != g1.x || g0.y != g1.y || g0.z != g1.z;
  const bool force_released = setup_.constants.user_force.strength != 0.0f && constants.user_force.strength == 0.0f;
  setup_.constants = constants;
  double c_max = 0.0;
  for (int32_t f = 0; f < constants.num_fluids; ++f)
    c_max = std::max(c_max, double(constants.fluids[f].speed_of_sound));
  setup_.max_speed_of_sound = c_max;
  setup_.viscous_rate = viscous_rate(constants, setup_.spacing, setup_.h, setup_.lattice_density);
  setup_.constants.artificial_rate =
      float(artificial_viscous_rate(constants, setup_.spacing, setup_.h, setup_.lattice_density));
  setup_.constants.substep_rate = float(double(setup_.constants.artificial_rate) + setup_.viscous_rate);
  setup_.blowup_speed = fallback_blowup_speed(scene_, c_max, setup_.jets);
  backend_->set_constants(setup_.constants);
  if (gravity_changed || force_released) rebase_energy(backend_->download());
}

std::string Simulation::add_body(const BodySpec& body) {
  if (scene_.solver == Solver::Pbf || !scene_.boundary_particles)
    return "rigid bodies need the wcsph or dfsph solver and \"sph\": {\"walls\": \"particles\"}";
  Scene alone = scene_;
  alone.bodies = {body};
  std::vector<std::string> report;
  try {
    std::vector<RigidBody> added = make_rigid_bodies(alone, setup_.constants, setup_.spacing, particle_budget(scene_), report);
    std::vector<RigidBody> bodies = backend_->bodies();
    added[0].label = "bodies." + std::to_string(bodies.size()) + (body.sphere ? " (sphere)" : " (box)");
    bodies.push_back(added[0]);
    backend_->set_bodies(bodies);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void Simulation::switch_backend(const BackendFactory& factory) {
  const ParticleState state = backend_->download();
  std::unique_ptr<Backend> next = factory(setup_.constants);
  next->set_boundary(setup_.boundary);
  next->set_bodies(backend_->bodies());
  next->set_springs(backend_->download_springs());
  next->upload(state);
  next->initialise_forces();
  backend_ = std::move(next);
  diag_ = backend_->diagnose();
}

// WCSPH: the thesis's limits (time_step.h, choose_time_step); DFSPH and PBF: the CFL step of [BK15]
// (choose_incompressible_step), with the acceleration's limit under DFSPH, and under PBF where the continuum
// surface force acts (its capillary waves; otherwise PBF's step follows the speeds only), and the laminar
// viscosity's explicit limit for both (the artificial viscosity's rate, scaled by c0, is sub-cycled instead:
// dfsph.h, pbf.h).
StepChoice Simulation::choose_step() const {
  const SimConstants& c = setup_.constants;
  if (c.solver != Solver::Wcsph) {
    const bool accel_limit = c.solver == Solver::Dfsph || (c.solver == Solver::Pbf && c.csf_enabled);
    return choose_incompressible_step(scene_.time_step, setup_.spacing, setup_.viscous_rate, diag_.max_speed, setup_.h,
                                      accel_limit ? diag_.max_accel : 0.0, setup_.spring_rate);
  }
  return choose_time_step(scene_.time_step, setup_.h, setup_.max_speed_of_sound, setup_.viscous_rate,
                          diag_.max_speed, diag_.max_accel);
}

void Simulation::advance() {
  const StepChoice choice = choose_step();
  const double dt = choice.dt;
  backend_->step(float(dt));
  if (setup_.constants.solver != Solver::Wcsph) {
    solver_stats_ = backend_->solver_stats();
    solver_totals_.add(solver_stats_);
  }
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
         << std::llround(scene_.max_particles) << "; give the jets a lifetime or raise the limit (--set limits.max_particles=N)";
      throw SceneError(os.str());
    }
    for (const Spawn& sp : spawns) add_energy(sp.pos, sp.vel, sp.fluid);
    backend_->emit(spawns);
  }
  time_ += dt;
  ++steps_;
  last_dt_ = dt;
  last_limit_ = choice.limit;

  diag_ = backend_->diagnose();
  if (diag_.non_finite >= 0) blow_up("a non-finite position or velocity", diag_.non_finite, dt);
  if (solver_stats_.density_error > kSolverDensityErrorBound) {
    std::ostringstream os;
    os << "the pressure solve ended with a mean compression of " << 100.0 * solver_stats_.density_error
       << "% after " << solver_stats_.density_iterations << " iterations, above the bound of "
       << 100.0 * kSolverDensityErrorBound << "% (the fastest particle has speed " << diag_.max_speed << " m/s)";
    blow_up(os.str(), diag_.fastest, dt);
  }
  const double bound = speed_bound();
  if (!(diag_.max_speed <= bound)) {
    std::ostringstream os;
    const char* which = scene_.blowup_speed > 0.0            ? "limits.blowup_speed"
                        : !energy_check_active()             ? "10 c0 while the user force is on"
                        : bound == setup_.max_speed_of_sound ? "the speed of sound c0"
                                                             : "2 sqrt(e_max), e_max the largest specific energy put in";
    os << "speed " << diag_.max_speed << " m/s, above the speed bound " << bound << " m/s (" << which << ")";
    blow_up(os.str(), diag_.fastest, dt);
  }
  if (energy_check_active() && steps_ % kEnergyCheckEvery == 0) check_energy(dt);
}

void Simulation::check_energy(double dt) {
  const ParticleState& ps = backend_->download();
  // Kinetic energy as measure() counts it (inlet particles left out), without its other figures.
  double kinetic = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!floor_bounded_)  // falling for ever: the lowest level reached so far is the floor
      potential_reference_ = std::min(potential_reference_, specific_potential(setup_.constants, ps.pos[i]));
    if (ps.age[i] >= 0.0f) kinetic += particle_kinetic_energy(setup_.constants, ps, i);
  }
  if (kinetic <= energy_limit()) return;
  std::ostringstream os;
  os << "kinetic energy " << kinetic << " J, above " << kEnergyMargin << " x the energy budget " << energy_budget()
     << " J (the initial kinetic, potential and internal energy, potential above the lowest level the fluid can "
     << "reach" << (setup_.jets.empty() ? "" : ", plus what the jets put in")
     << (setup_.constants.csf_enabled || setup_.constants.surface_tension_enabled ? ", and the surface energy surface tension can release" : "")
     << ") + " << energy_floor()
     << " J (a floor: the kinetic energy of the whole mass at 1% of c0); the fastest particle has speed "
     << diag_.max_speed << " m/s";
  blow_up(os.str(), diag_.fastest, dt);
}

// The blow-up message: when, where, which bound, the likely cause and what to change. The cause is read off
// the scene: a fixed step above the sound-speed limit; a flow faster than a tenth of c0 (weak
// compressibility needs c0 >= 10 times the flow speed); otherwise the method creates energy at this step
// (tensile instability, walls, no dissipation of the start-up noise).
void Simulation::blow_up(const std::string& what, int32_t particle, double dt) const {
  const ParticleState& ps = backend_->download();
  std::ostringstream os;
  os << "simulation became unstable at t = " << time_ << " s (step " << steps_ << ", dt = " << dt << " s): ";
  if (particle >= 0 && std::size_t(particle) < ps.size()) {
    const Vec3 x = ps.pos[std::size_t(particle)];
    os << "particle id " << ps.id[std::size_t(particle)] << " at (" << x.x << ", " << x.y << ", " << x.z << ")";
  } else {
    os << "particle id -1";
  }
  os << ": " << what << ".";

  // Surface tension too strong for the spacing's damping: the energy check fired with a budget mostly of
  // surface energy. The Ohnesorge number at the spacing, mu / sqrt(rho0 sigma d), was 0.08 for drop_oscillation
  // (sigma 4.7 N/m, held) and 0.0055 at 1000 N/m, which flew apart (docs/results.md, "A drop's energy budget").
  const FluidSpec* strongest = nullptr;
  for (const FluidSpec& f : scene_.fluids)
    if (f.surface_tension > 0.0 && (!strongest || f.surface_tension > strongest->surface_tension)) strongest = &f;
  if (strongest && what.find("kinetic energy") == 0 && surface_in_ > 0.5 * energy_budget()) {
    const double ohnesorge = strongest->viscosity / std::sqrt(strongest->rest_density * strongest->surface_tension * setup_.spacing);
    os << " Likely cause: the surface tension (fluid \"" << strongest->name << "\", sigma = " << strongest->surface_tension
       << " N/m) drives the surface faster than the viscosity damps it at this spacing (Ohnesorge number mu / "
       << "sqrt(rho0 sigma d) = " << ohnesorge << "): lower fluids.N.surface_tension, raise fluids.N.viscosity or "
       << "refine the resolution.";
    throw BlowUp(os.str());
  }
  if (scene_.solver != Solver::Wcsph) {
    const bool dfsph = scene_.solver == Solver::Dfsph;
    os << " Likely cause: the " << solver_name(scene_.solver) << " pressure solve did not hold the fluid at this step "
       << "(last solve: " << solver_stats_.density_iterations << " iterations, mean compression "
       << 100.0 * solver_stats_.density_error << "%). "
       << (dfsph ? (scene_.time_step.mode == TimeStepMode::Fixed
                        ? "Raise dfsph.max_iterations or lower the time step (time_step.dt), or let DFSPH choose it "
                          "(time_step.mode = \"adaptive\")."
                        : "Raise dfsph.max_iterations or lower time_step.max or time_step.cfl_velocity.")
                 : "Raise pbf.iterations or lower the time step (time_step.dt).");
    throw BlowUp(os.str());
  }
  const double c0 = setup_.max_speed_of_sound;
  const double dt_sound = scene_.time_step.cfl_sound * setup_.h / c0;
  const double flow = std::sqrt(2.0 * std::max(0.0, max_specific_in_ - potential_reference_));
  const double dt_viscous = setup_.viscous_rate > 0.0 ? 2.0 / setup_.viscous_rate : 0.0;  // viscous_limit.h
  if (scene_.time_step.mode == TimeStepMode::Fixed && dt_viscous > 0.0 && dt > dt_viscous) {
    os << " Likely cause: the fixed time step " << dt << " s is above the explicit viscous limit 2 / lambda_max = "
       << dt_viscous << " s of this viscosity (src/common/viscous_limit.h). Use time_step.dt <= "
       << scene_.time_step.cfl_viscosity * dt_viscous << " s or time_step.mode = \"adaptive\".";
  } else if (scene_.time_step.mode == TimeStepMode::Fixed && dt > dt_sound) {
    os << " Likely cause: the fixed time step " << dt << " s is above the sound-speed limit cfl_sound h / c0 = "
       << dt_sound << " s. Use a smaller time step (time_step.dt) or time_step.mode = \"adaptive\".";
  } else if (what.find("non-finite") != std::string::npos) {
    os << " Try a smaller time step (time_step.dt, time_step.max or the CFL factors), a stabler integrator "
          "(modified_velocity_verlet), or more viscosity.";
  } else if (what.find("speed") == 0 && 10.0 * flow > c0) {
    os << " Likely cause: the flow (up to " << flow << " m/s, free fall and jets) is faster than a tenth of the "
       << "speed of sound c0 = " << c0 << " m/s, so the fluid compresses far beyond the weakly compressible range. "
       << "Raise fluids.N.speed_of_sound to at least " << 10.0 * flow << " m/s (10 times the flow speed).";
  } else {
    os << " Likely cause: energy grows at this time step, so the method creates it.";
    bool alpha = false;
    for (const FluidSpec& f : scene_.fluids) alpha = alpha || f.artificial_viscosity > 0.0;
    if (!scene_.clamp_negative_pressure)
      os << " Negative pressure pulls particles into clumps (tensile instability): set sph.negative_pressure = "
            "\"clamp\" or add near pressure (fluids.N.near_stiffness).";
    if (!alpha) os << " Nothing damps the noise: set fluids.N.artificial_viscosity = 0.05 (the default).";
    if (!scene_.mirror_walls) os << " Penalty walls pack particles against the walls: set sph.walls = \"mirror\".";
    os << " A smaller time step (time_step.max or the CFL factors) helps where the step is near its limit.";
  }
  throw BlowUp(os.str());
}

}  // namespace sph
