// The device back end: the phases of a step as data-parallel loops over particle or cell indices
// (device_launch.h), the physics from src/common/, the grid by atomic binning. One source, two builds (see
// device_backend.h): SPH_DEVICE_NS and the factory name are set by the including build.
//
// The simulation constants are read from one copy (device_constants.h): the GPU's constant memory under
// nvcc; the functors carry only views, scalars and a ConstantsRef.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <cuda/atomic>
#include <thrust/count.h>
#include <thrust/copy.h>
#include <thrust/execution_policy.h>
#include <thrust/fill.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/scan.h>
#include <thrust/transform_reduce.h>

#include "../common/boundaries.h"
#include "../common/density.h"
#include "../common/forces.h"
#include "../common/grid.h"
#include "../common/integrate.h"
#include "../common/pressure.h"
#include "../render/colour_map.h"
#include "device_arrays.h"
#include "device_constants.h"
#include "device_faults.h"
#include "device_launch.h"
#include "device_backend.h"

namespace sph {
namespace SPH_DEVICE_NS {

// ---- phase functors: each calls the shared per-particle code --------------------------------------------

struct PredictFn {
  ConstantsRef c;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { predict_particle(*c, p, i, dt); }
};

// Grid binning: each particle's cell, and its slot in the cell by an atomic increment of the cell count.
struct BinFn {
  GridGeometry g;
  const Vec3* pos;
  int32_t* cell_count;
  int32_t* particle_cell;
  int32_t* particle_slot;
  SPH_HD void operator()(int32_t i) const {
    const int32_t cell = cell_index(g, pos[i]);
    particle_cell[i] = cell;
    cuda::atomic_ref<int32_t, cuda::thread_scope_device> count(cell_count[cell]);
    particle_slot[i] = count.fetch_add(1, cuda::memory_order_relaxed);
  }
};

// Scatter: particle i goes to its cell's first index plus its slot.
struct ScatterFn {
  const int32_t* cell_start;
  const int32_t* particle_cell;
  const int32_t* particle_slot;
  int32_t* order;
  SPH_HD void operator()(int32_t i) const { order[cell_start[particle_cell[i]] + particle_slot[i]] = i; }
};

// The slot order inside a cell depends on atomic timing: sort each cell by particle id (deterministic).
struct SortCellFn {
  const int32_t* cell_start;
  const int32_t* id;
  int32_t* order;
  SPH_HD void operator()(int32_t cell) const {
    const int32_t begin = cell_start[cell], end = cell_start[cell + 1];
    if (end - begin > 1) sort_cell_by_id(order, begin, end, id);
  }
};

// Occupancy targets of issue 11 (kBlocksPerSm, see launch): density 64 registers (4 blocks of 256 per
// SM), forces 80 (3 blocks). Ignored by the host build.
struct DensityFn {
  static constexpr int kBlocksPerSm = 4;
  ConstantsRef c;
  GridView g;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { density_of(*c, g, p, i, dt); }
};

struct PressureFn {
  ConstantsRef c;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { pressure_of(*c, p, i); }
};

template <class Model>  // a ForceModel (forces.h)
struct ForcesFn {
  static constexpr int kBlocksPerSm = 3;
  ConstantsRef c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { forces_with<Model>(*c, g, p, i); }
};

struct CorrectFn {
  ConstantsRef c;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { correct_particle(*c, p, i, dt); }
};

struct BoundariesFn {
  ConstantsRef c;
  ParticleView p;
  float dt;
  SPH_KERNEL_FN void operator()(int32_t i) const { boundaries_of(*c, p, i, dt); }
};

struct CopyVelocityFn {
  ParticleView p;
  SPH_HD void operator()(int32_t i) const { p.vel_force[i] = p.vel[i]; }
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

// Diagnostics as a deterministic reduction: ties go to the lower index, as in the serial reference.
struct Diag {
  float max_speed;
  int32_t fastest;
  float max_accel;
  int32_t non_finite;
};

struct DiagOfFn {
  ParticleView p;
  SPH_HD Diag operator()(int32_t i) const {
    const Vec3 x = p.pos[i], v = p.vel[i];
    const float sum = x.x + x.y + x.z + v.x + v.y + v.z;
    const bool finite = sum - sum == 0.0f;  // false for NaN and infinities
    return Diag{finite ? length(v) : 0.0f, finite ? i : -1, finite ? length(p.acc[i]) : 0.0f, finite ? -1 : i};
  }
};

struct DiagCombineFn {
  SPH_HD Diag operator()(const Diag& a, const Diag& b) const {
    Diag r;
    const bool take_a = a.fastest >= 0 && (b.fastest < 0 || a.max_speed > b.max_speed ||
                                            (a.max_speed == b.max_speed && a.fastest < b.fastest));
    r.max_speed = take_a ? a.max_speed : b.max_speed;
    r.fastest = take_a ? a.fastest : b.fastest;
    r.max_accel = a.max_accel > b.max_accel ? a.max_accel : b.max_accel;
    r.non_finite = a.non_finite < 0 ? b.non_finite : (b.non_finite < 0 || a.non_finite < b.non_finite ? a.non_finite : b.non_finite);
    return r;
  }
};

// Interop: positions and colours written by a kernel into mapped OpenGL buffers (the same colour maps as
// the host path, src/render/colour_map.h).
struct WriteRenderFn {
  ConstantsRef c;
  ParticleView p;
  Vec3* positions;
  Vec3* colours;
  int mode;
  float lo, hi;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    positions[i] = p.pos[i];
    const Vec3 col = render::particle_colour(render::ColourMode(mode), lo, hi, length(p.vel[i]), p.density[i],
                                             (*c).fluids[p.fluid[i]].rest_density, p.pressure[i], p.fluid[i],
                                             cell_index((*c).grid, p.pos[i]));
    colours[i] = col;
  }
};

// ---- the back end -----------------------------------------------------------------------------------------

class DeviceBackend final : public Backend {
 public:
  DeviceBackend(const SimConstants& constants, std::string name) : c_(constants), name_(std::move(name)) {}

