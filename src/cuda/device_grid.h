// The neighbour grid on the device back end: the steps of src/common/grid_build.h as data-parallel loops,
// a stable radix sort by cell key (CUB through Thrust under nvcc; Thrust's OpenMP sort on the host build)
// and prefix sums. Its memory grows with the particle count only (grid.h).
#pragma once

#include <chrono>
#include <cstdint>

#include <thrust/scan.h>
#include <thrust/sort.h>

#include "../common/grid_build.h"
#include "../common/neighbour_list.h"
#include "../common/neighbour_list_choice.h"
#include "../common/neighbour_rows.h"
#include "device_arrays.h"
#include "device_launch.h"

namespace sph {
namespace SPH_DEVICE_NS {

struct CellKeyFn {
  GridGeometry g;
  const Vec3* pos;
  uint64_t* key;
  int32_t* order;
  SPH_HD void operator()(int32_t i) const {
    key[i] = cell_key(g, pos[i]);
    order[i] = i;
  }
};

// The stable sort by key keeps the previous order inside a cell: put each cell in id order (grid_build.h).
struct SortCellsByIdFn {
  const uint64_t* key;
  const int32_t* id;
  int32_t* order;
  int32_t n;
  SPH_HD void operator()(int32_t j) const {
    if (!is_cell_start(key, j)) return;
    const int32_t end = cell_end(key, j, n);
    if (end - j > 1) sort_cell_by_id(order, j, end, id);
  }
};

struct BlockStartFn {
  const uint64_t* key;
  int32_t* flag;
  SPH_HD void operator()(int32_t j) const { flag[j] = is_block_start(key, j) ? 1 : 0; }
};

// After the inclusive scan of the flags: block index from 0, and each block's first particle and code.
struct RecordBlocksFn {
  const uint64_t* key;
  int32_t* particle_block;
  int32_t* block_begin;
  uint64_t* block_code;
  int32_t n;
  SPH_HD void operator()(int32_t j) const {
    const int32_t b = particle_block[j] - 1;
    particle_block[j] = b;
    if (is_block_start(key, j)) {
      block_begin[b] = j;
      block_code[b] = block_of_key(key[j]);
    }
    if (j == n - 1) block_begin[b + 1] = n;
  }
};

struct BlockTablesFn {
  const uint64_t* key;
  const int32_t* block_begin;
  const uint64_t* block_code;
  int32_t blocks;
  int32_t* cell_start;
  int32_t* block_neighbours;
  SPH_HD void operator()(int32_t b) const {
    fill_block_table(key, block_begin[b], block_begin[b + 1], cell_start + int64_t(b) * kBlockTable);
    find_block_neighbours(block_code, blocks, b, block_neighbours + int64_t(b) * kBlockNeighbours);
  }
};

// The CPU build's neighbour lists (grid.h), a row of cells of a block per index (neighbour_rows.h): not on a
// GPU, whose candidate loop has no branch predictor to spare and whose memory traffic a list would double.
#if !defined(__CUDACC__)
template <bool kBranchFree>
struct NeighbourListFn {
  GridView g;
  const Vec3* pos;
  float h2;
  int32_t* list;
  int32_t* count;
  int32_t capacity;
  void operator()(int32_t block_row) const {
    constexpr int32_t kRows = kBlockY * kBlockZ;
    neighbour_rows::list_row_neighbours<kBranchFree>(g, pos, h2, block_row / kRows, block_row % kRows, list, count,
                                                     capacity);
  }
};
#endif

class DeviceGrid {
 public:
  // Device bytes per particle for the grid, assuming blocks of at least 8 particles on average (a dense
  // fluid fills a block of 256 cells with about 256; a thin spray fewer).
  static constexpr std::size_t kBytesPerParticle =
      sizeof(uint64_t) + 3 * sizeof(int32_t) + (kBlockTable + kBlockNeighbours + 1) * sizeof(int32_t) / 8 + sizeof(uint64_t) / 8;

