#include "cpu_backend.h"

#include <chrono>
#include <cmath>

#include "../common/boundaries.h"
#include "../common/density.h"
#include "../common/forces.h"
#include "../common/grid.h"
#include "../common/integrate.h"
#include "../common/pressure.h"

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

void CpuBackend::step(float dt) {
  timed(times_, Phase::Predict, [&] { predict(dt); });        // integrator: move to where forces are evaluated
  timed(times_, Phase::BuildGrid, [&] { build_grid(); });     // counting sort by cell, reorder all arrays
  timed(times_, Phase::Density, [&] { density(dt); });        // density and near density
  timed(times_, Phase::Pressure, [&] { pressure(); });        // equation of state, near pressure
  timed(times_, Phase::Forces, [&] { forces(); });            // pressure, viscosity, surface tension, gravity
  timed(times_, Phase::Correct, [&] { correct(dt); });        // integrator: finish the step
  timed(times_, Phase::Boundaries, [&] { boundaries(dt); });  // penalty boundaries
  timed(times_, Phase::Recycle, [&] { recycle(); });          // remove particles past their lifetime
  ++times_.steps;
}

void CpuBackend::initialise_forces() {
  for (std::size_t i = 0; i < s_.size(); ++i) s_.vel_force[i] = s_.vel[i];
  build_grid();
  density(0.0f);
  pressure();
  forces();
}

void CpuBackend::predict(float dt) {
  const ParticleView p = s_.view();
  for (int32_t i = 0; i < p.n; ++i) predict_particle(c_, p, i, dt);
}

// Counting sort by cell: count, exclusive prefix sum, fill, sort each cell by particle id, then move every
// array into that order so that neighbour loops read memory in order.
void CpuBackend::build_grid() {
  const std::size_t n = s_.size();
  const std::size_t ncells = std::size_t(cell_count(c_.grid));
  cell_start_.assign(ncells + 1, 0);
  particle_cell_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int32_t cell = cell_index(c_.grid, s_.pos[i]);
    particle_cell_[i] = cell;
    ++cell_start_[std::size_t(cell) + 1];
  }
  for (std::size_t cell = 0; cell < ncells; ++cell) cell_start_[cell + 1] += cell_start_[cell];
  next_slot_.assign(cell_start_.begin(), cell_start_.end() - 1);
  order_.resize(n);
  for (std::size_t i = 0; i < n; ++i) order_[std::size_t(next_slot_[std::size_t(particle_cell_[i])]++)] = int32_t(i);
  for (std::size_t cell = 0; cell < ncells; ++cell)
    if (cell_start_[cell + 1] - cell_start_[cell] > 1)
      sort_cell_by_id(order_.data(), cell_start_[cell], cell_start_[cell + 1], s_.id.data());
  sorted_.resize(n);
  for (std::size_t j = 0; j < n; ++j) sorted_.copy_particle(j, s_, std::size_t(order_[j]));
  std::swap(s_, sorted_);
}

void CpuBackend::density(float dt) {
  const ParticleView p = s_.view();
  const GridView g = grid_view();
  for (int32_t i = 0; i < p.n; ++i) density_of(c_, g, p, i, dt);
}

void CpuBackend::pressure() {
  const ParticleView p = s_.view();
  for (int32_t i = 0; i < p.n; ++i) pressure_of(c_, p, i);
}

void CpuBackend::forces() {
  const ParticleView p = s_.view();
  const GridView g = grid_view();
  with_force_model(c_, [&](auto model) {
    for (int32_t i = 0; i < p.n; ++i) forces_with<decltype(model)>(c_, g, p, i);
  });
}

void CpuBackend::correct(float dt) {
  const ParticleView p = s_.view();
  for (int32_t i = 0; i < p.n; ++i) correct_particle(c_, p, i, dt);
}

void CpuBackend::boundaries(float dt) {
  if (c_.num_shapes == 0) return;
  const ParticleView p = s_.view();
  for (int32_t i = 0; i < p.n; ++i) boundaries_of(c_, p, i, dt);
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
