// The CPU builds' neighbour lists, made a row of cells at a time (issue 11, item 9): the particles of one
// row of a block (16 cells along x, contiguous in the sorted order) share the 25 rows of cells around them,
// so those rows' cell tables are looked up once per row, not once per particle. Each particle's candidates
// are then gathered into one index stream without a branch per range, and filtered four at a time
// (or with a branch per candidate while the fluid is still a lattice, neighbour_list_choice.h).
//
// Why: late in a dam break a particle's ~90 candidates lie in ~25 short ranges of 1 to 4 particles; a
// filter that loops per range mispredicts its loop exits, and a particle's own range arithmetic and
// table lookups cost more than its filter. The list is exactly list_neighbours' (the direct search's, as
// the GPU sees it): the same particles, in the same order (tests/test_grid.cpp).
#pragma once

#if !defined(__CUDACC__)

#include <cstdint>
#include <cstring>

#include "grid.h"
#include "neighbour_list.h"

namespace sph {
namespace neighbour_rows {

using neighbour_simd::Ints4;
using neighbour_simd::kCompaction;

constexpr int32_t kSide = 2 * kGridReach + 1;
constexpr int32_t kRowsAround = kSide * kSide;  // rows of cells around a row: 5 x 5
// A particle's candidates are gathered when there are at most kGatherCapacity (else it is searched range
// by range, list_neighbours). Each range is copied as kGatherWidth consecutive indices without a branch
// (slots past its end are overwritten by the next range); only a longer range loops.
constexpr int32_t kGatherWidth = 8;
constexpr int32_t kGatherCapacity = 384;

// The cell tables of the 25 rows of cells around one row of a block, in the search's order (z, then y),
// each in three parts along x: the row in the block to the left (its last kGridReach cells are
// candidates), in the same block, and to the right (its first kGridReach cells). A missing block is an
// empty table.
struct RowsAround {
  const int32_t* part[kRowsAround][3];
};

// False where the block or one around it has no tables (GridView::block_capacity on the device back
// end's host build): its particles are then searched one by one.
inline bool rows_around(const GridView& grid, int32_t block, int32_t ly, int32_t lz, RowsAround& rows) {
  static constexpr int32_t kEmpty[kBlockX + 1] = {};
  const uint32_t capacity = uint32_t(grid.block_capacity);
  if (uint32_t(block) >= capacity) return false;
  const int32_t* around = grid.block_neighbours + int64_t(block) * kBlockNeighbours;
  int32_t t = 0;
  for (int32_t z = lz - kGridReach; z <= lz + kGridReach; ++z) {
    const int32_t bz = z < 0 ? -1 : (z >= kBlockZ ? 1 : 0);
    for (int32_t y = ly - kGridReach; y <= ly + kGridReach; ++y, ++t) {
      const int32_t by = y < 0 ? -1 : (y >= kBlockY ? 1 : 0);
      const int32_t row = ((z - kBlockZ * bz) * kBlockY + (y - kBlockY * by)) * kBlockX;
      for (int32_t bx = -1; bx <= 1; ++bx) {
        const int32_t b = around[(bz + 1) * 9 + (by + 1) * 3 + (bx + 1)];
        if (b >= 0 && uint32_t(b) >= capacity) return false;
        rows.part[t][bx + 1] = b >= 0 ? grid.cell_start + int64_t(b) * kBlockTable + row : kEmpty;
      }
    }
  }
  return true;
}

// Copies the index range [begin, end) to cand at k (see kGatherWidth); false when it does not fit.
inline bool append_range(int32_t begin, int32_t end, int32_t* cand, int32_t& k) {
  const int32_t len = end - begin;
  if (len > kGatherCapacity - k) return false;
  const Ints4 first = Ints4{begin, begin, begin, begin} + Ints4{0, 1, 2, 3};
  const Ints4 second = first + Ints4{4, 4, 4, 4};
  std::memcpy(cand + k, &first, sizeof first);
  std::memcpy(cand + k + 4, &second, sizeof second);
  for (int32_t b = begin + kGatherWidth; b < end; ++b) cand[k + (b - begin)] = b;
  k += len;
  return true;
}

// The candidates of a particle in cell lx of the row: the same ranges, in the same order, as
// candidate_ranges_nested. cand has kGatherCapacity + kGatherWidth slots; returns the count, or -1.
inline int32_t gather_candidates(const RowsAround& rows, int32_t lx, int32_t* cand) {
  const int32_t left_from = lx - kGridReach + kBlockX < kBlockX ? lx - kGridReach + kBlockX : kBlockX;
  const int32_t from = lx - kGridReach > 0 ? lx - kGridReach : 0;
  const int32_t to = lx + kGridReach + 1 < kBlockX ? lx + kGridReach + 1 : kBlockX;
  const int32_t right_to = lx + kGridReach + 1 - kBlockX > 0 ? lx + kGridReach + 1 - kBlockX : 0;
  int32_t k = 0;
  if (lx >= kGridReach && lx + kGridReach < kBlockX) {  // 12 cells of 16: the rows lie inside the block
    for (int32_t t = 0; t < kRowsAround; ++t)
      if (!append_range(rows.part[t][1][from], rows.part[t][1][to], cand, k)) return -1;
    return k;
  }
  for (int32_t t = 0; t < kRowsAround; ++t) {
    const int32_t* const* part = rows.part[t];
    if (!append_range(part[0][left_from], part[0][kBlockX], cand, k) ||
        !append_range(part[1][from], part[1][to], cand, k) || !append_range(part[2][0], part[2][right_to], cand, k))
      return -1;
  }
  return k;
}

// Appends the candidates cand[0, k) within h of xa to list at *m, four at a time (cand[k, k + 4) hold valid
// particle indices; lanes past k are masked out). Same arithmetic and order as filter_range.
inline void filter_candidates(const Vec3* pos, Vec3 xa, float h2, const int32_t* cand, int32_t k, int32_t* list,
                              int32_t capacity, int32_t& m) {
  for (int32_t t = 0; t < k; t += 4) {
    int32_t idx[4];
    std::memcpy(idx, cand + t, sizeof idx);
    const int mask = neighbour_simd::within_mask(xa, h2, pos[idx[0]], pos[idx[1]], pos[idx[2]], pos[idx[3]],
                                                 Ints4{t, t + 1, t + 2, t + 3} < Ints4{k, k, k, k});
    const int32_t* lanes = kCompaction.lanes[mask];
    const Ints4 found = {idx[lanes[0]], idx[lanes[1]], idx[lanes[2]], idx[lanes[3]]};
    std::memcpy(list + (m < capacity ? m : capacity), &found, sizeof found);
    m += kCompaction.count[mask];
  }
}

// The same with a branch per candidate (cheaper while the particles sit on a lattice).
inline void filter_candidates_branchy(const Vec3* pos, Vec3 xa, float h2, const int32_t* cand, int32_t k,
                                      int32_t* list, int32_t capacity, int32_t& m) {
  for (int32_t t = 0; t < k; ++t) {
    const int32_t b = cand[t];
    if (length2(xa - pos[b]) < h2) {
      if (m < capacity) list[m] = b;
      ++m;
    }
  }
}

// Lists the neighbours of every particle of row `row` (its y + kBlockY z) of block `block`, as
// list_neighbours<kBranchFree> would, into lists (capacity + kNeighbourListPad slots per particle) and
// counts (see list_neighbours).
template <bool kBranchFree>
inline void list_row_neighbours(const GridView& grid, const Vec3* pos, float h2, int32_t block, int32_t row,
                                int32_t* lists, int32_t* counts, int32_t capacity) {
  int32_t begin, end;
  if (uint32_t(block) < uint32_t(grid.block_capacity)) {
    const int32_t* cells = grid.cell_start + int64_t(block) * kBlockTable + row * kBlockX;
    begin = cells[0];
    end = cells[kBlockX];
  } else {
    begin = first_in_block_from(grid, block, row * kBlockX);
    end = first_in_block_from(grid, block, (row + 1) * kBlockX);
  }
  if (begin == end) return;
  RowsAround rows;
  const bool tables = rows_around(grid, block, row % kBlockY, row / kBlockY, rows);
  int32_t cand[kGatherCapacity + kGatherWidth];
  for (int32_t a = begin; a < end; ++a) {
    int32_t* list = lists + int64_t(a) * (capacity + kNeighbourListPad);
    const int32_t k = tables ? gather_candidates(rows, int32_t(grid.key[a] & uint64_t(kBlockX - 1)), cand) : -1;
    if (k < 0) {
      counts[a] = list_neighbours<kBranchFree>(grid, pos, a, h2, list, capacity);
      continue;
    }
    for (int32_t pad = 0; pad < 4; ++pad) cand[k + pad] = a;
    int32_t m = 0;
    if (kBranchFree)
      filter_candidates(pos, pos[a], h2, cand, k, list, capacity, m);
    else
      filter_candidates_branchy(pos, pos[a], h2, cand, k, list, capacity, m);
    counts[a] = m;
  }
}

}  // namespace neighbour_rows
}  // namespace sph

#endif
