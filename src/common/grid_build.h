// Building the neighbour grid (grid.h), as per-index steps that every back end runs in the same order:
//   1. key[i] = cell_key(pos[i]) for every particle;
//   2. sort the particles by (key, id) (a stable sort by key, then sort_cell_by_id in every run of equal
//      keys; the result is unique, so the back ends agree bit for bit);
//   3. mark the first particle of every block (is_block_start) and number the blocks (a prefix sum);
//      block_begin[b] = first particle of block b, block_begin[blocks] = n;
//   4. per block: fill_block_table (its cells' first particles) and find_block_neighbours.
// The back ends differ only in how they run each loop and which sort they use.
#pragma once

#include <cstdint>

#include "grid.h"

namespace sph {

SPH_HD inline uint64_t block_of_key(uint64_t key) { return key >> kLocalBits; }

// Whether sorted particle j is the first of a cell (j > 0 compares with the previous key).
SPH_HD inline bool is_cell_start(const uint64_t* key, int32_t j) { return j == 0 || key[j] != key[j - 1]; }

// Whether sorted particle j is the first of a block.
SPH_HD inline bool is_block_start(const uint64_t* key, int32_t j) {
  return j == 0 || block_of_key(key[j]) != block_of_key(key[j - 1]);
}

// The end of the run of equal keys that starts at j (n: particle count).
SPH_HD inline int32_t cell_end(const uint64_t* key, int32_t j, int32_t n) {
  int32_t e = j + 1;
  while (e < n && key[e] == key[j]) ++e;
  return e;
}

// table[l] = first particle of block's cell l, or of the next occupied cell after it; the last entry
// (table[kCellsPerBlock]) = end.
// key[begin, end): the block's particles, sorted.
SPH_HD inline void fill_block_table(const uint64_t* key, int32_t begin, int32_t end, int32_t* table) {
  int32_t j = begin;
  for (int32_t l = 0; l < kCellsPerBlock; ++l) {
    while (j < end && int32_t(key[j] & kLocalMask) < l) ++j;
    table[l] = j;
  }
  table[kCellsPerBlock] = end;
}

}  // namespace sph