  // Sorts d by (cell key, id) (sorted: the reordering buffer, swapped with d) and builds the tables.
  template <class Policy>
  void build(const SimConstants& c, DeviceArrays& d, DeviceArrays& sorted, Policy policy) {
    const GridGeometry& g = c.grid;
    const int32_t n = int32_t(d.size());
    key_.resize(std::size_t(n));
    order_.resize(std::size_t(n));
    particle_block_.resize(std::size_t(n));
    blocks_ = 0;
    if (n == 0) return;
    launch(n, CellKeyFn{g, raw(d.pos), raw(key_), raw(order_)});
    thrust::stable_sort_by_key(policy, key_.begin(), key_.end(), order_.begin());
    launch(n, SortCellsByIdFn{raw(key_), raw(d.id), raw(order_), n});
    sorted.gather_from(d, order_);
    std::swap(d, sorted);

    flag_.resize(std::size_t(n));
    launch(n, BlockStartFn{raw(key_), raw(flag_)});
    thrust::inclusive_scan(policy, flag_.begin(), flag_.end(), particle_block_.begin());
    blocks_ = particle_block_.back();  // the one read back of the grid build: how many blocks to size
    block_begin_.resize(std::size_t(blocks_) + 1);
    block_code_.resize(std::size_t(blocks_));
    launch(n, RecordBlocksFn{raw(key_), raw(particle_block_), raw(block_begin_), raw(block_code_), n});
    cell_start_.resize(std::size_t(blocks_) * kBlockTable);
    block_neighbours_.resize(std::size_t(blocks_) * kBlockNeighbours);
    launch(blocks_, BlockTablesFn{raw(key_), raw(block_begin_), raw(block_code_), blocks_, raw(cell_start_),
                                  raw(block_neighbours_)});
#if !defined(__CUDACC__)
    list_capacity_ = neighbour_list_capacity(c);
    if (list_capacity_ == 0) return;  // no lists: every loop searches
    neighbour_list_.resize(std::size_t(n) * std::size_t(list_capacity_ + kNeighbourListPad));
    neighbour_count_.resize(std::size_t(n));
    GridView search = view(g);
    search.neighbour_list = nullptr;
    const float h2 = c.kernel.h2;
    const auto t0 = std::chrono::steady_clock::now();
    const bool branch_free = list_choice_.branch_free();
    const int32_t block_rows = blocks_ * kBlockY * kBlockZ;
    if (branch_free)
      launch(block_rows, NeighbourListFn<true>{search, raw(d.pos), h2, raw(neighbour_list_), raw(neighbour_count_), list_capacity_});
    else
      launch(block_rows, NeighbourListFn<false>{search, raw(d.pos), h2, raw(neighbour_list_), raw(neighbour_count_), list_capacity_});
    list_choice_.record(branch_free, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                        std::size_t(n));
#endif
  }

  GridView view(const GridGeometry& g) const {
    return GridView{g,
                    raw(key_),
                    raw(particle_block_),
                    raw(block_neighbours_),
                    raw(cell_start_),
                    list_capacity_ > 0 ? raw(neighbour_list_) : nullptr,
                    raw(neighbour_count_),
                    list_capacity_};
  }

 private:
  template <class T>
  static T* raw(DeviceVector<T>& v) {
    return thrust::raw_pointer_cast(v.data());
  }
  template <class T>
  static const T* raw(const DeviceVector<T>& v) {
    return thrust::raw_pointer_cast(v.data());
  }

  DeviceVector<uint64_t> key_, block_code_;
  DeviceVector<int32_t> order_, flag_, particle_block_, block_begin_, cell_start_, block_neighbours_;
  DeviceVector<int32_t> neighbour_list_, neighbour_count_;  // host build only
  int32_t list_capacity_ = 0;  // host build: neighbour_list_capacity at the last build; cuda: 0 (no lists)
  NeighbourListChoice list_choice_;
  int32_t blocks_ = 0;
};

}  // namespace SPH_DEVICE_NS
}  // namespace sph
