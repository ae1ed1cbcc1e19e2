// The device back end: the solver's phases (src/solvers/step.h) as data-parallel loops over particle or
// block indices (device_launch.h), the physics from src/common/, the grid sorted by cell key (device_grid.h). One source, two builds (see
// device_backend.h): SPH_DEVICE_NS and the factory name are set by the including build.
//
// The simulation constants are read from one copy (device_constants.h): the GPU's constant memory under
// nvcc; the functors carry only views, scalars and a ConstantsRef.
//
// Under nvcc a step is asynchronous (issue 11, item 6): every phase is enqueued on one stream without
// waiting, and the step ends with one reduction of the diagnostics whose result, with the recycled count
// and the grid's block count, is copied to the host: the step's one read; the host waits for it once,
// when it needs it (the next step, size(), diagnose(), emit(), download()). Phase times come from CUDA
// events (device_timers.h). Under g++ every loop finishes before it returns, and the step ends with the
// same summary, so that the host build runs (and tests) the same logic.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <thrust/copy.h>
#include <thrust/execution_policy.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <thrust/scan.h>
#include <thrust/transform_reduce.h>

#include "../common/grid.h"
#include "../solvers/reduction.h"
#include "../solvers/step.h"
#include "device_arrays.h"
#include "device_constants.h"
#include "device_diagnostics.h"
#include "device_faults.h"
#include "device_grid.h"
#include "device_interop.h"
#include "device_launch.h"
#include "device_readback.h"
#include "device_timers.h"
#include "device_backend.h"

#if defined(__CUDACC__)
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_select.cuh>
#endif

namespace sph {
namespace SPH_DEVICE_NS {

// ---- the back end's own functors (the solver's phases are in src/solvers/wcsph.h) ----------------------

// The grid phase's packed position and mass records (pack_position), after the reorder.
struct PackPositionFn {
  ConstantsRef c;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { pack_position(*c, p, i); }
};

// Recycle: whether each particle stays, in a loop of its own, so that the stable selection that follows
// (CUB's select kernel) reads flags only: with this test as its predicate it spilled registers (ptxas).
struct KeepFn {
  ConstantsRef c;
  ParticleView p;
  uint8_t* keep;
  SPH_KERNEL_FN void operator()(int32_t i) const { keep[i] = !expired((*c).fluids[p.fluid[i]], p.age[i]); }
};

struct IsSetFn {
  SPH_HD bool operator()(uint8_t flag) const { return flag != 0; }
};

// Whether any particle can expire (params.h, expired): some fluid has a lifetime or some shape absorbs.
// Otherwise the recycle phase has nothing to do and is skipped.
inline bool particles_can_expire(const SimConstants& c) {
  for (int32_t f = 0; f < c.num_fluids; ++f)
    if (c.fluids[f].lifetime > 0.0f) return true;
  for (int32_t s = 0; s < c.num_shapes; ++s)
    if (c.shapes[s].absorb) return true;
  return false;
}

// ---- the back end -----------------------------------------------------------------------------------------

class DeviceBackend final : public Backend {
 public:
  DeviceBackend(const SimConstants& constants, std::string name)
      : c_(constants), can_expire_(particles_can_expire(constants)), name_(std::move(name)), summary_(1) {}

