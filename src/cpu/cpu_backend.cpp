#include "cpu_backend.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "../common/grid_build.h"
#include "../common/neighbour_list.h"
#include "../common/neighbour_rows.h"
#include "../solvers/reduction.h"
#include "../solvers/step.h"

namespace sph {
namespace {

// Runs f and adds its wall time to the phase's total.
template <class F>
void timed(PhaseTimes& t, Phase p, F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  t.seconds[std::size_t(p)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// The serial reference's execution interface (src/solvers/execution.h): plain loops, in index order, no
// threads.
struct CpuBackend::Exec {
  struct Constants {
    const SimConstants* p;
    const SimConstants& operator*() const { return *p; }
  };
  CpuBackend& b;
  Constants constants() const { return Constants{&b.c_}; }
  const SimConstants& host_constants() const { return b.c_; }
  ParticleView particles() { return b.s_.view(); }
  GridView grid() const { return b.grid_view(); }
  SpringView springs() { return b.springs_.view(); }
  template <class F>
  void for_each(const F& f) {
    const int32_t n = int32_t(b.s_.size());
    for (int32_t i = 0; i < n; ++i) f(i);
  }
  template <class F>
  void for_index(int32_t n, const F& f) {
    for (int32_t i = 0; i < n; ++i) f(i);
  }
  void* scratch(std::size_t bytes) {
    b.scratch_.resize((bytes + 7) / 8);
    return b.scratch_.data();
  }
  void build_grid() { b.build_grid(); }
  void recycle() { b.recycle(); }
  std::vector<RigidBody>& bodies() { return b.bodies_; }
  void upload_bodies() { b.upload_bodies(); }
  // The deterministic sum of reduction.h, its groups one after another.
  template <class F>
  double sum(int32_t n, const F& f) {
    const std::size_t groups = std::size_t(reduce_groups(n));
    b.reduce_a_.resize(groups);
    b.reduce_b_.resize(groups);
    const double* r = reduce_sum_into(n, f, b.reduce_a_.data(), b.reduce_b_.data(), [](int32_t count, const auto& g) {
      for (int32_t k = 0; k < count; ++k) g(k);
    });
    return r != nullptr ? *r : 0.0;
  }
};

void CpuBackend::step(float dt) {
  for (const Phase p : step_phases(c_.solver)) step_phase(p, dt);
  ++times_.steps;
}

// The solver's phase p (src/solvers/step.h), timed.
void CpuBackend::step_phase(Phase p, float dt) {
  if (!step_phases(c_.solver).contains(p))
    throw std::invalid_argument(std::string("cpu: ") + phase_name(p) + " is not a phase of a step of this solver");
  Exec x{*this};
  timed(times_, p, [&] { run_solver_phase(x, p, dt, stats_); });
}

void CpuBackend::initialise_forces() {
  Exec x{*this};
  initialise_solver(x);
}

// The grid of grid_build.h: keys, sort by (key, id), blocks, each block's cell table and neighbours; then
// every array moves into the sorted order so that neighbour loops read memory in order; last each
// particle's neighbour list (grid.h), which density, forces and mirror walls then read.
void CpuBackend::build_grid() {
  const int32_t n = int32_t(s_.size());
  // (key, id, index) records in the current order, which is the previous step's sorted order but for the
  // particles that changed cell: those (a few percent a step) are taken out, sorted and merged back, in
  // O(n + k log k) instead of a full sort's O(n log n). (key, id) is unique, so the result is the full
  // sort's, whichever records are taken out.
  const auto before = [](const SortRecord& a, const SortRecord& b) {
    return a.key < b.key || (a.key == b.key && a.id < b.id);
  };
  sort_records_.resize(std::size_t(n));
  for (int32_t i = 0; i < n; ++i)
    sort_records_[std::size_t(i)] = SortRecord{cell_key(c_.grid, s_.pos[std::size_t(i)]), s_.id[std::size_t(i)], i};
  // Keep a record in the ascending run if it is not below the last kept one and not above its successor
  // (a record that jumped ahead is taken out instead of the many it would leave behind).
  moved_records_.clear();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    const SortRecord r = sort_records_[i];
    const bool in_order = (kept == 0 || !before(r, sort_records_[kept - 1])) &&
                          (i + 1 == std::size_t(n) || !before(sort_records_[i + 1], r));
    if (in_order) sort_records_[kept++] = r;
    else moved_records_.push_back(r);
  }
  sort_records_.resize(kept);
  std::sort(moved_records_.begin(), moved_records_.end(), before);
  merged_records_.resize(std::size_t(n));
  std::merge(sort_records_.begin(), sort_records_.end(), moved_records_.begin(), moved_records_.end(),
             merged_records_.begin(), before);
  std::swap(sort_records_, merged_records_);
  key_.resize(std::size_t(n));
  sorted_.resize(std::size_t(n));
  for (int32_t j = 0; j < n; ++j) {
    const SortRecord& r = sort_records_[std::size_t(j)];
    key_[std::size_t(j)] = r.key;
    sorted_.copy_particle(std::size_t(j), s_, std::size_t(r.index));
  }
  std::swap(s_, sorted_);
  s_.take_derived(sorted_);
  s_.fit_derived(needs_solver_fields(c_));
  const ParticleView p = s_.view();
  for (int32_t j = 0; j < n; ++j) pack_position(c_, p, j);  // the neighbour loops' position and mass records

  particle_block_.resize(std::size_t(n));
  block_begin_.clear();
  block_code_.clear();
  for (int32_t j = 0; j < n; ++j) {
    if (is_block_start(key_.data(), j)) {
      block_begin_.push_back(j);
      block_code_.push_back(block_of_key(key_[std::size_t(j)]));
    }
    particle_block_[std::size_t(j)] = int32_t(block_begin_.size()) - 1;
  }
  blocks_ = int32_t(block_code_.size());
  const int32_t blocks = blocks_;
  block_begin_.push_back(n);
  cell_start_.resize(std::size_t(blocks) * kBlockTable);
  block_neighbours_.resize(std::size_t(blocks) * kBlockNeighbours);
  for (int32_t b = 0; b < blocks; ++b) {
    fill_block_table(key_.data(), block_begin_[std::size_t(b)], block_begin_[std::size_t(b) + 1],
                     cell_start_.data() + std::size_t(b) * kBlockTable);
    find_block_neighbours(block_code_.data(), blocks, b, block_neighbours_.data() + std::size_t(b) * kBlockNeighbours);
  }
  list_capacity_ = neighbour_list_capacity(c_);
  if (list_capacity_ == 0) return;  // no lists: every loop searches
  const std::size_t stride = std::size_t(list_capacity_ + kNeighbourListPad);
  neighbour_list_.resize(std::size_t(n) * stride);
  neighbour_count_.resize(std::size_t(n));
  GridView search = grid_view();
  search.neighbour_list = nullptr;
  const auto t0 = std::chrono::steady_clock::now();
  const bool branch_free = list_choice_.branch_free();
  constexpr int32_t kRows = kBlockY * kBlockZ;
  for (int32_t b = 0; b < blocks; ++b)
    for (int32_t row = 0; row < kRows; ++row) {
      if (branch_free)
        neighbour_rows::list_row_neighbours<true>(search, s_.pos.data(), neighbour_radius2(c_), b, row, neighbour_list_.data(),
                                                  neighbour_count_.data(), list_capacity_);
      else
        neighbour_rows::list_row_neighbours<false>(search, s_.pos.data(), neighbour_radius2(c_), b, row, neighbour_list_.data(),
                                                   neighbour_count_.data(), list_capacity_);
    }
  list_choice_.record(branch_free, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                      std::size_t(n));
}

// Particles older than their fluid's lifetime, or taken out by an absorbing boundary, leave the
// simulation; their slots are reused by emission.
void CpuBackend::recycle() {
  std::size_t n = s_.size();
  for (std::size_t i = 0; i < n;) {
    if (expired(c_.fluids[s_.fluid[i]], s_.age[i])) {
      s_.copy_particle(i, s_, n - 1);
      --n;
    } else {
      ++i;
    }
  }
  s_.resize(n);
}

void CpuBackend::emit(const std::vector<Spawn>& spawns) {
  const auto t0 = std::chrono::steady_clock::now();
  for (const Spawn& sp : spawns) s_.append(sp);
  times_.seconds[std::size_t(Phase::Emit)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Diagnostics CpuBackend::diagnose() {
  Diagnostics d;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const Vec3 x = s_.pos[i], v = s_.vel[i], a = s_.acc[i];
    if (!std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z)) {
      d.non_finite = int32_t(i);
      break;
    }
    const float speed = length(v);
    if (speed > d.max_speed) {
      d.max_speed = speed;
      d.fastest = int32_t(i);
    }
    const float accel = length(a);
    if (accel > d.max_accel) d.max_accel = accel;
  }
  return d;
}

}  // namespace sph
