// The neighbour grid on the device back end: the steps of src/common/grid_build.h as data-parallel loops,
// a stable radix sort by cell key (CUB through Thrust under nvcc; Thrust's OpenMP sort on the host build)
// and prefix sums. Its memory grows with the particle count only (grid.h).
//
// The build never waits for the device: the block count is written into the step's summary, which the host
// reads once per step anyway (device_backend.cu), and the block tables are kept for a capacity of blocks
// grown from the counts read so far. The table kernel runs over the capacity, its threads past this build's
// count (read from device memory) doing nothing; blocks past the capacity have no tables and are searched
// without them (grid.h), until the next step's build has grown the capacity from this step's count.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <thrust/scan.h>
#include <thrust/sort.h>

#include "../common/grid_build.h"
#include "../common/neighbour_list.h"
#include "../common/neighbour_list_choice.h"
#include "../common/neighbour_rows.h"
#include "device_arrays.h"
#include "device_launch.h"
#include "device_reads.h"

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

// After the inclusive scan of the flags: block index from 0, each block's first particle and code, and the
// block count (into device memory: nobody waits for it).
struct RecordBlocksFn {
  const uint64_t* key;
  int32_t* particle_block;
  int32_t* block_begin;
  uint64_t* block_code;
  int32_t* block_count;
  int32_t n;
  SPH_HD void operator()(int32_t j) const {
    const int32_t b = particle_block[j] - 1;
    particle_block[j] = b;
    if (is_block_start(key, j)) {
      block_begin[b] = j;
      block_code[b] = block_of_key(key[j]);
    }
    if (j == n - 1) {
      block_begin[b + 1] = n;
      *block_count = b + 1;
    }
  }
};

