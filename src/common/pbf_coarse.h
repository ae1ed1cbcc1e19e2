// PBF's coarse-grid correction (issue 12): the per-cell and per-particle formulas of one projection of the
// particles' compression on a grid of cells h wide, shared by every back end. src/solvers/pbf_coarse.h runs
// them in order (the conjugate-gradient solve between them).
//
// Why: k Jacobi iterations carry a correction about k kernel radii, so under gravity PBF's compression grows
// with depth as (depth / d) g dt^2 / k (docs/results.md, "Why PBF misses 1%": 2.5% on a 20-particle column at
// 4 ms and 4 iterations; a bound of about 1.2% for any iteration that uses neighbours only). A coarse grid
// carries the floor's push up a column in one solve, as the coarse level of a multigrid cycle does, and the
// hierarchy of Mueller's "Hierarchical Position Based Dynamics" (2008) does for cloth. The correction is the
// pressure projection of grid-based solvers (Foster and Fedkiw 2001; Bridson, "Fluid Simulation for Computer
// Graphics", ch. 5) applied to the particles' displacements instead of their velocities:
//   find p with div u = C, u = grad p / rho, on the cells holding fluid; p = 0 in cells of air (the free
//   surface), u . n = 0 through walls (no flux),
// where C is the cell's compressed volume fraction, sum_i w_ic max(C_i, 0) V_i / H^3 (V_i = m_i / rho0_i, w_ic
// trilinear "cloud in cell" weights), so that moving each particle by u expands every cell by the volume it
// is compressed by; as a pressure, p moves a light fluid more than a heavy one beside it, and a free cloud of
// two fluids keeps its momentum (with u = grad p alike for both, a cloud of water and a fluid ten times
// lighter changed its momentum by a fifth of what the solve moved, measured). Discretely (cells of H):
// A p = b with
//   (A p)_c = sum over the six faces f of c that are not walls of beta_f (p_c - p_n), p_n = 0 in air,
//   b_c = -H^2 C_c,
// beta_f = 1 / rho at the face (coarse_face; rho_c = the cell's mass over its volume). A is symmetric positive
// definite wherever the fluid touches air (otherwise only a constant, of zero gradient, is undetermined). A
// particle moves by u = grad p / rho, trilinear between the cells' own (coarse_displacement); the Jacobi
// iterations that follow remove what is left at the particles' scale.
//
// Cells: the neighbour grid's domain (GridGeometry: its origin, and cells of h / 2, two to a coarse cell),
// dense, so the cells' number is known on the host without reading the particles. A cell is solid where the
// scene's shapes keep the fluid out of more than half of it (shape_excludes), fluid where the particles'
// trilinear weights fill at least half of what is left open, air otherwise. Sums over particles are fixed
// point (integers, 2^-32 units) added atomically: integer sums do not depend on the order, so back ends whose
// arithmetic rounds alike (cpu, host) get the same bits. For fluids of one rest density only: the loader
// refuses two (docs/results.md, "PBF's coarse grid", says what the forms tried did between them). A fluid
// that touches no air anywhere has its b evened out (pbf_coarse.h in src/solvers); a sealed pocket beside an
// open fluid is not detected.
#pragma once

#include <cstdint>

#include "boundaries.h"
#include "params.h"
#include "particle_view.h"
#include "sph_hd.h"
#include "vec3.h"

