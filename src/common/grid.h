// The neighbour grid shared by every back end: a grid over the particles, not over the domain.
//
// Cells are h / 2 wide (reach 2: every neighbour within h lies in the 5 x 5 x 5 cells around a particle's
// own; 42% fewer candidates than 27 cells of h). Cells are grouped in blocks of 16 x 4 x 4. A particle's
// 64-bit cell key is the Morton (Z-order) code of its block followed by its cell inside the block, rows
// of 16 cells along x contiguous. Particles are sorted by (cell key, id), so only occupied blocks exist:
// memory and time scale with the particle count whatever the size of the domain, and the Morton order
// keeps neighbouring blocks close in memory whatever the fluid's shape (issue 11, items 7 and 9).
// Each occupied block holds a dense table of its 256 cells' first particles and the indices of its 26
// neighbour blocks, so a search finds every row of up to 5 cells as one or two index ranges without any
// lookup: grid_build.h builds the tables, the back ends only schedule the loops. The device build keeps
// tables for as many blocks as an earlier step's summary reported, so that it never waits for this step's
// count (device_grid.h); blocks past that capacity, when the fluid spread into more blocks within a step,
// are searched by binary search over the block codes and the block's keys instead: the same ranges, slower.
#pragma once

#include <cstdint>

#include "particle_view.h"
#include "sph_hd.h"