// Over the tables' capacity: slot b >= the count holds no block in this build.
struct BlockTablesFn {
  const uint64_t* key;
  const int32_t* block_begin;
  const uint64_t* block_code;
  const int32_t* block_count;
  int32_t* cell_start;
  int32_t* block_neighbours;
  SPH_HD void operator()(int32_t b) const {
    const int32_t blocks = *block_count;
    if (b >= blocks) return;
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
  // Device bytes per particle for the grid: keys, order, flags, blocks, block starts and codes (one per
  // particle at most), and tables for at least 8 particles per block on average (a dense fluid fills a
  // block of 256 cells with about 256; a thin spray fewer).
  static constexpr std::size_t kBytesPerParticle =
      2 * sizeof(uint64_t) + 4 * sizeof(int32_t) + (kBlockTable + kBlockNeighbours) * sizeof(int32_t) / 8;

  // The first capacity of the tables: n / kFirstParticlesPerBlock blocks, at least kFirstBlocks (at most
  // n). When a count read back comes within an eighth of the capacity, the capacity grows to 1.5 times the
  // larger of the two: a fluid that spreads a little every step regrows rarely, and within one step it
  // may spread into an eighth more blocks before any is searched without tables.
  static constexpr int32_t kFirstBlocks = 16, kFirstParticlesPerBlock = 64;

  DeviceGrid() : fixed_capacity_(fixed_capacity_from_environment()) {}

  // Sorts d by (cell key, id) (sorted: the reordering buffer, swapped with d) and builds the tables.
  // block_count: device memory that receives the block count (the step's summary); blocks_seen: the latest
  // count the host has read (0 before any), from which the tables' capacity grows.
  template <class Policy>
  void build(const SimConstants& c, DeviceArrays& d, DeviceArrays& sorted, Policy policy, int32_t* block_count,
             int32_t blocks_seen) {
    const GridGeometry& g = c.grid;
    const int32_t n = int32_t(d.size());
    key_.resize(std::size_t(n));
    order_.resize(std::size_t(n));
    particle_block_.resize(std::size_t(n));
    block_count_ = block_count;
    if (n == 0) return;
    launch(n, CellKeyFn{g, raw(d.pos), raw(key_), raw(order_)});
    thrust::stable_sort_by_key(policy, key_.begin(), key_.end(), order_.begin());
    launch(n, SortCellsByIdFn{raw(key_), raw(d.id), raw(order_), n});
    sorted.gather_from(d, order_);
    std::swap(d, sorted);

    flag_.resize(std::size_t(n));
    launch(n, BlockStartFn{raw(key_), raw(flag_)});
    thrust::inclusive_scan(policy, flag_.begin(), flag_.end(), particle_block_.begin());
    block_begin_.resize(std::size_t(n) + 1);
    block_code_.resize(std::size_t(n));
    launch(n, RecordBlocksFn{raw(key_), raw(particle_block_), raw(block_begin_), raw(block_code_), block_count, n});
    fit_capacity(n, blocks_seen);
    launch(capacity_, BlockTablesFn{raw(key_), raw(block_begin_), raw(block_code_), block_count, raw(cell_start_),
                                    raw(block_neighbours_)});
#if !defined(__CUDACC__)
    list_capacity_ = neighbour_list_capacity(c);
    if (list_capacity_ == 0) return;  // no lists: every loop searches
    neighbour_list_.resize(std::size_t(n) * std::size_t(list_capacity_ + kNeighbourListPad));
    neighbour_count_.resize(std::size_t(n));
    GridView search = view(g, BoundaryView{}, nullptr, 0);
    search.neighbour_list = nullptr;
    const float h2 = neighbour_radius2(c);  // h^2, or PBF's wider list radius (neighbour_list.h)
    const auto t0 = std::chrono::steady_clock::now();
    const bool branch_free = list_choice_.branch_free();
    const int32_t block_rows = *block_count * kBlockY * kBlockZ;  // host memory in this build
    if (branch_free)
      launch(block_rows, NeighbourListFn<true>{search, raw(d.pos), h2, raw(neighbour_list_), raw(neighbour_count_), list_capacity_});
    else
      launch(block_rows, NeighbourListFn<false>{search, raw(d.pos), h2, raw(neighbour_list_), raw(neighbour_count_), list_capacity_});
    list_choice_.record(branch_free, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                        std::size_t(n));
#endif
  }

  GridView view(const GridGeometry& g, const BoundaryView& boundary, const BodyView* bodies, int32_t num_bodies) const {
    return GridView{g,
                    raw(key_),
                    raw(particle_block_),
                    raw(block_neighbours_),
                    raw(cell_start_),
                    list_capacity_ > 0 ? raw(neighbour_list_) : nullptr,
                    raw(neighbour_count_),
                    list_capacity_,
                    raw(block_begin_),
                    raw(block_code_),
                    block_count_,
                    capacity_,
                    boundary,
                    bodies,
                    num_bodies};
  }

 private:
  // SPH_DEVICE_BLOCK_CAPACITY=N in the environment fixes the capacity at N blocks (tests: every block
  // from N on is searched without tables); -1 when unset.
  static int32_t fixed_capacity_from_environment() {
    const char* env = std::getenv("SPH_DEVICE_BLOCK_CAPACITY");
    if (env == nullptr || *env == '\0') return -1;
    char* end = nullptr;
    const long long v = std::strtoll(env, &end, 10);
    if (*end != '\0' || v < 0 || v > INT32_MAX)
      throw std::invalid_argument("SPH_DEVICE_BLOCK_CAPACITY must be a block count from 0 to 2147483647, not \"" +
                                  std::string(env) + "\"");
    return int32_t(v);
  }

  // Sizes the tables for capacity_ blocks (kFirstBlocks above), never for more blocks than particles
  // (n: this build's particle count); never shrinks them.
  void fit_capacity(int32_t n, int32_t blocks_seen) {
    int64_t wanted = capacity_;
    if (fixed_capacity_ >= 0) {
      wanted = fixed_capacity_;
    } else if (!sized_) {
      wanted = std::min<int64_t>(n, std::max<int64_t>(kFirstBlocks, n / kFirstParticlesPerBlock));
      sized_ = true;
    } else if (8 * int64_t(blocks_seen) > 7 * int64_t(capacity_)) {
      wanted = std::min<int64_t>(n, 3 * std::max<int64_t>(capacity_, blocks_seen) / 2 + 1);
      if (wanted <= capacity_) return;
      ++device_counters().table_growths;
    }
    if (wanted == capacity_) return;
    capacity_ = int32_t(wanted);
    cell_start_.resize(std::size_t(capacity_) * kBlockTable);
    block_neighbours_.resize(std::size_t(capacity_) * kBlockNeighbours);
  }

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
  int32_t* block_count_ = nullptr;  // device memory: the last build's block count (the step's summary)
  int32_t fixed_capacity_;          // SPH_DEVICE_BLOCK_CAPACITY, or -1
  int32_t capacity_ = 0;            // blocks with tables
  bool sized_ = false;              // capacity_ set from a first build
};

}  // namespace SPH_DEVICE_NS
}  // namespace sph