  std::string name() const override { return name_; }
  void upload(const ParticleState& state) override {
    run_phase(name_, "upload", [&] {
      check_memory_for(state.size());
      d_.upload(state);
    });
  }
  std::size_t size() const override { return d_.size(); }
  const PhaseTimes& phase_times() const override { return times_; }
  void set_constants(const SimConstants& constants) override {
    c_ = constants;
    constants_.changed();
  }

#if defined(SPH_DEVICE_GL_INTEROP)
  ~DeviceBackend() override { unregister_gl(); }

  bool write_gl_buffers(const GlBuffers& b) override {
    if (std::size_t(n()) > b.capacity) throw std::runtime_error("interop buffers hold fewer particles than the simulation");
    if (b.generation != gl_generation_ || !gl_registered_) {
      unregister_gl();
      CUDA_CHECK(cudaGraphicsGLRegisterBuffer(&gl_[0], b.position_vbo, cudaGraphicsRegisterFlagsWriteDiscard));
      CUDA_CHECK(cudaGraphicsGLRegisterBuffer(&gl_[1], b.colour_vbo, cudaGraphicsRegisterFlagsWriteDiscard));
      gl_registered_ = true;
      gl_generation_ = b.generation;
    }
    CUDA_CHECK(cudaGraphicsMapResources(2, gl_, 0));
    void* pos = nullptr;
    void* col = nullptr;
    std::size_t bytes_pos = 0, bytes_col = 0;
    CUDA_CHECK(cudaGraphicsResourceGetMappedPointer(&pos, &bytes_pos, gl_[0]));
    CUDA_CHECK(cudaGraphicsResourceGetMappedPointer(&col, &bytes_col, gl_[1]));
    launch(n(), WriteRenderFn{constants(), d_.view(), static_cast<Vec3*>(pos), static_cast<Vec3*>(col), b.colour_mode, b.lo, b.hi});
    CUDA_CHECK(cudaGraphicsUnmapResources(2, gl_, 0));  // before OpenGL draws from them
    return true;
  }

 private:
  void unregister_gl() {
    if (!gl_registered_) return;
    cudaGraphicsUnregisterResource(gl_[0]);  // no throw from a destructor path
    cudaGraphicsUnregisterResource(gl_[1]);
    gl_registered_ = false;
  }
  cudaGraphicsResource_t gl_[2] = {nullptr, nullptr};
  bool gl_registered_ = false;
  uint32_t gl_generation_ = 0;

 public:
#endif

  void initialise_forces() override {
    run_phase(name_, "initial forces", [&] {
      launch(n(), CopyVelocityFn{d_.view()});
      build_grid();
      density(0.0f);
      pressure();
      forces();
    });
  }

  void step(float dt) override {
    timed(Phase::Predict, [&] { launch(n(), PredictFn{constants(), d_.view(), dt}); });
    timed(Phase::BuildGrid, [&] { build_grid(); });
    timed(Phase::Density, [&] { density(dt); });
    timed(Phase::Pressure, [&] { pressure(); });
    timed(Phase::Forces, [&] { forces(); });
    timed(Phase::Correct, [&] { launch(n(), CorrectFn{constants(), d_.view(), dt}); });
    timed(Phase::Boundaries, [&] {
      if (c_.num_shapes > 0) launch(n(), BoundariesFn{constants(), d_.view(), dt});
    });
    timed(Phase::Recycle, [&] { recycle(); });
    ++times_.steps;
  }

  void emit(const std::vector<Spawn>& spawns) override {
    timed(Phase::Emit, [&] {
      ParticleState extra;
      for (const Spawn& s : spawns) extra.append(s);
      check_memory_for(d_.size() + extra.size());
      d_.append(extra);
    });
  }

  const ParticleState& download() override {
    run_phase(name_, "download", [&] { d_.download(host_); });
    return host_;
  }

