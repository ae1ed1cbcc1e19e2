// Continuing a run from a frame (sph_run --restart) and describing the current state for a frame. The
// continued run repeats the uninterrupted one bit for bit because everything a step reads is restored:
// positions, velocities, accelerations (the integrator's previous evaluation), densities (the continuity
// method integrates them), ages, ids, the simulated time, the step, the next id and the jets' emission
// accumulators. The order of the particles does not matter: every back end sorts them by (cell, id) before
// any sum over neighbours. The grid comes from the scene exactly as in the original run.
#include <cmath>
#include <sstream>

#include "simulation.h"

namespace sph {

void Simulation::continue_from(const Frame& frame) {
  const FrameInfo& info = frame.info;
  auto refuse = [&](const std::string& what) {
    throw SceneError(frame.path + ": cannot continue " + scene_.source + " from this frame: " + what);
  };
  if (!setup_.bodies.empty())
    refuse("the scene has rigid bodies (\"bodies\"), whose state the frames do not hold; run it from the start");
  for (std::size_t i = 0; i < scene_.fluids.size(); ++i)
    if (scene_.fluids[i].spring_modulus > 0.0)
      refuse("fluids." + std::to_string(i) + ".spring_modulus: the fluid has viscoelastic springs, whose rest lengths "
             "the frames do not hold; run the scene from the start (or without springs: --set fluids." +
             std::to_string(i) + ".spring_modulus=0)");
  if (info.scene != scene_.name)
    refuse("it was written by the scene \"" + info.scene + "\", not \"" + scene_.name +
           "\" (to start another scene from a frame, use the scene key initial_state)");
  // The solvers keep different state in the same fields (DFSPH's warm start in pressure and near_pressure).
  if (!info.solver.empty() && info.solver != solver_name(scene_.solver))
    refuse("it was written by solver \"" + info.solver + "\", and this run's is \"" + solver_name(scene_.solver) +
           "\"; continue with --set solver=" + info.solver);
  if (info.spacing != setup_.spacing) {
    std::ostringstream os;
    os.precision(17);
    os << "it was written at particle spacing " << info.spacing << " m, the scene now gives " << setup_.spacing
       << " m; continue with the resolution of the original run";
    refuse(os.str());
  }
  if (info.jet_travelled.size() != setup_.jets.size())
    refuse("it records " + std::to_string(info.jet_travelled.size()) + " jet(s), the scene has " +
           std::to_string(setup_.jets.size()));
  check_frame_fluids(frame, scene_, frame.path);
  for (std::size_t j = 0; j < setup_.jets.size(); ++j) setup_.jets[j].set_travelled(info.jet_travelled[j]);
  setup_.particles = frame.particles;
  setup_.next_id = info.next_id;
  time_ = info.time;
  steps_ = info.step;
  backend_->upload(setup_.particles);  // with the stored accelerations: no initialise_forces
  rebase_energy(setup_.particles);      // the floor; then the original run's budget where the frame has it
  if (info.has_energy) {
    energy_in_ = info.energy_in;
    mass_in_ = info.mass_in;
    max_specific_in_ = info.max_specific_in;
    potential_reference_ = info.potential_reference;
  }
}

FrameInfo Simulation::frame_info(int frame_index) const {
  FrameInfo info;
  info.scene = scene_.name;
  info.solver = solver_name(scene_.solver);
  info.time = time_;
  info.step = steps_;
  info.frame_index = frame_index;
  info.next_id = setup_.next_id;
  info.spacing = setup_.spacing;
  for (const JetEmitter& j : setup_.jets) info.jet_travelled.push_back(j.travelled());
  info.has_energy = std::isfinite(max_specific_in_) && std::isfinite(potential_reference_);
  info.energy_in = energy_in_;
  info.mass_in = mass_in_;
  info.max_specific_in = max_specific_in_;
  info.potential_reference = potential_reference_;
  return info;
}

}  // namespace sph
