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

// The simulation became unstable: NaN, a speed above the speed bound, or more kinetic energy than the scene
// can hold (see Simulation). The message names the time, the step, the particle, which bound, the likely
// cause and what to change.
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
  // Bulk density at the end, as rho / rho0 - 1 of the particle at the 90th percentile of rho / rho0 (the
  // surface reads low with summation density; the 90th percentile is a bulk particle), and whether it is
  // within kRelaxedDensityTolerance of rest density. converged implies at_rest_density.
  double bulk_density_error = 0.0;
  bool at_rest_density = false;
  // One line for the runner's summary: steps, whether it converged, the bulk density and, when it did not
  // reach rest density or balance, why and what to change.
  std::string summary() const;
};
constexpr double kRelaxedDensityTolerance = 0.02;

// Energy check (issue 10): the energy the scene can hold is what was put in, measured from the lowest level
// the fluid can reach (metrics.h, lowest_reachable_potential): the initial kinetic, potential and internal
// energy of every particle (the elastic energy of its equation of state and near pressure,
// equation_of_state.h; zero for a lattice at rest density with clamped negative pressure) plus
// 1/2 m v^2 + m phi of each particle a jet creates (at rest density). A run is unstable when its kinetic
// energy exceeds kEnergyMargin times that budget plus a floor, or when a particle is faster than the speed
// bound (Simulation::speed_bound()).
constexpr double kEnergyMargin = 1.2;
// Steps between two energy checks: the check reads the particles back (a copy from a GPU), while energy
// grows over many steps; a fast explosion is caught at every step by the speed bound. Nine steps in ten
// do not check, so the median ms per step (sph_run, sph_bench) does not include it.
constexpr long kEnergyCheckEvery = 10;

// The incompressible solvers' density error bound: a step whose pressure solve ends with a mean compression
// (SolverStats::density_error) above it stops the run with the blow-up message. A converging solve ends at its
// tolerance (DFSPH 0.01%); PBF with a fixed iteration count measured up to a few percent on the dam break
// (docs/results.md); 10% means the solve has lost hold of the fluid.
constexpr double kSolverDensityErrorBound = 0.1;

// What the iterative solvers did over a run (Simulation::solver_totals), for the runner's summary.
struct SolverTotals {
  long steps = 0;                        // steps counted
  long density_iterations = 0;           // summed over the steps
  long divergence_iterations = 0;
  int32_t max_density_iterations = 0;
  int32_t max_divergence_iterations = 0;
  long density_capped_steps = 0;         // steps whose solve stopped at its cap above tolerance
  long divergence_capped_steps = 0;
  double max_density_error = 0.0;        // largest end-of-solve mean compression of any step
  long substepped_steps = 0;             // DFSPH, PBF: steps that sub-cycled the non-pressure forces (PBF: viscosity)
  int32_t max_viscous_substeps = 1;
  long coarse_iterations = 0;            // PBF's coarse grid: conjugate-gradient iterations, summed
  int32_t max_coarse_iterations = 0;
  long coarse_capped_steps = 0;          // steps whose coarse solve stopped at pbf.coarse_iterations
  void add(const SolverStats& s);
};

class Simulation {
 public:
  // restart: a frame of an earlier run of this scene (frame_reader.h) to continue from, bit for bit: its
  // particles (with their accelerations), time, step, next id and jet accumulators replace the start-up
  // state; no relaxation, no initialise_forces. Throws SceneError when the frame does not fit the scene.
  Simulation(const Scene& scene, const BackendFactory& factory, double run_time, const Frame* restart = nullptr);

  // One time step; throws BlowUp when the state has become unphysical.
  void advance();
  // Adds a rigid body between steps (the demo's D key): sampled as make_rigid_bodies does, at rest. Returns ""
  // or why it was not added (bodies need WCSPH or DFSPH and walls of boundary particles; it must lie inside the
  // containers).
  std::string add_body(const BodySpec& body);

