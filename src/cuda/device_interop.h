// Drawing from the device back end (issue 11, items 6 and Build 5): the kernel that writes positions and
// colours for the renderer, and, in the cuda build with OpenGL headers (SPH_DEVICE_GL_INTEROP), the
// CUDA-OpenGL interop that lets it write the demo's vertex buffers directly.
//
// Interop degrades instead of dying: when the OpenGL context is not on the back end's CUDA device
// (Mesa/Xvfb, an Optimus laptop's integrated GPU, remote X) or registration fails, attach() says why, once,
// and never retries; the demo then uploads from the host. Order: the caller releases (unregisters) before
// it reallocates or deletes the buffers; a mapping is scoped, so an exception between map and unmap
// still unmaps.
#pragma once

#include <cstdint>
#include <string>

#include "../common/backend.h"
#include "../common/grid.h"
#include "../common/particle_view.h"
#include "../render/colour_map.h"
#include "device_constants.h"
#include "device_launch.h"

#if defined(SPH_DEVICE_GL_INTEROP)
#include "cuda_check.h"
#endif

namespace sph {
namespace SPH_DEVICE_NS {

// Position and colour of particle i, by render::particle_colour: the definition the host upload path uses
// (render/particle_colours.h), so both paths give the same bits (checked by the device test).
struct WriteRenderFn {
  ConstantsRef c;
  ParticleView p;
  Vec3* positions;
  Vec3* colours;
  RenderColouring r;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    positions[i] = p.pos[i];
    colours[i] = render::particle_colour(render::ColourMode(r.colour_mode), r.lo, r.hi, length(p.vel[i]), p.density[i],
                                         (*c).fluids[p.fluid[i]].rest_density, p.pressure[i], p.fluid[i],
                                         cell_index((*c).grid, p.pos[i]));
  }
};

// Writes the first n particles of p into positions[0, n) and colours[0, n): device memory under nvcc (mapped
// OpenGL buffers or a device vector), host memory in the host build. Asynchronous under nvcc.
inline void write_render(ConstantsRef c, const ParticleView& p, int32_t n, Vec3* positions, Vec3* colours,
                         const RenderColouring& r) {
  launch(n, WriteRenderFn{c, p, positions, colours, r});
}

#if defined(SPH_DEVICE_GL_INTEROP)

// The renderer's two vertex buffers (positions, colours) registered with CUDA, owned here: unregistered
// by release() and by the destructor. Every call needs the thread's current OpenGL context to be the one
// that owns the buffers.
class GlInterop {
 public:
  GlInterop() = default;
  GlInterop(const GlInterop&) = delete;
  GlInterop& operator=(const GlInterop&) = delete;
  ~GlInterop() { release(); }

  // Registers b's buffers unless they are registered already (same ids and generation). False, with the
  // reason in `why`, when interop cannot work here; after one failure it returns false at once.
  bool attach(const GlBuffers& b, std::string& why) {
    if (!failure_.empty()) {
      why = failure_;
      return false;
    }
    if (registered_ && b.generation == generation_ && b.position_vbo == vbo_[0] && b.colour_vbo == vbo_[1]) return true;
    release();
    failure_ = context_device_mismatch();
    if (failure_.empty()) failure_ = register_buffers(b);
    why = failure_;
    return failure_.empty();
  }

  // Unregisters the buffers (before OpenGL reallocates or deletes them). Never throws: it runs in
  // destructors, also after a fault.
  void release() {
    if (!registered_) return;
    (void)cudaGraphicsUnregisterResource(resources_[0]);
    (void)cudaGraphicsUnregisterResource(resources_[1]);
    registered_ = false;
  }

  cudaGraphicsResource_t* resources() { return resources_; }

 private:
  // "" when the current OpenGL context runs on this thread's CUDA device (cudaGLGetDevices); otherwise why
  // not. The errors here are not sticky: they are cleared, so no later phase reports them.
  static std::string context_device_mismatch() {
    int mine = 0;
    cudaError_t status = cudaGetDevice(&mine);
    unsigned int count = 0;
    int devices[8] = {};
    if (status == cudaSuccess) status = cudaGLGetDevices(&count, devices, 8, cudaGLDeviceListAll);
    if (status != cudaSuccess) {
      (void)cudaGetLastError();
      return std::string("the OpenGL context is not on a CUDA device (cudaGLGetDevices: ") + cudaGetErrorName(status) + ")";
    }
    if (count == 0) return "the OpenGL context is not on a CUDA device (cudaGLGetDevices found none)";
    for (unsigned int k = 0; k < count && k < 8; ++k)
      if (devices[k] == mine) return "";
    return "the OpenGL context is on CUDA device " + std::to_string(devices[0]) + ", the back end on device " +
           std::to_string(mine);
  }

  std::string register_buffers(const GlBuffers& b) {
    cudaError_t status = cudaGraphicsGLRegisterBuffer(&resources_[0], b.position_vbo, cudaGraphicsRegisterFlagsWriteDiscard);
    if (status == cudaSuccess) {
      status = cudaGraphicsGLRegisterBuffer(&resources_[1], b.colour_vbo, cudaGraphicsRegisterFlagsWriteDiscard);
      if (status != cudaSuccess) (void)cudaGraphicsUnregisterResource(resources_[0]);
    }
    if (status != cudaSuccess) {
      (void)cudaGetLastError();
      return std::string("cudaGraphicsGLRegisterBuffer failed: ") + cudaGetErrorName(status) + " (" +
             cudaGetErrorString(status) + ")";
    }
    registered_ = true;
    generation_ = b.generation;
    vbo_[0] = b.position_vbo;
    vbo_[1] = b.colour_vbo;
    return "";
  }

  cudaGraphicsResource_t resources_[2] = {nullptr, nullptr};
  bool registered_ = false;
  uint32_t generation_ = 0;
  uint32_t vbo_[2] = {0, 0};
  std::string failure_;  // why interop cannot work here; "" while it can
};

// The registered buffers mapped for CUDA while this object lives (RAII): an exception between map and
// unmap still unmaps. unmap() ends the mapping early with its error checked: OpenGL may draw only after.
class GlMapping {
 public:
  explicit GlMapping(cudaGraphicsResource_t* resources) : resources_(resources) {
    CUDA_CHECK(cudaGraphicsMapResources(2, resources_, 0));
    mapped_ = true;
  }
  GlMapping(const GlMapping&) = delete;
  GlMapping& operator=(const GlMapping&) = delete;
  ~GlMapping() {
    if (mapped_) (void)cudaGraphicsUnmapResources(2, resources_, 0);  // unwinding: the first error is reported
  }

  // Buffer k (0: positions, 1: colours) as device memory; throws when it holds fewer than `particles`.
  Vec3* buffer(int k, std::size_t particles) const {
    void* pointer = nullptr;
    std::size_t bytes = 0;
    CUDA_CHECK(cudaGraphicsResourceGetMappedPointer(&pointer, &bytes, resources_[k]));
    if (bytes < particles * sizeof(Vec3))
      throw std::runtime_error("mapped OpenGL buffer " + std::to_string(k) + " holds " + std::to_string(bytes) + " bytes, " +
                               std::to_string(particles) + " particles need " + std::to_string(particles * sizeof(Vec3)));
    return static_cast<Vec3*>(pointer);
  }

  void unmap() {
    mapped_ = false;
    CUDA_CHECK(cudaGraphicsUnmapResources(2, resources_, 0));
  }

 private:
  cudaGraphicsResource_t* resources_;
  bool mapped_ = false;
};

#endif  // SPH_DEVICE_GL_INTEROP

}  // namespace SPH_DEVICE_NS
}  // namespace sph