  Diagnostics diagnose() override {
    Diagnostics out;
    if (n() == 0) return out;
    Diag r{};
    run_phase(name_, "diagnostics", [&] {
      r = thrust::transform_reduce(with_temporaries(temporary_), thrust::counting_iterator<int32_t>(0), thrust::counting_iterator<int32_t>(n()),
                                   DiagOfFn{d_.view()}, Diag{0.0f, -1, 0.0f, -1}, DiagCombineFn{});
    });
    out.max_speed = r.max_speed;
    out.fastest = r.fastest;
    out.max_accel = r.max_accel;
    out.non_finite = r.non_finite;
    return out;
  }

 private:
  int32_t n() const { return int32_t(d_.size()); }
  int32_t ncells() const { return int32_t(cell_count(c_.grid)); }
  GridView grid_view() const { return GridView{c_.grid, thrust::raw_pointer_cast(cell_start_.data())}; }

  // The constants as the kernels read them, uploaded first if another back end bound them last.
  ConstantsRef constants() { return constants_.bind(c_); }

  // Refuses, with a message naming the limit, a particle count the device memory cannot hold.
  void check_memory_for(std::size_t particles) const {
    // particle_cell_, particle_slot_, order_, keep_ and keep_flag_
    constexpr std::size_t kIndexBytes = 4 * sizeof(int32_t) + sizeof(uint8_t);
    const std::size_t per_particle = DeviceArrays::kBytesPerParticle + kIndexBytes;
    check_device_memory(particles, per_particle, 2 * sizeof(int32_t) * (std::size_t(ncells()) + 1),
                        d_.size() * per_particle);
  }

  template <class F>
  void timed(Phase p, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    run_phase(name_, phase_name(p), f);
    times_.seconds[std::size_t(p)] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  // Count per cell with atomics, exclusive scan, scatter, sort each cell by id, reorder every array.
  void build_grid() {
    const int32_t count = n();
    cell_count_.assign(std::size_t(ncells()) + 1, 0);
    particle_cell_.resize(std::size_t(count));
    particle_slot_.resize(std::size_t(count));
    order_.resize(std::size_t(count));
    launch(count, BinFn{c_.grid, thrust::raw_pointer_cast(d_.pos.data()), thrust::raw_pointer_cast(cell_count_.data()),
                        thrust::raw_pointer_cast(particle_cell_.data()), thrust::raw_pointer_cast(particle_slot_.data())});
    cell_start_.resize(cell_count_.size());
    thrust::exclusive_scan(with_temporaries(temporary_), cell_count_.begin(), cell_count_.end(), cell_start_.begin());
    launch(count, ScatterFn{thrust::raw_pointer_cast(cell_start_.data()), thrust::raw_pointer_cast(particle_cell_.data()),
                            thrust::raw_pointer_cast(particle_slot_.data()), thrust::raw_pointer_cast(order_.data())});
    launch(ncells(), SortCellFn{thrust::raw_pointer_cast(cell_start_.data()), thrust::raw_pointer_cast(d_.id.data()),
                                thrust::raw_pointer_cast(order_.data())});
    sorted_.gather_from(d_, order_);
    std::swap(d_, sorted_);
  }

  void density(float dt) { launch(n(), DensityFn{constants(), grid_view(), d_.view(), dt}); }
  void pressure() {
    d_.fit_derived();  // the reorder and the compaction carry only the fields the pressure phase reads
    launch(n(), PressureFn{constants(), d_.view()});
  }
  void forces() {
    with_force_model(c_, [&](auto model) { launch(n(), ForcesFn<decltype(model)>{constants(), grid_view(), d_.view()}); });
  }

  // Keeps the particles that have not expired, in order (a stable compaction: deterministic).
  void recycle() {
    const int32_t count = n();
    if (count == 0) return;
    keep_.resize(std::size_t(count));
    keep_flag_.resize(std::size_t(count));
    launch(count, KeepFn{constants(), d_.view(), thrust::raw_pointer_cast(keep_flag_.data())});
    const auto end = thrust::copy_if(with_temporaries(temporary_), thrust::counting_iterator<int32_t>(0),
                                     thrust::counting_iterator<int32_t>(count), keep_flag_.begin(), keep_.begin(), IsSetFn{});
    const std::ptrdiff_t kept = end - keep_.begin();
    if (kept == count) return;
    keep_.resize(std::size_t(kept));
    sorted_.gather_from(d_, keep_);
    std::swap(d_, sorted_);
  }

  SimConstants c_;
  ConstantsOwner constants_;
  std::string name_;
  DeviceArrays d_, sorted_;
  QuietTemporaryAllocator temporary_;
  DeviceVector<int32_t> cell_count_, cell_start_, particle_cell_, particle_slot_, order_, keep_;
  DeviceVector<uint8_t> keep_flag_;
  ParticleState host_;
  PhaseTimes times_;
};

}  // namespace SPH_DEVICE_NS

std::unique_ptr<Backend> SPH_DEVICE_FACTORY(const SimConstants& constants) {
  SPH_DEVICE_PREPARE();
  return std::make_unique<SPH_DEVICE_NS::DeviceBackend>(constants, SPH_DEVICE_NAME);
}

}  // namespace sph