  double time() const { return time_; }
  long steps() const { return steps_; }
  double last_dt() const { return last_dt_; }
  StepLimit last_limit() const { return last_limit_; }
  const Setup& setup() const { return setup_; }
  const Scene& scene() const { return scene_; }
  const RelaxationReport& relaxation() const { return relaxation_; }
  // The iterative solvers' last step and their totals over the run (zero under WCSPH).
  const SolverStats& solver_stats() const { return solver_stats_; }
  const SolverTotals& solver_totals() const { return solver_totals_; }
  // Energy budget [J]: everything put in, measured from potential_reference(); see kEnergyMargin.
  double energy_budget() const { return energy_in_ - mass_in_ * potential_reference_; }
  // The specific potential energy -g.x [J/kg] counted as zero (pass it to measure()).
  double potential_reference() const { return potential_reference_; }
  // Kinetic energy [J] allowed before the run stops: kEnergyMargin * budget + energy_floor().
  double energy_limit() const { return kEnergyMargin * energy_budget() + energy_floor(); }
  // Absolute floor [J]: the kinetic energy of everything put in moving at 1% of the largest speed of sound,
  // 1/2 M (0.01 c0)^2. It equals the elastic energy a weakly compressible fluid stores at a 1% density
  // change (c0^2 delta^2 / 2 per kg), which WCSPH allows and may release, so a fluid at rest without
  // potential energy is not flagged for its acoustic noise or round-off.
  double energy_floor() const;
  // Fastest allowed particle [m/s]: limits.blowup_speed when the scene gives one, else
  // max(c0, 2 sqrt(e_max)), e_max the largest specific energy put in [J/kg]. 2 sqrt(e) is sqrt(2) times the
  // ballistic speed sqrt(2 e): pressure can pass energy on, and a dam-break front runs at 2 sqrt(g H)
  // (Ritter 1892) where free fall from H gives sqrt(2 g H). A jet faster than its c0 (water_jet) keeps running.
  // While the user force is on: guided creation's 10 times the fastest of c0 and the jets.
  double speed_bound() const;
  // Whether the energy check runs: suspended while the demo's user force (which does work) is on.
  bool energy_check_active() const { return setup_.constants.user_force.strength == 0.0f; }
  TimeStepSpec& time_step() { return scene_.time_step; }  // live edits (the demo)
  Backend& backend() { return *backend_; }
  const Backend& backend() const { return *backend_; }
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
  SolverStats solver_stats_;
  SolverTotals solver_totals_;

  // Energy bookkeeping (absolute: phi = -g.x without reference): sum m (1/2 v^2 + phi + u) and sum m of
  // everything put in, the largest 1/2 v^2 + phi + u, and the reference level (see rebase_energy()).
  double energy_in_ = 0.0;
  double mass_in_ = 0.0;
  double max_specific_in_ = 0.0;
  double potential_reference_ = 0.0;
  double surface_in_ = 0.0;  // the budget's share of surface energy [J] (rebase_energy()): names the blow-up's cause
  bool floor_bounded_ = true;

  void relax(const BackendFactory& factory);
  void continue_from(const Frame& frame);  // simulation_restart.cpp
  // Counts a particle put in (the initial state or a jet's spawn) into the budget.
  void add_energy(Vec3 x, Vec3 v, int32_t fluid, double internal = 0.0);
  // Starts the budget afresh from the particles present (set-up, and live changes of gravity or the user
  // force, which change what the scene can hold).
  void rebase_energy(const ParticleState& ps);
  void check_energy(double dt);
  [[noreturn]] void blow_up(const std::string& what, int32_t particle, double dt) const;
  StepChoice choose_step() const;
  double time_ = 0.0;
  long steps_ = 0;
  double last_dt_ = 0.0;
  StepLimit last_limit_ = StepLimit::Fixed;
  bool stop_emission_at_limit_ = false, emission_stopped_ = false;
};

}  // namespace sph