  std::string name() const override { return name_; }
  void upload(const ParticleState& state) override {
    settle();
    run_phase(name_, "upload", [&] {
      check_memory_for(state.size());
      d_.upload(state);
    });
    diag_current_ = false;
  }
  void set_boundary(const BoundaryParticles& b) override {
    settle();
    run_phase(name_, "boundary upload", [&] { boundary_.upload(b); });
  }
  void set_springs(const SpringNetwork& springs) override {
    settle();
    run_phase(name_, "springs upload", [&] { springs_.upload(springs); });
  }
  SpringNetwork download_springs() override {
    await_step();
    SpringNetwork s;
    run_phase(name_, "springs download", [&] { s = springs_.download(); });
    return s;
  }
  void set_bodies(const std::vector<RigidBody>& bodies) override {
    settle();
    run_phase(name_, "bodies upload", [&] {
      bodies_ = bodies;
      body_locals_.resize(bodies_.size());
      for (std::size_t k = 0; k < bodies_.size(); ++k) body_locals_[k].upload(bodies_[k].local);
      upload_bodies();
    });
  }
  const std::vector<RigidBody>& bodies() const override {
    await_step();
    return bodies_;
  }
  // Waits for the last step's end when it recycled on cuda (its count comes with the diagnostics).
  std::size_t size() const override {
    await_step();
    return trim_to_ >= 0 ? std::size_t(trim_to_) : d_.size();
  }
  SolverStats solver_stats() const override { return stats_; }
  // Under nvcc the phase times of enqueued work are read here, or at the step's end (device_timers.h).
  const PhaseTimes& phase_times() const override {
    clock_.collect(times_);
    return times_;
  }
  void set_constants(const SimConstants& constants) override {
    c_ = constants;
    can_expire_ = particles_can_expire(constants);
    constants_.changed();
  }

  // Drawing (device_interop.h): the render kernel into host arrays (tests), or into the demo's OpenGL
  // buffers through interop in the cuda build.
  bool write_render_arrays(const RenderColouring& r, std::vector<Vec3>& positions, std::vector<Vec3>& colours) override {
    settle();
    run_phase(name_, "render arrays", [&] {
      DeviceVector<Vec3> pos(d_.size()), col(d_.size());
      write_render(constants(), d_.view(), n(), thrust::raw_pointer_cast(pos.data()), thrust::raw_pointer_cast(col.data()), r);
      positions.resize(d_.size());
      colours.resize(d_.size());
      thrust::copy(pos.begin(), pos.end(), positions.begin());
      thrust::copy(col.begin(), col.end(), colours.begin());
    });
    return true;
  }

#if defined(SPH_DEVICE_GL_INTEROP)
  bool write_gl_buffers(const GlBuffers& b, std::string& why) override {
    settle();
    if (d_.size() > b.capacity) throw std::runtime_error("interop buffers hold fewer particles than the simulation");
    if (!gl_.attach(b, why)) return false;
    run_phase(name_, "interop", [&] {
      GlMapping mapped(gl_.resources());
      write_render(constants(), d_.view(), n(), mapped.buffer(0, d_.size()), mapped.buffer(1, d_.size()), b.colouring);
      mapped.unmap();  // before OpenGL draws from them
    });
    return true;
  }
  void release_gl_buffers() override { gl_.release(); }
#endif

  void initialise_forces() override {
    settle();
    diag_current_ = false;
    run_phase(name_, "initial forces", [&] {
      Exec x{*this};
      initialise_solver(x);
    });
  }

  void step(float dt) override {
    settle();
    for (const Phase p : step_phases(c_.solver)) run_step_phase(p, dt);
    ++times_.steps;
    end_of_work();
  }

  // One phase alone (tests), with the step's end: its summary (cuda) or fresh diagnostics (host).
  void step_phase(Phase p, float dt) override {
    if (!step_phases(c_.solver).contains(p))
      throw std::invalid_argument(name_ + ": " + phase_name(p) + " is not a phase of a step of this solver");
    settle();
    run_step_phase(p, dt);
    end_of_work();
  }