namespace sph {

constexpr int32_t kGridReach = 2;                // cells on each side a search visits (cells of h / 2)
constexpr int kBlockXBits = 4, kBlockYBits = 2, kBlockZBits = 2;  // blocks of 16 x 4 x 4 cells
constexpr int32_t kBlockX = 1 << kBlockXBits, kBlockY = 1 << kBlockYBits, kBlockZ = 1 << kBlockZBits;
constexpr int kLocalBits = kBlockXBits + kBlockYBits + kBlockZBits;
constexpr int32_t kCellsPerBlock = 1 << kLocalBits;  // 256: 8 bits of the key
constexpr int32_t kBlockTable = kCellsPerBlock + 1;  // per block: first particle of each cell, then the end
constexpr int32_t kBlockNeighbours = 27;            // per block: itself and its 26 neighbours (-1: empty)
constexpr int32_t kBlockBits = 18;  // per axis: 2^18 blocks, +-2^17 blocks from the origin (+-2^18 h in y, z)
constexpr uint64_t kLocalMask = uint64_t(kCellsPerBlock) - 1;

// Cell coordinate along one axis, counted from the cell that holds the grid origin plus half the range,
// so that it is never negative. Clamped in floating point before the conversion (which is undefined for
// far-away or non-finite values and differs between x86 and GPUs): positions beyond about 2^17 blocks
// share the border cells, which keeps the search exact (they are candidates of one another).
SPH_HD inline int32_t cell_coord(float coord, float origin, float inv_cell, int32_t cells_per_block) {
  const float half = float((1 << (kBlockBits - 1)) * cells_per_block);
  const float last = float((1 << kBlockBits) * cells_per_block - 1);
  float c = floorf((coord - origin) * inv_cell) + half;
  c = c > 0.0f ? c : 0.0f;  // NaN goes to 0 as well
  c = c < last ? c : last;
  return int32_t(c);
}

struct CellCoord {
  int32_t x, y, z;
};

SPH_HD inline CellCoord cell_of(const GridGeometry& g, Vec3 p) {
  const float inv = 1.0f / g.cell_size;
  return {cell_coord(p.x, g.origin.x, inv, kBlockX), cell_coord(p.y, g.origin.y, inv, kBlockY),
          cell_coord(p.z, g.origin.z, inv, kBlockZ)};
}

// Morton code of three 18-bit coordinates: their bits interleaved (x lowest), 54 bits.
SPH_HD inline uint64_t spread_bits3(uint32_t v) {
  uint64_t x = v & 0x3ffffu;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

SPH_HD inline uint32_t compact_bits3(uint64_t x) {
  x &= 0x1249249249249249ull;
  x = (x ^ (x >> 2)) & 0x10c30c30c30c30c3ull;
  x = (x ^ (x >> 4)) & 0x100f00f00f00f00full;
  x = (x ^ (x >> 8)) & 0x1f0000ff0000ffull;
  x = (x ^ (x >> 16)) & 0x1f00000000ffffull;
  x = (x ^ (x >> 32)) & 0x3ffffull;
  return uint32_t(x);
}

SPH_HD inline uint64_t block_key(int32_t bx, int32_t by, int32_t bz) {
  return spread_bits3(uint32_t(bx)) | spread_bits3(uint32_t(by)) << 1 | spread_bits3(uint32_t(bz)) << 2;
}

// Cell key: block's Morton code, then the cell inside the block (x fastest: rows of 8 cells contiguous).
SPH_HD inline uint64_t cell_key(const GridGeometry& g, Vec3 p) {
  const CellCoord c = cell_of(g, p);
  const uint64_t local = uint64_t(c.x % kBlockX) | uint64_t(c.y % kBlockY) << kBlockXBits |
                         uint64_t(c.z % kBlockZ) << (kBlockXBits + kBlockYBits);
  return block_key(c.x / kBlockX, c.y / kBlockY, c.z / kBlockZ) << kLocalBits | local;
}

// A label of the cell that holds p, for colouring particles by cell (render/colour_map.h).
SPH_HD inline int32_t cell_index(const GridGeometry& g, Vec3 p) {
  const uint64_t k = cell_key(g, p);
  return int32_t(uint32_t(k) ^ uint32_t(k >> 32));
}

// A read of data that stays constant during a kernel: through the read-only cache on a GPU.
template <class T>
SPH_HD inline T read_only(const T* p) {
#if defined(__CUDA_ARCH__)
  return __ldg(p);
#else
  return *p;
#endif
}

// The index of the block with Morton code `code` among the sorted codes[0, blocks), or -1.
SPH_HD inline int32_t find_block(const uint64_t* codes, int32_t blocks, uint64_t code) {
  int32_t lo = 0, hi = blocks;
  while (lo < hi) {
    const int32_t mid = lo + (hi - lo) / 2;
    if (codes[mid] < code)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < blocks && codes[lo] == code ? lo : -1;
}

// The block at block coordinates (x, y, z), or -1 where no particle is or they leave the key range.
// codes: every block's Morton code, ascending.
SPH_HD inline int32_t block_at(const uint64_t* codes, int32_t blocks, int32_t x, int32_t y, int32_t z) {
  constexpr int32_t kLast = (1 << kBlockBits) - 1;
  const bool inside = x >= 0 && y >= 0 && z >= 0 && x <= kLast && y <= kLast && z <= kLast;
  return inside ? find_block(codes, blocks, block_key(x, y, z)) : -1;
}

// The block at offset (dx, dy, dz) in (-1..1)^3 of block b, as block_at: one entry of find_block_neighbours.
SPH_HD inline int32_t neighbour_block(const uint64_t* codes, int32_t blocks, int32_t b, int32_t dx, int32_t dy, int32_t dz) {
  if (dx == 0 && dy == 0 && dz == 0) return b;
  const uint64_t code = codes[b];
  return block_at(codes, blocks, int32_t(compact_bits3(code)) + dx, int32_t(compact_bits3(code >> 1)) + dy,
                  int32_t(compact_bits3(code >> 2)) + dz);
}

// out[27]: the blocks at offsets (dx, dy, dz) in (-1..1)^3 of block b (z slowest, x fastest), as
// neighbour_block, with b's coordinates decoded once: a block's row of block_neighbours.
SPH_HD inline void find_block_neighbours(const uint64_t* codes, int32_t blocks, int32_t b, int32_t* out) {
  const uint64_t code = codes[b];
  const int32_t bx = int32_t(compact_bits3(code)), by = int32_t(compact_bits3(code >> 1)),
                bz = int32_t(compact_bits3(code >> 2));
  int32_t k = 0;
  for (int32_t dz = -1; dz <= 1; ++dz)
    for (int32_t dy = -1; dy <= 1; ++dy)
      for (int32_t dx = -1; dx <= 1; ++dx, ++k)
        out[k] = dx == 0 && dy == 0 && dz == 0 ? b : block_at(codes, blocks, bx + dx, by + dy, bz + dz);
}

// The first particle of block `block` whose cell inside the block is `local` or after it, else the block's
// end: the entry cell_start[local] of its table (grid_build.h, fill_block_table), found by binary search
// over its sorted keys instead, for a block without a table (GridView::block_capacity).
SPH_HD inline int32_t first_in_block_from(const GridView& grid, int32_t block, int32_t local) {
  int32_t lo = grid.block_begin[block], hi = grid.block_begin[block + 1];
  while (lo < hi) {
    const int32_t mid = lo + (hi - lo) / 2;
    if (int32_t(read_only(grid.key + mid) & kLocalMask) < local)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

// The index ranges of particles in the 5 x 5 x 5 cells around particle a's cell (its own included): one
// or two ranges per row of 5 cells, in one fixed order (rows by z, then y, then x ascending), so that
// every sum over neighbours has the same bits on every back end. Two schedules of the same ranges, both
// compiled everywhere so that tests/test_grid.cpp checks they call f(begin, end) identically:
//
// candidate_ranges_by_counter (GPU): one counter over (row, part), part 0 and 1 being the row's cells in
// the left and right block of the two it may touch along x (a part with no cells is skipped); the
// particle's block and cell are read again in each turn rather than held, so that the forces kernel fits
// 80 registers without spilling (tests/ptxas_resources.sh).
template <class F>
SPH_HD inline void candidate_ranges_by_counter(const GridView& grid, int32_t a, F&& f) {
  constexpr int32_t kSide = 2 * kGridReach + 1;
#if defined(__CUDA_ARCH__)
#pragma unroll 1
#endif
  for (int32_t s = 0; s < 2 * kSide * kSide; ++s) {
    const int32_t lx = int32_t(read_only(grid.key + a) & uint64_t(kBlockX - 1));
    const int32_t bx = (lx < kGridReach ? -1 : 0) + (s & 1);
    if (bx > (lx + kGridReach >= kBlockX ? 1 : 0)) continue;
    const int32_t here = int32_t(read_only(grid.key + a) & kLocalMask);
    const int32_t r = s >> 1;
    const int32_t z = (here >> (kBlockXBits + kBlockYBits)) + r / kSide - kGridReach;
    const int32_t y = ((here >> kBlockXBits) & (kBlockY - 1)) + r % kSide - kGridReach;
    const int32_t bz = z < 0 ? -1 : (z >= kBlockZ ? 1 : 0);
    const int32_t by = y < 0 ? -1 : (y >= kBlockY ? 1 : 0);
    const int32_t own = read_only(grid.particle_block + a);
    const int32_t block = own < grid.block_capacity
                              ? grid.block_neighbours[int64_t(own) * kBlockNeighbours + (bz + 1) * 9 + (by + 1) * 3 + (bx + 1)]
                              : neighbour_block(grid.block_code, *grid.block_count, own, bx, by, bz);
    const int32_t from = lx - kGridReach - kBlockX * bx > 0 ? lx - kGridReach - kBlockX * bx : 0;
    const int32_t to = lx + kGridReach - kBlockX * bx < kBlockX - 1 ? lx + kGridReach - kBlockX * bx : kBlockX - 1;
    const int32_t row = (z - kBlockZ * bz) * (kBlockX * kBlockY) + (y - kBlockY * by) * kBlockX;
    int32_t begin, end;
    if (uint32_t(block) < uint32_t(grid.block_capacity)) {  // -1 (no block) wraps above
      const int32_t* start = grid.cell_start + int64_t(block) * kBlockTable + row;
      begin = start[from];
      end = start[to + 1];
    } else {
      if (block < 0) continue;
      begin = first_in_block_from(grid, block, row + from);
      end = first_in_block_from(grid, block, row + to + 1);
    }
    f(begin, end);
  }
}

// candidate_ranges_nested (CPU): nested loops with everything that does not change along them hoisted (on
// a CPU the range arithmetic was a good part of the search's cost).
template <class F>
SPH_HD inline void candidate_ranges_nested(const GridView& grid, int32_t a, F&& f) {
  const int32_t local = int32_t(grid.key[a] & kLocalMask);
  const int32_t lx = local & (kBlockX - 1), ly = (local >> kBlockXBits) & (kBlockY - 1),
                lz = local >> (kBlockXBits + kBlockYBits);
  int32_t parts = 0, part_bx[2], part_from[2], part_to[2];
  for (int32_t bx = lx < kGridReach ? -1 : 0; bx <= (lx + kGridReach >= kBlockX ? 1 : 0); ++bx, ++parts) {
    part_bx[parts] = bx + 1;
    part_from[parts] = lx - kGridReach - kBlockX * bx > 0 ? lx - kGridReach - kBlockX * bx : 0;
    part_to[parts] = (lx + kGridReach - kBlockX * bx < kBlockX - 1 ? lx + kGridReach - kBlockX * bx : kBlockX - 1) + 1;
  }
  const uint32_t capacity = uint32_t(grid.block_capacity);  // held: f's stores may alias grid
  const int32_t own = grid.particle_block[a];
  const int32_t* around = grid.block_neighbours + int64_t(own) * kBlockNeighbours;
  int32_t searched[kBlockNeighbours];
  if (uint32_t(own) >= capacity) {
    find_block_neighbours(grid.block_code, *grid.block_count, own, searched);
    around = searched;
  }
  for (int32_t z = lz - kGridReach; z <= lz + kGridReach; ++z) {
    const int32_t bz = z < 0 ? -1 : (z >= kBlockZ ? 1 : 0);
    const int32_t z_offset = (z - kBlockZ * bz) * (kBlockX * kBlockY);
    for (int32_t y = ly - kGridReach; y <= ly + kGridReach; ++y) {
      const int32_t by = y < 0 ? -1 : (y >= kBlockY ? 1 : 0);
      const int32_t row = z_offset + (y - kBlockY * by) * kBlockX;
      const int32_t* row_blocks = around + (bz + 1) * 9 + (by + 1) * 3;
      for (int32_t k = 0; k < parts; ++k) {
        const int32_t block = row_blocks[part_bx[k]];
        int32_t begin, end;
        if (uint32_t(block) < capacity) {  // one test on the common path: -1 (no block) wraps above
          const int32_t* start = grid.cell_start + int64_t(block) * kBlockTable + row;
          begin = start[part_from[k]];
          end = start[part_to[k]];
        } else {
          if (block < 0) continue;
          begin = first_in_block_from(grid, block, row + part_from[k]);
          end = first_in_block_from(grid, block, row + part_to[k]);
        }
        f(begin, end);
      }
    }
  }
}

// Calls f(begin, end) for every candidate range around particle a, in the order above.
template <class F>
SPH_HD inline void for_each_candidate_range(const GridView& grid, int32_t a, F&& f) {
#if defined(__CUDA_ARCH__)
  candidate_ranges_by_counter(grid, a, f);
#else
  candidate_ranges_nested(grid, a, f);
#endif
}

// Calls f(b) for every candidate b around particle a (for_each_candidate_range's order); the caller
// tests the distance.
template <class F>
SPH_HD inline void for_each_candidate(const GridView& grid, int32_t a, F&& f) {
  for_each_candidate_range(grid, a, [&](int32_t begin, int32_t end) {
    for (int32_t b = begin; b < end; ++b) f(b);
  });
}

// Neighbour lists of the CPU builds (grid.neighbour_list, neighbour_list.h): each particle's list has
// list_capacity + kNeighbourListPad slots, the pad for the vectorised filter, which may write past the end.
constexpr int32_t kNeighbourListPad = 4;

// Calls f(b, xab, r2) for every particle b with r2 = |x_a - x_b|^2 < h2 (a itself included), xab = x_a - x_b,
// in for_each_candidate's order on every back end, so every sum has the same bits. The CPU builds read
// the list made with the grid (neighbour_list.h) when it holds them all: the search and its branch
// mispredictions are then paid once per step instead of once per loop. A GPU tests each candidate.
// pos: Vec3 positions, or the loops' packed Vec4 records (ParticleView::pos_mass: one 128-bit load on a GPU).
template <class Pos, class F>
SPH_HD inline void for_each_neighbour(const GridView& grid, const Pos* pos, int32_t a, float h2, F&& f) {
  const Vec3 xa = xyz(pos[a]);
#if !defined(__CUDA_ARCH__)
  if (grid.neighbour_list != nullptr && grid.neighbour_count[a] < grid.list_capacity) {
    const int32_t* list = grid.neighbour_list + int64_t(a) * (grid.list_capacity + kNeighbourListPad);
    for (int32_t t = 0, m = grid.neighbour_count[a]; t < m; ++t) {
      const Vec3 xab = xa - xyz(pos[list[t]]);
      f(list[t], xab, length2(xab));
    }
    return;
  }
#endif
  for_each_candidate(grid, a, [&](int32_t b) {
    const Vec3 xab = xa - xyz(pos[b]);
    const float r2 = length2(xab);
    if (r2 < h2) f(b, xab, r2);
  });
}

// Puts the particles of one cell, order[begin, end), in ascending id order (insertion sort: cells hold a
// few particles and arrive nearly sorted). The particle order, and with it every floating-point sum,
// then depends only on the particle set, not on the previous order or on a parallel sort's timing.
SPH_HD inline void sort_cell_by_id(int32_t* order, int32_t begin, int32_t end, const int32_t* id) {
  for (int32_t i = begin + 1; i < end; ++i) {
    const int32_t moving = order[i];
    const int32_t key = id[moving];
    int32_t j = i - 1;
    while (j >= begin && id[order[j]] > key) {
      order[j + 1] = order[j];
      --j;
    }
    order[j + 1] = moving;
  }
}

}  // namespace sph
