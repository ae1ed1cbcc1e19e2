// PBF's coarse-grid correction (pbf.coarse_grid; the formulas and why: src/common/pbf_coarse.h): its loops in
// order over the execution interface (execution.h), called by the constraint solve (pbf.h) once a step,
// after the first density:
//   clear the cells and mark the solid ones; deposit every particle's volume, mass and compression (fixed
//   point, atomic: any order gives the same bits); classify the others (fluid, air) and set b; conjugate
//   gradients on A p = b (two deterministic sums an iteration, reduction.h) until |r| <= kCoarseTolerance |b|
//   or pbf.coarse_iterations (the run's summary reports the steps that stop there);
//   every particle's displacement u = grad p / rho into delta_pos, which pbf.h applies as a Jacobi iteration's
//   correction (then the shapes, the walls' spacing, the boundary particles).
#pragma once

#include <cstdint>

#include "../common/pbf_coarse.h"
#include "../common/sph_hd.h"
#include "reduction.h"

namespace sph {
namespace pbf {

// The conjugate-gradient solve stops once the residual's norm is this share of b's.
constexpr double kCoarseTolerance = 1e-2;

template <class C>
struct CoarseClearFn {
  C c;
  CoarseView v;
  SPH_KERNEL_FN void operator()(int32_t q) const { coarse_clear(*c, v, q); }
};

template <class C>
struct CoarseDepositFn {
  C c;
  CoarseView v;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { coarse_deposit(*c, v, p, i); }
};

struct CoarseClassifyFn {
  CoarseView v;
  SPH_HD void operator()(int32_t q) const { coarse_classify(v, q); }
};

struct CoarseApplyFn {  // a_dir = A dir
  CoarseView v;
  SPH_HD void operator()(int32_t q) const { v.a_dir[q] = coarse_apply(v, v.dir, q); }
};

struct CoarseStepFn {  // p += alpha dir, r -= alpha A dir
  CoarseView v;
  float alpha;
  SPH_HD void operator()(int32_t q) const {
    v.pressure[q] += alpha * v.dir[q];
    v.r[q] -= alpha * v.a_dir[q];
  }
};

struct CoarseDirectionFn {  // dir = r + beta dir
  CoarseView v;
  float beta;
  SPH_HD void operator()(int32_t q) const { v.dir[q] = v.r[q] + beta * v.dir[q]; }
};

struct CoarseOpenOf {
  CoarseView v;
  SPH_HD double operator()(int32_t q) const { return double(coarse_open(v, q)); }
};

struct CoarseFluidOf {
  CoarseView v;
  SPH_HD double operator()(int32_t q) const { return v.flag[q] == kCoarseFluid ? 1.0 : 0.0; }
};

struct CoarseShiftFn {  // b += shift on fluid cells (r and dir hold b)
  CoarseView v;
  float shift;
  SPH_HD void operator()(int32_t q) const {
    if (v.flag[q] != kCoarseFluid) return;
    v.r[q] += shift;
    v.dir[q] = v.r[q];
  }
};

// a[q] b[q] in double: the solve's inner products (Exec::sum).
struct ProductOf {
  const float* a;
  const float* b;
  SPH_HD double operator()(int32_t q) const { return double(a[q]) * double(b[q]); }
};

// delta_pos = u(x), the displacement (the move is ApplyCorrectionFn's, pbf.h: it adds delta_pos and
// collides with the shapes; in one loop with this one, the shapes' arrays took a 48-byte stack frame on sm_90).
struct CoarseDisplacementFn {
  CoarseView v;
  ParticleView p;
  SPH_HD void operator()(int32_t i) const {
    p.delta_pos[i] = p.age[i] < 0.0f ? Vec3{0.0f, 0.0f, 0.0f} : coarse_displacement(v, p.pos[i]);
  }
};

// One coarse-grid solve from the compression p.solver_error (store_density): the displacement of every
// particle into p.delta_pos. Returns the conjugate-gradient iterations made; capped: it stopped at
// pbf.coarse_iterations above its tolerance.
template <class Exec>
int32_t coarse_correction(Exec& x, bool& capped) {
  using C = typename Exec::Constants;
  const SimConstants& c = x.host_constants();
  const CoarseGrid g = coarse_grid_of(c.grid);
  const int32_t cells = int32_t(coarse_cell_count(g));
  const CoarseView v = coarse_view(g, x.scratch(coarse_view_bytes(cells)));
  x.for_index(cells, CoarseClearFn<C>{x.constants(), v});
  x.for_each(CoarseDepositFn<C>{x.constants(), v, x.particles()});
  x.for_index(cells, CoarseClassifyFn{v});
  if (x.sum(cells, CoarseOpenOf{v}) == 0.0) {
    // A fluid that touches no air (a closed box filled to its lid) cannot expand: b less its mean over the
    // fluid cells, so that the solve only evens the compression out (without this, the constant part of p
    // grew without bound and its rounding moved the particles: a full box blew up within 3 steps).
    const double fluid = x.sum(cells, CoarseFluidOf{v});
    if (fluid > 0.0) x.for_index(cells, CoarseShiftFn{v, float(-x.sum(cells, ValuesOf<float>{v.r}) / fluid)});
  }
  double rr = x.sum(cells, ProductOf{v.r, v.r});
  const double stop = rr * kCoarseTolerance * kCoarseTolerance;
  int32_t k = 0;
  for (; k < c.pbf.coarse_iterations && rr > stop && rr > 0.0; ++k) {
    x.for_index(cells, CoarseApplyFn{v});
    const double curvature = x.sum(cells, ProductOf{v.dir, v.a_dir});
    if (!(curvature > 0.0)) break;  // only a constant left undetermined (a fluid that touches no air)
    x.for_index(cells, CoarseStepFn{v, float(rr / curvature)});
    const double next = x.sum(cells, ProductOf{v.r, v.r});
    x.for_index(cells, CoarseDirectionFn{v, float(next / rr)});
    rr = next;
  }
  capped = rr > stop && k == c.pbf.coarse_iterations;
  x.for_each(CoarseDisplacementFn{v, x.particles()});
  return k;
}

}  // namespace pbf
}  // namespace sph