namespace sph {

// The coarse grid: dense over the domain, cells of two neighbour-grid cells (h).
struct CoarseGrid {
  Vec3 origin;  // the domain's lower corner [m]
  float size;   // H [m]
  int32_t nx, ny, nz;
};

// The coarse grid over the neighbour grid's domain.
inline CoarseGrid coarse_grid_of(const GridGeometry& g) {
  return CoarseGrid{g.origin, 2.0f * g.cell_size, (g.nx + 1) / 2, (g.ny + 1) / 2, (g.nz + 1) / 2};
}

inline int64_t coarse_cell_count(const CoarseGrid& g) { return int64_t(g.nx) * g.ny * g.nz; }

enum : int32_t { kCoarseAir = 0, kCoarseFluid = 1, kCoarseSolid = 2 };

// The arrays of one correction (scratch memory of the back end), one entry per cell.
struct CoarseView {
  CoarseGrid g;
  unsigned long long* volume;       // sum w V / H^3, fixed point (kCoarseFixed)
  unsigned long long* mass;         // sum w m / H^3 [kg/m^3], fixed point
  unsigned long long* compression;  // sum w max(C, 0) V / H^3, fixed point
  int32_t* flag;                    // kCoarseAir, kCoarseFluid or kCoarseSolid
  float* open;                      // the share of the cell the shapes leave to the fluid (coarse_clear)
  float* beta;                      // 1 / rho of the cell's fluid [m^3/kg] (0 in a wall or where none is)
  float* pressure;                  // the pressure-like potential p [kg/m]
  float* r;                         // the conjugate-gradient residual b - A p
  float* dir;                       // its search direction
  float* a_dir;                     // A dir
};

// Bytes of scratch memory a CoarseView of `cells` cells takes (coarse_view carves them, 8-byte aligned).
inline std::size_t coarse_view_bytes(int64_t cells) {
  return std::size_t(cells) * (3 * sizeof(unsigned long long) + sizeof(int32_t) + 6 * sizeof(float)) + 64;
}

inline CoarseView coarse_view(const CoarseGrid& g, void* scratch) {
  const std::size_t n = std::size_t(coarse_cell_count(g));
  CoarseView v{};
  v.g = g;
  v.volume = static_cast<unsigned long long*>(scratch);
  v.mass = v.volume + n;
  v.compression = v.mass + n;
  v.beta = reinterpret_cast<float*>(v.compression + n);
  v.open = v.beta + n;
  v.pressure = v.open + n;
  v.r = v.pressure + n;
  v.dir = v.r + n;
  v.a_dir = v.dir + n;
  v.flag = reinterpret_cast<int32_t*>(v.a_dir + n);
  return v;
}

constexpr double kCoarseFixed = 4294967296.0;  // 2^32: the fixed-point unit of the cells' sums

// sum += v in fixed point, atomically (several particles add to a cell at once on host and cuda).
SPH_HD inline void add_fixed(unsigned long long* sum, float v) {
  const unsigned long long q = static_cast<unsigned long long>(static_cast<long long>(double(v) * kCoarseFixed));
#if defined(__CUDA_ARCH__)
  atomicAdd(sum, q);
#else
  __atomic_fetch_add(sum, q, __ATOMIC_RELAXED);
#endif
}

SPH_HD inline float from_fixed(unsigned long long q) { return float(double(static_cast<long long>(q)) / kCoarseFixed); }

// Whether point x lies where shape s keeps the fluid out (boundaries.h's regions): outside a container (a box's
// open top is not a wall), inside an obstacle's solid, behind a plane, where a quadric is negative. An
// absorbing shape is an outflow, not a wall.
SPH_HD inline bool shape_excludes(const Shape& s, Vec3 x) {
  if (s.absorb) return false;
  switch (s.type) {
    case ShapeType::Box: {
      if (s.keep_inside)
        return x.x < s.a.x || x.y < s.a.y || x.z < s.a.z || x.x > s.b.x || x.z > s.b.z || (!s.open_top && x.y > s.b.y);
      float lo[3], hi[3];
      obstacle_solid(s, lo, hi);
      return x.x > lo[0] && x.x < hi[0] && x.y > lo[1] && x.y < hi[1] && x.z > lo[2] && x.z < hi[2];
    }
    case ShapeType::Sphere: {
      const float r2 = length2(x - s.a), R2 = s.radius * s.radius;
      return s.keep_inside ? r2 > R2 : r2 < R2;
    }
    case ShapeType::Plane: return dot(x - s.a, s.b) < 0.0f;
    case ShapeType::Quadric: return quadric_value(s.q, x) < 0.0f;
  }
  return false;
}

// A position's place in the grid, in cells from the first cell's centre: cell (i0, j0, k0) and the
// trilinear weights t towards the next cell along each axis.
struct CoarseStencil {
  int32_t i0, j0, k0;
  float tx, ty, tz;
};

SPH_HD inline CoarseStencil coarse_stencil(const CoarseGrid& g, Vec3 x) {
  const float inv = 1.0f / g.size;
  const float fx = (x.x - g.origin.x) * inv - 0.5f, fy = (x.y - g.origin.y) * inv - 0.5f,
              fz = (x.z - g.origin.z) * inv - 0.5f;
  // Clamped before the conversion (far-away or non-finite positions), as grid.h's cell_coord.
  const float lo = -2.0f, hx = float(g.nx) + 1.0f, hy = float(g.ny) + 1.0f, hz = float(g.nz) + 1.0f;
  const float cx = fminf(fmaxf(floorf(fx), lo), hx), cy = fminf(fmaxf(floorf(fy), lo), hy),
              cz = fminf(fmaxf(floorf(fz), lo), hz);
  CoarseStencil s;
  s.i0 = int32_t(cx), s.j0 = int32_t(cy), s.k0 = int32_t(cz);
  s.tx = fminf(fmaxf(fx - cx, 0.0f), 1.0f), s.ty = fminf(fmaxf(fy - cy, 0.0f), 1.0f), s.tz = fminf(fmaxf(fz - cz, 0.0f), 1.0f);
  return s;
}

SPH_HD inline bool coarse_inside(const CoarseGrid& g, int32_t i, int32_t j, int32_t k) {
  return i >= 0 && j >= 0 && k >= 0 && i < g.nx && j < g.ny && k < g.nz;
}

SPH_HD inline int64_t coarse_index(const CoarseGrid& g, int32_t i, int32_t j, int32_t k) {
  return (int64_t(k) * g.ny + j) * g.nx + i;
}

struct CoarseCell {
  int32_t i, j, k;
};

// Cell q's coordinates (coarse_index's inverse).
SPH_HD inline CoarseCell coarse_cell(const CoarseGrid& g, int64_t q) {
  return CoarseCell{int32_t(q % g.nx), int32_t((q / g.nx) % g.ny), int32_t(q / (int64_t(g.nx) * g.ny))};
}

// Face neighbour n (0 to 5: -x, +x, -y, +y, -z, +z) of cell a.
SPH_HD inline CoarseCell coarse_neighbour(CoarseCell a, int32_t n) {
  const int32_t step = n % 2 == 0 ? -1 : 1;
  return CoarseCell{a.i + (n / 2 == 0 ? step : 0), a.j + (n / 2 == 1 ? step : 0), a.k + (n / 2 == 2 ? step : 0)};
}

// Corner c (0 to 7) of a stencil: its cell and trilinear weight w.
SPH_HD inline CoarseCell coarse_corner(const CoarseStencil& s, int32_t c, float& w) {
  const int32_t di = c & 1, dj = (c >> 1) & 1, dk = c >> 2;
  w = (di ? s.tx : 1.0f - s.tx) * (dj ? s.ty : 1.0f - s.ty) * (dk ? s.tz : 1.0f - s.tz);
  return CoarseCell{s.i0 + di, s.j0 + dj, s.k0 + dk};
}

// Cell q's start: no fluid; the share of it the scene's shapes leave to the fluid (3 x 3 x 3 points, at a
// sixth, half and five sixths of the cell along each axis), and solid where that is less than half.
SPH_HD inline void coarse_clear(const SimConstants& c, const CoarseView& v, int64_t q) {
  const CoarseGrid& g = v.g;
  const CoarseCell cq = coarse_cell(g, q);
  const int32_t i = cq.i, j = cq.j, k = cq.k;
  int32_t open = 0;
  for (int32_t p = 0; p < 27; ++p) {
    const Vec3 x{g.origin.x + (float(i) + float(2 * (p % 3) + 1) / 6.0f) * g.size,
                 g.origin.y + (float(j) + float(2 * ((p / 3) % 3) + 1) / 6.0f) * g.size,
                 g.origin.z + (float(k) + float(2 * (p / 9) + 1) / 6.0f) * g.size};
    bool excluded = false;
    for (int32_t s = 0; s < c.num_shapes; ++s) excluded = excluded || shape_excludes(c.shapes[s], x);
    open += excluded ? 0 : 1;
  }
  v.open[q] = float(open) / 27.0f;
  v.flag[q] = 2 * open < 27 ? kCoarseSolid : kCoarseAir;
  v.volume[q] = 0ull;
  v.mass[q] = 0ull;
  v.compression[q] = 0ull;
}

// Particle i's volume, mass and compressed volume, over H^3, into the eight cells around it (trilinear
// weights; a wall cell's share is lost, so cells along walls read a little less full). Inlet particles (age <
// 0) take no part.
SPH_HD inline void coarse_deposit(const SimConstants& c, const CoarseView& v, const ParticleView& p, int32_t i) {
  if (p.age[i] < 0.0f) return;
  const FluidConstants& f = c.fluids[p.fluid[i]];
  const float H = v.g.size;
  const float share = f.mass / (f.rest_density * H * H * H);  // V_i / H^3
  const float compressed = share * p.solver_error[i];         // max(C_i, 0): PBF's store_density
  const CoarseStencil s = coarse_stencil(v.g, p.pos[i]);
  for (int32_t corner = 0; corner < 8; ++corner) {
    float w;
    const CoarseCell a = coarse_corner(s, corner, w);
    if (!coarse_inside(v.g, a.i, a.j, a.k)) continue;
    const int64_t cell = coarse_index(v.g, a.i, a.j, a.k);
    add_fixed(v.volume + cell, w * share);
    add_fixed(v.mass + cell, w * share * f.rest_density);
    if (compressed > 0.0f) add_fixed(v.compression + cell, w * compressed);
  }
}

// Cell q's kind (fluid where the particles fill at least half of the share the shapes leave open, unless
// solid), its fluid's 1 / rho, and the solve's start: p = 0, r = dir = b. Against the open share, not the whole
// cell: a cell a wall cuts short would otherwise read as air beside the wall, and the projection would push
// the fluid into the wall (a resting column of 11 particles across, whose top wall cuts its cells, moved at up
// to 0.44 m/s, measured).
SPH_HD inline void coarse_classify(const CoarseView& v, int64_t q) {
  const CoarseGrid& g = v.g;
  const float volume = from_fixed(v.volume[q]), mass = from_fixed(v.mass[q]);
  const bool fluid = v.flag[q] != kCoarseSolid && volume >= 0.5f * v.open[q];
  if (v.flag[q] != kCoarseSolid) v.flag[q] = fluid ? kCoarseFluid : kCoarseAir;
  v.beta[q] = v.flag[q] != kCoarseSolid && mass > 0.0f ? volume / mass : 0.0f;
  const float b = fluid ? -(g.size * g.size) * from_fixed(v.compression[q]) : 0.0f;
  v.pressure[q] = 0.0f;
  v.r[q] = b;
  v.dir[q] = b;
}

// The value x takes at cell (a, b, c) in the stencil of a cell whose own value is `own`: x there if it holds
// fluid, 0 in air or outside the grid, `own` behind a wall (the wall's mirror: no flux through it).
SPH_HD inline float coarse_seen(const CoarseView& v, const float* x, int32_t a, int32_t b, int32_t c, float own) {
  if (!coarse_inside(v.g, a, b, c)) return 0.0f;
  const int64_t n = coarse_index(v.g, a, b, c);
  const int32_t f = v.flag[n];
  return f == kCoarseFluid ? x[n] : (f == kCoarseSolid ? own : 0.0f);
}

// 1 for a fluid cell with a face on air (or on the grid's edge): where the fluid can expand. Without any, A
// p = b fixes p only up to a constant, and has a solution only for b of zero sum.
SPH_HD inline float coarse_open(const CoarseView& v, int64_t q) {
  if (v.flag[q] != kCoarseFluid) return 0.0f;
  const CoarseGrid& g = v.g;
  const CoarseCell cq = coarse_cell(g, q);
  for (int32_t m = 0; m < 6; ++m) {
    const CoarseCell n = coarse_neighbour(cq, m);
    if (!coarse_inside(g, n.i, n.j, n.k)) return 1.0f;
    if (v.flag[coarse_index(g, n.i, n.j, n.k)] == kCoarseAir) return 1.0f;
  }
  return 0.0f;
}

// The face's coefficient between fluid cell q and its neighbour (a, b, c): 1 / rho at the face, the inverse of
// the two cells' mean density between two fluid cells, q's own 1 / rho towards air; 0 through a wall (no flux).
SPH_HD inline float coarse_face(const CoarseView& v, int64_t q, int32_t a, int32_t b, int32_t c) {
  if (!coarse_inside(v.g, a, b, c)) return v.beta[q];
  const int64_t n = coarse_index(v.g, a, b, c);
  const int32_t f = v.flag[n];
  if (f == kCoarseSolid) return 0.0f;
  if (f == kCoarseAir) return v.beta[q];
  const float bq = v.beta[q], bn = v.beta[n];
  return bq + bn > 0.0f ? 2.0f * bq * bn / (bq + bn) : 0.0f;
}

// (A x)_q = sum over the six faces of beta_f (x_q - x_n), x_n = 0 in air, for a fluid cell; 0 elsewhere.
SPH_HD inline float coarse_apply(const CoarseView& v, const float* x, int64_t q) {
  if (v.flag[q] != kCoarseFluid) return 0.0f;
  const CoarseCell cq = coarse_cell(v.g, q);
  const float xq = x[q];
  float sum = 0.0f;
  for (int32_t m = 0; m < 6; ++m) {
    const CoarseCell n = coarse_neighbour(cq, m);
    sum += coarse_face(v, q, n.i, n.j, n.k) * (xq - coarse_seen(v, x, n.i, n.j, n.k, xq));
  }
  return sum;
}

// grad p at cell q's centre [kg/m^2]: central differences, p = 0 in air, mirrored behind walls.
SPH_HD inline Vec3 coarse_gradient(const CoarseView& v, int64_t q) {
  const CoarseGrid& g = v.g;
  const CoarseCell cq = coarse_cell(g, q);
  const int32_t i = cq.i, j = cq.j, k = cq.k;
  const float own = v.flag[q] == kCoarseFluid ? v.pressure[q] : 0.0f;
  const float s = 0.5f / g.size;
  const float* x = v.pressure;
  return Vec3{s * (coarse_seen(v, x, i + 1, j, k, own) - coarse_seen(v, x, i - 1, j, k, own)),
              s * (coarse_seen(v, x, i, j + 1, k, own) - coarse_seen(v, x, i, j - 1, k, own)),
              s * (coarse_seen(v, x, i, j, k + 1, own) - coarse_seen(v, x, i, j, k - 1, own))};
}

// The displacement u at x [m]: each surrounding cell's own u_c = grad p / rho_c, trilinear over the cells that
// hold fluid (not solid, some mass), their weights renormalised. Beside a wall the fluid's own u: a wall's zero
// taken into the weights lifted the layer along each wall less than the fluid beside it, every step, and a
// resting column never came to rest. (Tried and not kept, docs/results.md: grad p trilinear divided by the
// particle's own rho0, which lifted a light fluid off the water under it; u on the cells' faces, as a MAC
// grid has it, which held two fluids at rest but set a column's surface sloshing.)
SPH_HD inline Vec3 coarse_displacement(const CoarseView& v, Vec3 x) {
  const CoarseStencil s = coarse_stencil(v.g, x);
  Vec3 u{0.0f, 0.0f, 0.0f};
  float total = 0.0f;
  for (int32_t corner = 0; corner < 8; ++corner) {
    float w;
    const CoarseCell a = coarse_corner(s, corner, w);
    if (!coarse_inside(v.g, a.i, a.j, a.k)) continue;
    const int64_t cell = coarse_index(v.g, a.i, a.j, a.k);
    const float beta = v.beta[cell];
    if (!(beta > 0.0f)) continue;
    u += (w * beta) * coarse_gradient(v, cell);
    total += w;
  }
  return total > 0.0f ? (1.0f / total) * u : u;
}

}  // namespace sph
