// The serial reference back end: plain loops over particles, no threads. It runs the solver's phases
// (src/solvers/step.h) through its execution interface; the physics is the shared per-particle code of
// src/common/, the order of a step the solver's.
#pragma once

#include <vector>

#include "../common/backend.h"
#include "../common/neighbour_list_choice.h"
#include "../common/particle_state.h"

namespace sph {

class CpuBackend final : public Backend {
 public:
  explicit CpuBackend(const SimConstants& constants) : c_(constants) {}

  std::string name() const override { return "cpu"; }
  void upload(const ParticleState& state) override { s_ = state; }
  void set_boundary(const BoundaryParticles& boundary) override { boundary_ = boundary; }
  void set_springs(const SpringNetwork& springs) override { springs_ = springs; }
  SpringNetwork download_springs() override { return springs_; }
  void set_bodies(const std::vector<RigidBody>& bodies) override {
    bodies_ = bodies;
    upload_bodies();
  }
  const std::vector<RigidBody>& bodies() const override { return bodies_; }
  // The bodies' views for the loops, from their state.
  void upload_bodies() {
    body_views_.resize(bodies_.size());
    for (std::size_t k = 0; k < bodies_.size(); ++k) body_views_[k] = bodies_[k].view(bodies_[k].local.view(), c_.kernel.h);
  }
  void initialise_forces() override;
  void step(float dt) override;
  void step_phase(Phase p, float dt) override;
  void emit(const std::vector<Spawn>& spawns) override;
  const ParticleState& download() override { return s_; }
  std::size_t size() const override { return s_.size(); }
  Diagnostics diagnose() override;
  const PhaseTimes& phase_times() const override { return times_; }
  SolverStats solver_stats() const override { return stats_; }
  void set_constants(const SimConstants& constants) override { c_ = constants; }

  // The grid phase alone (tests of the grid and of per-particle formulas); step_phase runs any phase.
  void build_grid();

  GridView grid_view() const {
    return GridView{c_.grid,
                    key_.data(),
                    particle_block_.data(),
                    block_neighbours_.data(),
                    cell_start_.data(),
                    list_capacity_ > 0 ? neighbour_list_.data() : nullptr,
                    neighbour_count_.data(),
                    list_capacity_,
                    block_begin_.data(),
                    block_code_.data(),
                    &blocks_,
                    blocks_,  // a table for every block
                    boundary_.view(),
                    body_views_.data(),
                    int32_t(body_views_.size())};
  }
  const SimConstants& constants() const { return c_; }
  ParticleState& state() { return s_; }

 private:
  struct Exec;  // the execution interface the solver runs on (cpu_backend.cpp, src/solvers/execution.h)
  void recycle();

  SimConstants c_;
  ParticleState s_;
  ParticleState sorted_;              // reorder target, swapped with s_
  BoundaryParticles boundary_;        // static; read in place
  SpringNetwork springs_;             // by particle id; updated in place
  std::vector<RigidBody> bodies_;     // their particles read in place
  std::vector<BodyView> body_views_;
  // The grid (grid_build.h): sorted keys, block of each particle, blocks' first particles and codes, cell
  // tables and neighbours, neighbour lists.
  struct SortRecord {
    uint64_t key;
    int32_t id, index;
  };
  std::vector<SortRecord> sort_records_, moved_records_, merged_records_;
  std::vector<uint64_t> key_, block_code_;
  std::vector<int32_t> particle_block_, block_begin_, block_neighbours_, cell_start_;
  int32_t blocks_ = 0;  // occupied blocks at the last grid build
  std::vector<int32_t> neighbour_list_, neighbour_count_;
  int32_t list_capacity_ = 0;  // neighbour_list_capacity(c_) at the last grid build
  NeighbourListChoice list_choice_;
  PhaseTimes times_;
  SolverStats stats_;
  std::vector<double> reduce_a_, reduce_b_;  // the levels of a reduction (src/solvers/reduction.h)
  std::vector<unsigned long long> scratch_;  // Exec::scratch (PBF's coarse grid)
};

}  // namespace sph