  // Emission is host work and synchronous copies: timed with the host clock on both builds. The new
  // particles' diagnostics are taken here, on the host, when the step's are known (cuda), so that
  // diagnose() needs no second reduction: the combination is exact (maxima and least indices).
  void emit(const std::vector<Spawn>& spawns) override {
    settle();
    const auto t0 = std::chrono::steady_clock::now();
    run_phase(name_, phase_name(Phase::Emit), [&] {
      ParticleState extra;
      for (const Spawn& s : spawns) extra.append(s);
      check_memory_for(d_.size() + extra.size());
      if (diag_current_) spawn_diag_ = DiagCombineFn{}(spawn_diag_, diagnostics_of(extra, n()));
      d_.append(extra);
    });
    times_.seconds[std::size_t(Phase::Emit)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  const ParticleState& download() override {
    settle();
    run_phase(name_, "download", [&] { d_.download(host_); });
    return host_;
  }

  // After a step on cuda: the step's reduction, read at its end. Otherwise one reduction now.
  Diagnostics diagnose() override {
    settle();
    if (!diag_current_) {
      run_phase(name_, "diagnostics", [&] { enqueue_summary(nullptr); }, false);
      settle();
    }
    const Diag r = DiagCombineFn{}(result_.diag, spawn_diag_);
    Diagnostics out;
    out.max_speed = r.max_speed;
    out.fastest = r.fastest;
    out.max_accel = r.max_accel;
    out.non_finite = r.non_finite;
    return out;
  }

 private:
  int32_t n() const { return int32_t(d_.size()); }
  GridView grid_view() const {
    return grid_.view(c_.grid, boundary_.view(), body_views_.empty() ? nullptr : thrust::raw_pointer_cast(body_views_.data()),
                      int32_t(body_views_.size()));
  }
  // The bodies' views (their poses this step, their particles in device memory) to the device.
  void upload_bodies() {
    std::vector<BodyView> views(bodies_.size());
    for (std::size_t k = 0; k < bodies_.size(); ++k) views[k] = bodies_[k].view(body_locals_[k].view(), c_.kernel.h);
    body_views_.assign(views.begin(), views.end());
  }

  // The constants as the kernels read them, uploaded first if another back end bound them last.
  ConstantsRef constants() { return constants_.bind(c_); }

  // Refuses, with a message naming the limit, a particle count the device memory cannot hold.
  void check_memory_for(std::size_t particles) const {
    // the grid, keep_ and keep_flag_
    constexpr std::size_t kIndexBytes = DeviceGrid::kBytesPerParticle + sizeof(int32_t) + sizeof(uint8_t);
    const std::size_t per_particle = DeviceArrays::kBytesPerParticle + kIndexBytes;
    check_device_memory(particles, per_particle, 0, d_.size() * per_particle);
  }

  // A phase of the step: enqueued (cuda; checked for launch errors, waited for only with SPH_DEVICE_SYNC=1)
  // or run (host), between the two marks of its timer.
  template <class F>
  void timed(Phase p, F&& f) {
    clock_.start(p, times_);
    run_phase(name_, phase_name(p), f, false);
    clock_.stop(p, times_);
    last_phase_ = phase_name(p);
  }

  StepSummary* summary() { return thrust::raw_pointer_cast(summary_.data()); }

  // The diagnostics of host particles that will sit at index offset on.
  static Diag diagnostics_of(ParticleState& ps, int32_t offset) {
    const ParticleView v = ps.view();
    Diag r = Diag::none();
    for (int32_t k = 0; k < v.n; ++k) {
      Diag d = DiagOfFn{v, nullptr}(k);
      if (d.fastest >= 0) d.fastest += offset;
      if (d.non_finite >= 0) d.non_finite += offset;
      r = DiagCombineFn{}(r, d);
    }
    return r;
  }

  // Enqueues the diagnostics of the particles (before *kept when kept is set) into the device's summary,
  // and the summary's copy to the host; settle() reads it.
  void enqueue_summary(const int32_t* kept) {
    StepSummary* s = summary();
#if defined(__CUDACC__)
    const auto diag_in = thrust::make_transform_iterator(thrust::counting_iterator<int32_t>(0), DiagOfFn{d_.view(), kept});
    cub_temporaries(temporary_, [&](void* t, std::size_t& bytes) {
      return cub::DeviceReduce::Reduce(t, bytes, diag_in, &s->diag, n(), DiagCombineFn{}, Diag::none(), kStream);
    });
#else
    s->diag = thrust::transform_reduce(with_temporaries(temporary_), thrust::counting_iterator<int32_t>(0),
                                       thrust::counting_iterator<int32_t>(n()), DiagOfFn{d_.view(), kept},
                                       Diag::none(), DiagCombineFn{});
#endif
    readback_.read_from(s);
    pending_ = true;
    last_phase_ = "diagnostics";
    diag_current_ = true;
    spawn_diag_ = Diag::none();
  }

  // Waits for the enqueued step (the one synchronisation of a step, naming the step if a kernel faulted),
  // then takes its summary and phase times. Const because size() needs the count a recycling step left.
  void await_step() const {
    if (!pending_) return;
    pending_ = false;
    wait_for_step(name_, last_phase_);
    clock_.collect(times_);
    result_ = readback_.value();
    if (recycled_) trim_to_ = result_.kept;
    recycled_ = false;
  }
  // await_step(), then drops the particles a recycling step left behind the kept ones.
  void settle() {
    await_step();
    if (trim_to_ < 0) return;
    if (std::size_t(trim_to_) < d_.size()) run_phase(name_, "recycle", [&] { d_.resize(std::size_t(trim_to_)); }, false);
    trim_to_ = -1;
  }

  // The device back end's execution interface (src/solvers/execution.h): every loop a kernel on the
  // step's stream (cuda) or an OpenMP loop (host), src/cuda/device_launch.h.
  struct Exec {
    using Constants = ConstantsRef;
    DeviceBackend& b;
    Constants constants() { return b.constants(); }
    const SimConstants& host_constants() const { return b.c_; }
    ParticleView particles() { return b.d_.view(); }
    GridView grid() const { return b.grid_view(); }
    SpringView springs() { return b.springs_.view(); }
    template <class F>
    void for_each(const F& f) {
      launch(b.n(), f);
    }
    template <class F>
    void for_index(int32_t n, const F& f) {
      launch(n, f);
    }
    void* scratch(std::size_t bytes) {
      const std::size_t words = (bytes + 7) / 8;
      if (b.scratch_.size() < words) b.scratch_.resize(words);
      return thrust::raw_pointer_cast(b.scratch_.data());
    }
    void build_grid() { b.build_grid(); }
    void recycle() { b.recycle(); }
    std::vector<RigidBody>& bodies() { return b.bodies_; }
    void upload_bodies() { b.upload_bodies(); }
    // The deterministic sum of reduction.h, a loop per level; its result is read to the host (on cuda a
    // copy that waits for the work enqueued before it: the iterative solvers' one read per check).
    template <class F>
    double sum(int32_t n, const F& f) {
      const std::size_t groups = std::size_t(reduce_groups(n));
      if (b.reduce_a_.size() < groups) b.reduce_a_.resize(groups);
      if (b.reduce_b_.size() < groups) b.reduce_b_.resize(groups);
      const double* r = reduce_sum_into(n, f, thrust::raw_pointer_cast(b.reduce_a_.data()),
                                        thrust::raw_pointer_cast(b.reduce_b_.data()),
                                        [](int32_t count, const auto& g) { launch(count, g); });
      if (r == nullptr) return 0.0;
      double value = 0.0;
#if defined(__CUDACC__)
      CUDA_CHECK(cudaMemcpy(&value, r, sizeof(double), cudaMemcpyDeviceToHost));
#else
      value = *r;
#endif
      ++device_counters().reads;
      return value;
    }
  };

  // The solver's phase p (src/solvers/step.h), timed.
  void run_step_phase(Phase p, float dt) {
    Exec x{*this};
    timed(p, [&] { run_solver_phase(x, p, dt, stats_); });
  }

  // After enqueued work that moved the particles: the summary (diagnostics, the kept count after recycling
  // on cuda, the block count) and its one copy to the host.
  void end_of_work() {
    run_phase(name_, "diagnostics", [&] { enqueue_summary(recycled_ ? &summary()->kept : nullptr); }, false);
  }

  // Sort by (cell key, id) and build the block tables (device_grid.h), moving every array into that order;
  // then the neighbour loops' position and mass records in that order; the tables' capacity follows the
  // block count of the summary read last.
  void build_grid() {
    grid_.build(c_, d_, sorted_, with_temporaries(temporary_), &summary()->blocks, result_.blocks);
    d_.take_derived(sorted_);  // the reorder and the compaction carry only the fields the loops derive theirs from
    d_.fit_derived(needs_solver_fields(c_));
    launch(n(), PackPositionFn{constants(), d_.view()});
  }

  // Keeps the particles that have not expired, in order (a stable compaction: deterministic). Skipped when
  // none can expire. On cuda the kept count stays on the device: every particle slot is gathered (the
  // threads past the count do nothing) and settle() drops the rest when the step's summary is read.
  void recycle() {
    const int32_t count = n();
    if (count == 0 || !can_expire_) return;
    keep_.resize(std::size_t(count));
    keep_flag_.resize(std::size_t(count));
    launch(count, KeepFn{constants(), d_.view(), thrust::raw_pointer_cast(keep_flag_.data())});
#if defined(__CUDACC__)
    int32_t* kept = &summary()->kept;
    cub_temporaries(temporary_, [&](void* t, std::size_t& bytes) {
      return cub::DeviceSelect::Flagged(t, bytes, thrust::counting_iterator<int32_t>(0), keep_flag_.data().get(),
                                        keep_.data().get(), kept, count, kStream);
    });
    sorted_.resize(std::size_t(count));
    launch(count, GatherFn{d_.view(), sorted_.view(), thrust::raw_pointer_cast(keep_.data()), kept});
    std::swap(d_, sorted_);
    d_.take_derived(sorted_);
    recycled_ = true;
#else
    const auto end = thrust::copy_if(with_temporaries(temporary_), thrust::counting_iterator<int32_t>(0),
                                     thrust::counting_iterator<int32_t>(count), keep_flag_.begin(), keep_.begin(), IsSetFn{});
    const std::ptrdiff_t kept = end - keep_.begin();
    if (kept == count) return;
    keep_.resize(std::size_t(kept));
    sorted_.gather_from(d_, keep_);
    std::swap(d_, sorted_);
    d_.take_derived(sorted_);
#endif
  }

  SimConstants c_;
  bool can_expire_;  // particles_can_expire(c_)
  ConstantsOwner constants_;
  std::string name_;
  DeviceArrays d_, sorted_;
  QuietTemporaryAllocator temporary_;
  DeviceGrid grid_;
  DeviceBoundary boundary_;  // static boundary particles (sph.walls = "particles")
  DeviceSprings springs_;    // viscoelastic springs (springs.h), by particle id
  std::vector<RigidBody> bodies_;             // the rigid bodies' host state
  std::vector<DeviceBoundary> body_locals_;   // their particles in device memory
  DeviceVector<BodyView> body_views_;         // their views this step
  DeviceVector<int32_t> keep_;
  DeviceVector<uint8_t> keep_flag_;
  DeviceVector<double> reduce_a_, reduce_b_;  // the levels of a reduction (src/solvers/reduction.h)
  DeviceVector<unsigned long long> scratch_;  // Exec::scratch (PBF's coarse grid)
  SolverStats stats_;
  ParticleState host_;

  // The step's end: the summary on the device and its copy on the host. Mutable: size() and phase_times()
  // are const but may have to wait for the step that was enqueued last.
  DeviceVector<StepSummary> summary_;
  PinnedReadback<StepSummary> readback_;
  mutable StepSummary result_{Diag::none(), 0, 0};  // the summary read last
  mutable bool pending_ = false;                 // a summary is enqueued and not read yet
  mutable bool recycled_ = false;                // the pending step recycled: its count is in the summary
  mutable int64_t trim_to_ = -1;                 // particles to keep once settled, -1: all
  const char* last_phase_ = "";                  // the last phase enqueued, for the fault message
  bool diag_current_ = false;                    // result_.diag is of the particles now, with spawn_diag_
  Diag spawn_diag_ = Diag::none();               // of the particles emitted since the summary was taken
  mutable PhaseClock clock_;
  mutable PhaseTimes times_;
#if defined(SPH_DEVICE_GL_INTEROP)
  GlInterop gl_;  // registered OpenGL buffers, unregistered by its destructor
#endif
};

}  // namespace SPH_DEVICE_NS

std::unique_ptr<Backend> SPH_DEVICE_FACTORY(const SimConstants& constants) {
  SPH_DEVICE_PREPARE();
  return std::make_unique<SPH_DEVICE_NS::DeviceBackend>(constants, SPH_DEVICE_NAME);
}

}  // namespace sph
