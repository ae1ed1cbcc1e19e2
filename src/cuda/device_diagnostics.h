// A device step's diagnostics (the fastest particle, the largest acceleration, the first non-finite one) as
// one deterministic reduction over the particles, and the summary a step leaves for the host's one read
// (device_backend.cu, device_readback.h). Included by device_backend.cu inside its build's namespace.
#pragma once

#include <cstdint>

#include "../common/particle_view.h"

namespace sph {
namespace SPH_DEVICE_NS {

// Diagnostics as a deterministic reduction: ties go to the lower index, as in the serial reference.
struct Diag {
  float max_speed;
  int32_t fastest;
  float max_accel;
  int32_t non_finite;
  SPH_HD static Diag none() { return Diag{0.0f, -1, 0.0f, -1}; }  // of no particle: the reduction's identity
};

struct DiagOfFn {
  ParticleView p;
  const int32_t* kept;  // when set, particles from *kept on were recycled by this step and do not count
  SPH_HD Diag operator()(int32_t i) const {
    if (kept != nullptr && i >= *kept) return Diag::none();
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

// What a step leaves for the host, read in one copy (device_readback.h): the diagnostics, how many
// particles it kept when it recycled on cuda, and how many blocks its grid has (device_grid.h: the tables'
// capacity grows from it).
struct StepSummary {
  Diag diag;
  int32_t kept;
  int32_t blocks;
};

}  // namespace SPH_DEVICE_NS
}  // namespace sph
