// Each particle's neighbours, listed once per step by the grid phase of the CPU builds (cpu and host) and
// read by density, forces and mirror walls (grid.h, for_each_neighbour). The back ends make the lists a
// row of cells at a time (neighbour_rows.h); list_neighbours below lists one particle by searching its
// ranges, where a row cannot be gathered. Two ways to the same list; the back end times both and uses the
// faster (neighbour_list_choice.h):
//   - with a branch per candidate: fast while the particles sit on a lattice, whose pattern the CPU's
//     branch predictor learns;
//   - without a branch, four candidates at a time (GCC vector extensions: SSE on x86-64): once the fluid
//     is disordered "is b within h?" is a coin toss (27% yes), and mispredicted branches had doubled the
//     cost of a dam-break step by its end (issue 11, item 9).
// Both compute r^2 = |x_a - x_b|^2 exactly as the loops do, so the list holds exactly the particles the
// GPU's direct search finds, in the same order.
#pragma once

#include <cstdint>
#include <cstring>

#include "grid.h"
#include "kernels.h"
#include "params.h"

namespace sph {

// The radius the lists (and every loop that reads them) select neighbours by, as a multiple of h: 1, but
// kPbfListReach for PBF, whose iterations move the particles after the grid phase. PBF's loops select their
// pairs by this radius at the grid phase's positions (pos_mass, which PBF leaves as the grid wrote them) and
// then keep those within h at the current positions (src/common/pbf.h, for_each_pbf_pair): the same pairs on
// every back end, lists or search, and the margin keeps the pairs that come within h while the iterations
// move them. With a margin of 0 pairs were missed and a resting column blew up in 0.85 s. At 0.1 h the resting
// column and two_layers keep every bit of 0.2 h's runs (no pair comes in from beyond 1.1 h there); the 16k dam
// break's differ from its eighth step on (a pair entering within h from between 1.1 h and 1.2 h), its surge
// front within 0.25 mm of 0.2 h's over 1 s, its largest mean compression 7.11% against 7.09%; and the constraint
// solve is about 20% cheaper, with (1.1 / 1.2)^3, a quarter, fewer candidates a loop (docs/results.md,
// "PBF's walls and cost").
constexpr float kPbfListReach = 1.1f;
SPH_HD inline float neighbour_reach(const SimConstants& c) { return c.solver == Solver::Pbf ? kPbfListReach : 1.0f; }
SPH_HD inline float neighbour_radius2(const SimConstants& c) {
  const float reach = neighbour_reach(c);
  return reach * reach * c.kernel.h2;
}

// Slots of a particle's list: twice the neighbours a particle of the densest fluid has at rest within the
// list radius (4/3 pi (reach h)^3 rho0 / m), at least 32, a multiple of 4; 0 (no lists: search in every loop)
// beyond 256, where the lists' memory would outweigh the search they save.
inline int32_t neighbour_list_capacity(const SimConstants& c) {
  double expected = 0.0;
  for (int32_t f = 0; f < c.num_fluids; ++f) {
    const double r = double(c.kernel.h) * neighbour_reach(c);
    const double n = 4.0 / 3.0 * kPiDouble * r * r * r * c.fluids[f].rest_density / c.fluids[f].mass;
    expected = n > expected ? n : expected;
  }
  const double slots = 2.0 * expected < 32.0 ? 32.0 : 2.0 * expected;
  return slots > 256.0 || !(slots == slots) ? 0 : (int32_t(slots) + 3) / 4 * 4;
}

#if !defined(__CUDACC__)
namespace neighbour_simd {

typedef float Floats4 __attribute__((vector_size(16)));
typedef int32_t Ints4 __attribute__((vector_size(16)));

// For each mask of four lanes: its set lanes in order (the rest 0), and how many there are.
struct Compaction {
  int32_t lanes[16][4];
  int32_t count[16];
};
constexpr Compaction make_compaction() {
  Compaction t{};
  for (int mask = 0; mask < 16; ++mask) {
    int k = 0;
    for (int lane = 0; lane < 4; ++lane)
      if ((mask >> lane) & 1) t.lanes[mask][k++] = lane;
    t.count[mask] = k;
  }
  return t;
}
inline constexpr Compaction kCompaction = make_compaction();

// Bit k set where candidate k of four, at p0..p3, lies within h of xa (r^2 < h2, computed as length2 does:
// (x^2 + y^2) + z^2) and lane k of `live` is set (all bits).
inline int within_mask(Vec3 xa, float h2, Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, Ints4 live) {
  const Floats4 dx = Floats4{xa.x, xa.x, xa.x, xa.x} - Floats4{p0.x, p1.x, p2.x, p3.x};
  const Floats4 dy = Floats4{xa.y, xa.y, xa.y, xa.y} - Floats4{p0.y, p1.y, p2.y, p3.y};
  const Floats4 dz = Floats4{xa.z, xa.z, xa.z, xa.z} - Floats4{p0.z, p1.z, p2.z, p3.z};
  const Floats4 r2 = dx * dx + dy * dy + dz * dz;
  const Ints4 in = (r2 < Floats4{h2, h2, h2, h2}) & live;
  return (in[0] & 1) | (in[1] & 2) | (in[2] & 4) | (in[3] & 8);
}

// Appends the particles of [begin, end) within h of xa to list at *m (writes up to 4 slots from
// min(*m, capacity), the list having capacity + kNeighbourListPad slots).
inline void filter_range(const Vec3* pos, Vec3 xa, float h2, int32_t begin, int32_t end, int32_t* list,
                         int32_t capacity, int32_t& m) {
  const int32_t last = end - 1;
  for (int32_t b = begin; b < end; b += 4) {
    // Lanes past the end read the last candidate again and are masked out.
    const int mask = within_mask(xa, h2, pos[b], pos[b + 1 < last ? b + 1 : last], pos[b + 2 < last ? b + 2 : last],
                                 pos[b + 3 < last ? b + 3 : last], Ints4{b, b + 1, b + 2, b + 3} < Ints4{end, end, end, end});
    Ints4 lanes;
    std::memcpy(&lanes, kCompaction.lanes[mask], sizeof lanes);
    const Ints4 found = Ints4{b, b, b, b} + lanes;
    std::memcpy(list + (m < capacity ? m : capacity), &found, sizeof found);
    m += kCompaction.count[mask];
  }
}

}  // namespace neighbour_simd
#endif

// The particles b within h of particle a (|x_a - x_b|^2 < h2, a itself included), in for_each_candidate's
// order: returns how many there are, and lists them all in list[0, capacity) when there are fewer than
// capacity (otherwise the list is incomplete and must not be used). list has capacity + kNeighbourListPad
// slots. kBranchFree: see the top of this file.
template <bool kBranchFree>
SPH_HD inline int32_t list_neighbours(const GridView& grid, const Vec3* pos, int32_t a, float h2, int32_t* list,
                                      int32_t capacity) {
  const Vec3 xa = pos[a];
  int32_t m = 0;
  for_each_candidate_range(grid, a, [&](int32_t begin, int32_t end) {
#if !defined(__CUDACC__)
    if (kBranchFree) {
      neighbour_simd::filter_range(pos, xa, h2, begin, end, list, capacity, m);
      return;
    }
#endif
    for (int32_t b = begin; b < end; ++b) {
      if (length2(xa - pos[b]) < h2) {
        if (m < capacity) list[m] = b;
        ++m;
      }
    }
  });
  return m;
}

}  // namespace sph
