// Neighbour grid (src/common/grid.h, grid_build.h, CpuBackend::build_grid): the neighbour sets found through
// the grid equal an O(N^2) brute force, every way of listing them gives the direct search's list in its order, for uniform and clustered particles, particles far outside the
// domain (beyond the keys' range they share border cells), empty regions and an empty particle set; and the
// sorted layout is consistent (ascending (key, id), every particle inside its own cell's range of its
// block's table, tables monotone, no particle lost).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/grid.h"
#include "common/neighbour_list.h"
#include "common/neighbour_list_choice.h"
#include "common/neighbour_rows.h"
#include "common/kernels.h"
#include "common/params.h"
#include "common/particle_state.h"
#include "cpu/cpu_backend.h"

namespace {

using sph::Vec3;

sph::SimConstants make_constants(double h, Vec3 origin, int32_t nx, int32_t ny, int32_t nz) {
  sph::SimConstants c{};
  c.kernel = sph::make_kernel_coeffs(h);
  c.grid.origin = origin;
  c.grid.cell_size = float(h) / sph::kGridReach;
  c.grid.reach = sph::kGridReach;
  c.grid.nx = nx;
  c.grid.ny = ny;
  c.grid.nz = nz;
  return c;
}

sph::ParticleState make_state(const std::vector<Vec3>& positions) {
  sph::ParticleState s;
  s.resize(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    s.pos[i] = positions[i];
    s.vel[i] = Vec3{0.0f, 0.0f, 0.0f};
    s.fluid[i] = 0;
    s.id[i] = int32_t(i);
  }
  return s;
}

bool within(Vec3 a, Vec3 b, float h) { return sph::length2(a - b) < h * h; }

// Runs the whole check on one configuration; returns the number of neighbour pairs found (to make sure a
// case is not vacuous).
std::size_t check_grid(const sph::SimConstants& c, const std::vector<Vec3>& positions) {
  const float h = c.kernel.h;
  const std::size_t n = positions.size();
  sph::CpuBackend backend(c);
  backend.upload(make_state(positions));
  backend.build_grid();
  const sph::ParticleState& s = backend.state();
  const sph::GridView view = backend.grid_view();
  const sph::GridGeometry& g = view.geom;
  REQUIRE(s.size() == n);

  // The reordering is a permutation that moves every field with its particle.
  std::vector<int> seen(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const int32_t id = s.id[i];
    REQUIRE(id >= 0);
    REQUIRE(std::size_t(id) < n);
    ++seen[std::size_t(id)];
    CHECK(s.pos[i].x == positions[std::size_t(id)].x);
    CHECK(s.pos[i].y == positions[std::size_t(id)].y);
    CHECK(s.pos[i].z == positions[std::size_t(id)].z);
  }
  for (std::size_t i = 0; i < n; ++i) REQUIRE(seen[i] == 1);

  // Keys ascending by (key, id), each particle's key its cell's, inside its cell's range of its block's table.
  for (std::size_t i = 0; i < n; ++i) {
    INFO("particle " << i);
    REQUIRE(view.key[i] == sph::cell_key(g, s.pos[i]));
    if (i > 0) {
      REQUIRE(view.key[i - 1] <= view.key[i]);
      if (view.key[i - 1] == view.key[i]) REQUIRE(s.id[i - 1] < s.id[i]);
    }
    const int32_t* table = view.cell_start + int64_t(view.particle_block[i]) * sph::kBlockTable;
    const uint64_t local = view.key[i] & sph::kLocalMask;
    REQUIRE(table[local] <= int32_t(i));
    REQUIRE(int32_t(i) < table[local + 1]);
    for (int32_t l = 0; l < sph::kCellsPerBlock; ++l) REQUIRE(table[l] <= table[l + 1]);
    REQUIRE(view.block_neighbours[int64_t(view.particle_block[i]) * sph::kBlockNeighbours + 13] == view.particle_block[i]);
  }

  // The neighbour lists, made per particle (list_neighbours) and per row of cells (neighbour_rows.h, as
  // the back ends make them), each with a branch and without: exactly the direct search's neighbours, in
  // its order (the order of every sum, which the GPU's direct search must match bit for bit).
  const int32_t capacity = int32_t(n) + 4;
  const std::size_t stride = std::size_t(capacity + sph::kNeighbourListPad);
  std::vector<int32_t> by_rows[2], by_rows_count[2];
  for (int variant = 0; variant < 2; ++variant) {
    by_rows[variant].assign(n * stride, -1);
    by_rows_count[variant].assign(n, -1);
    int32_t blocks = 0;
    for (std::size_t i = 0; i < n; ++i) blocks = std::max(blocks, view.particle_block[i] + 1);
    for (int32_t b = 0; b < blocks; ++b)
      for (int32_t row = 0; row < sph::kBlockY * sph::kBlockZ; ++row) {
        if (variant == 0)
          sph::neighbour_rows::list_row_neighbours<false>(view, s.pos.data(), c.kernel.h2, b, row, by_rows[0].data(),
                                                          by_rows_count[0].data(), capacity);
        else
          sph::neighbour_rows::list_row_neighbours<true>(view, s.pos.data(), c.kernel.h2, b, row, by_rows[1].data(),
                                                         by_rows_count[1].data(), capacity);
      }
  }
  std::vector<int32_t> list(stride);
  for (std::size_t a = 0; a < n; ++a) {
    std::vector<int32_t> direct;
    sph::for_each_candidate(view, int32_t(a), [&](int32_t b) {
      if (sph::length2(s.pos[a] - s.pos[std::size_t(b)]) < c.kernel.h2) direct.push_back(b);
    });
    INFO("particle " << a << " with " << direct.size() << " neighbours");
    const auto same = [&](const int32_t* got, int32_t count) {
      return count == int32_t(direct.size()) && std::equal(direct.begin(), direct.end(), got);
    };
    REQUIRE(same(list.data(), sph::list_neighbours<false>(view, s.pos.data(), int32_t(a), c.kernel.h2, list.data(), capacity)));
    REQUIRE(same(list.data(), sph::list_neighbours<true>(view, s.pos.data(), int32_t(a), c.kernel.h2, list.data(), capacity)));
    for (int variant = 0; variant < 2; ++variant)
      REQUIRE(same(by_rows[variant].data() + a * stride, by_rows_count[variant][a]));
    // The back end's own list, where it holds them all.
    if (view.neighbour_list != nullptr && view.neighbour_count[a] < view.list_capacity)
      REQUIRE(same(view.neighbour_list + a * std::size_t(view.list_capacity + sph::kNeighbourListPad),
                   view.neighbour_count[a]));
  }

  // Neighbour sets by id: grid against brute force.
  std::size_t pairs = 0;
  std::vector<int32_t> visited;
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3 pa = s.pos[a];
    std::set<int32_t> from_grid, from_neighbour_loop;
    visited.clear();
    sph::for_each_candidate(view, int32_t(a), [&](int32_t b) {
      visited.push_back(b);
      if (within(pa, s.pos[std::size_t(b)], h)) from_grid.insert(s.id[std::size_t(b)]);
    });
    // The GPU's schedule of the search gives the same ranges in the same order as the CPU's.
    std::vector<std::pair<int32_t, int32_t>> nested, by_counter;
    sph::candidate_ranges_nested(view, int32_t(a), [&](int32_t b, int32_t e) { nested.emplace_back(b, e); });
    sph::candidate_ranges_by_counter(view, int32_t(a), [&](int32_t b, int32_t e) { by_counter.emplace_back(b, e); });
    REQUIRE(nested == by_counter);
    sph::for_each_neighbour(view, s.pos.data(), int32_t(a), c.kernel.h2, [&](int32_t b, Vec3 xab, float r2) {
      REQUIRE(r2 == sph::length2(xab));
      from_neighbour_loop.insert(s.id[std::size_t(b)]);
    });
    std::set<int32_t> brute;
    for (std::size_t b = 0; b < n; ++b)
      if (within(pa, s.pos[b], h)) brute.insert(s.id[b]);
    INFO("particle id " << s.id[a] << " at (" << pa.x << ", " << pa.y << ", " << pa.z << "): grid finds "
                        << from_grid.size() << " neighbours, brute force " << brute.size());
    REQUIRE(from_grid == brute);
    REQUIRE(from_neighbour_loop == brute);
    // Every candidate is a valid index, visited once.
    std::sort(visited.begin(), visited.end());
    REQUIRE(std::adjacent_find(visited.begin(), visited.end()) == visited.end());
    if (!visited.empty()) {
      REQUIRE(visited.front() >= 0);
      REQUIRE(visited.back() < int32_t(n));
    }
    pairs += brute.size() - 1;  // not counting itself
  }
  return pairs;
}

std::vector<Vec3> uniform(std::mt19937& rng, std::size_t count, Vec3 lo, Vec3 hi) {
  std::uniform_real_distribution<float> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  std::vector<Vec3> p;
  for (std::size_t i = 0; i < count; ++i) p.push_back(Vec3{ux(rng), uy(rng), uz(rng)});
  return p;
}

void append(std::vector<Vec3>& to, const std::vector<Vec3>& from) { to.insert(to.end(), from.begin(), from.end()); }

struct GridCase {
  std::string name;
  sph::SimConstants constants;
};

// The same domain [origin, origin + (1.0, 0.8, 0.6)] with h = 0.1 and with h = 0.037 (cells of h / 2 whose
// boundaries fall elsewhere; blocks 2.4 h and 1.2 h wide).
std::vector<GridCase> grid_cases(double h, Vec3 origin) {
  return {
      {"h", make_constants(h, origin, 20, 16, 12)},
      {"0.37 h", make_constants(0.37 * h, origin, 54, 44, 33)},
  };
}

}  // namespace

TEST_CASE("grid neighbour sets equal brute force: uniform random particles, sparse and dense", "[grid]") {
  const double h = 0.1;
  const Vec3 origin{-0.3f, 0.1f, -0.2f};
  struct Cloud {
    const char* what;
    unsigned seed;
    std::size_t count;
    Vec3 lo, hi;          // offsets from the origin
    std::size_t pairs;    // at least this many neighbour pairs: the case is not vacuous
  };
  const Cloud clouds[] = {
      // 2 (h) and 0.66 (0.37 h) neighbours a particle.
      {"sparse", 12345, 1500, Vec3{0.0f, 0.0f, 0.0f}, Vec3{1.0f, 0.8f, 0.6f}, 800},
      // About 2.3 particles per cell of h / 2: rows of 5 cells hold about 12 candidates (more than the 8 a
      // range is copied as at once, neighbour_rows.h), and a particle has about 290 in all (fewer than the
      // 384 gathered at most); about 40 (h) and 4 (0.37 h) neighbours a particle.
      {"dense", 31337, 1200, Vec3{0.1f, 0.1f, 0.1f}, Vec3{0.5f, 0.5f, 0.5f}, 3000},
  };
  for (const Cloud& cloud : clouds)
    for (const GridCase& gc : grid_cases(h, origin)) {
      INFO(cloud.what << ", " << gc.name);
      std::mt19937 rng(cloud.seed);
      const std::vector<Vec3> p = uniform(rng, cloud.count, origin + cloud.lo, origin + cloud.hi);
      CHECK(check_grid(gc.constants, p) > cloud.pairs);
    }
}

TEST_CASE("grid neighbour sets equal brute force: clustered particles", "[grid]") {
  const double h = 0.1;
  const Vec3 origin{0.0f, 0.0f, 0.0f};
  for (const GridCase& gc : grid_cases(h, origin)) {
    INFO(gc.name);
    std::mt19937 rng(777);
    std::vector<Vec3> p;
    // Three dense clusters, one straddling cell boundaries, one in a grid corner, plus sparse particles.
    append(p, uniform(rng, 400, Vec3{0.42f, 0.31f, 0.22f}, Vec3{0.47f, 0.36f, 0.27f}));
    append(p, uniform(rng, 400, Vec3{0.18f, 0.48f, 0.28f}, Vec3{0.23f, 0.53f, 0.33f}));
    append(p, uniform(rng, 300, Vec3{0.0f, 0.0f, 0.0f}, Vec3{0.04f, 0.04f, 0.04f}));
    append(p, uniform(rng, 100, Vec3{0.0f, 0.0f, 0.0f}, Vec3{1.0f, 0.8f, 0.6f}));
    CHECK(check_grid(gc.constants, p) > 100000);
  }
  SECTION("all particles in one cell") {
    for (const GridCase& gc : grid_cases(h, origin)) {
      INFO(gc.name);
      std::mt19937 rng(4242);
      const float cell = gc.constants.grid.cell_size;
      // Strictly inside cell (3, 2, 1).
      const Vec3 lo{3.01f * cell, 2.01f * cell, 1.01f * cell}, hi{3.99f * cell, 2.99f * cell, 1.99f * cell};
      const std::vector<Vec3> p = uniform(rng, 600, lo, hi);
      const sph::SimConstants& c = gc.constants;
      const uint64_t only = sph::cell_key(c.grid, lo);
      for (const Vec3& q : p) REQUIRE(sph::cell_key(c.grid, q) == only);
      CHECK(check_grid(c, p) > 0);
      sph::CpuBackend backend(c);
      backend.upload(make_state(p));
      backend.build_grid();
      const sph::GridView view = backend.grid_view();
      const int32_t* table = view.cell_start;  // the only block
      CHECK(view.particle_block[599] == 0);
      CHECK(table[only & sph::kLocalMask] == 0);
      CHECK(table[(only & sph::kLocalMask) + 1] == 600);
    }
  }
}

TEST_CASE("grid order: a sorted state with some particles moved far ahead or behind sorts as from scratch", "[grid]") {
  // The CPU grid build keeps the previous order's ascending run and sorts only the records out of place
  // (CpuBackend::build_grid): particles jumping many blocks ahead or behind, one next to another, and the
  // first and last particle moving, must still give the unique (key, id) order.
  const sph::SimConstants c = make_constants(0.1, Vec3{0.0f, 0.0f, 0.0f}, 20, 16, 12);
  std::vector<Vec3> lattice;
  for (int z = 0; z < 12; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 20; ++x) lattice.push_back(Vec3{0.025f + 0.05f * x, 0.025f + 0.05f * y, 0.025f + 0.05f * z});
  sph::CpuBackend backend(c);
  backend.upload(make_state(lattice));
  backend.build_grid();
  sph::ParticleState moved = backend.state();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> ux(0.0f, 1.0f), uy(0.0f, 0.8f), uz(0.0f, 0.6f);
  std::uniform_int_distribution<std::size_t> pick(0, moved.size() - 1);
  for (int k = 0; k < 200; ++k) moved.pos[pick(rng)] = Vec3{ux(rng), uy(rng), uz(rng)};
  moved.pos.front() = Vec3{0.99f, 0.79f, 0.59f};
  moved.pos.back() = Vec3{0.001f, 0.001f, 0.001f};
  moved.pos[1000] = moved.pos[1001] = Vec3{0.9f, 0.7f, 0.5f};
  backend.upload(moved);
  backend.build_grid();
  const sph::ParticleState& s = backend.state();
  const sph::GridView view = backend.grid_view();
  REQUIRE(s.size() == lattice.size());
  std::vector<int> seen(s.size(), 0);
  for (std::size_t i = 0; i < s.size(); ++i) {
    ++seen[std::size_t(s.id[i])];
    REQUIRE(view.key[i] == sph::cell_key(c.grid, s.pos[i]));
    if (i > 0) REQUIRE((view.key[i - 1] < view.key[i] || (view.key[i - 1] == view.key[i] && s.id[i - 1] < s.id[i])));
  }
  for (int count : seen) REQUIRE(count == 1);
}

TEST_CASE("grid neighbour sets equal brute force: particles far outside the grid on every side", "[grid]") {
  const double h = 0.1;
  const Vec3 origin{0.0f, 0.0f, 0.0f};
  const Vec3 size{1.0f, 0.8f, 0.6f};
  for (const GridCase& gc : grid_cases(h, origin)) {
    INFO(gc.name);
    std::mt19937 rng(99);
    std::vector<Vec3> p = uniform(rng, 500, origin, size);
    // Small clouds (with neighbours among themselves) far outside each face, edge and corner, and clouds
    // just outside the faces, within h of particles inside.
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const auto place = [](int d, float extent, float offset) {
            return d < 0 ? -offset : (d > 0 ? extent + offset : 0.5f * extent);
          };
          for (float offset : {3.0f, 0.03f}) {
            const Vec3 centre{place(dx, size.x, offset), place(dy, size.y, offset), place(dz, size.z, offset)};
            append(p, uniform(rng, 15, centre - Vec3{0.04f, 0.04f, 0.04f}, centre + Vec3{0.04f, 0.04f, 0.04f}));
          }
        }
    // Far outside in one coordinate only; and beyond the keys' range (about 2^19 h), where particles share
    // the border cells, also with infinite and huge coordinates.
    append(p, uniform(rng, 100, Vec3{-50.0f, 0.0f, 0.0f}, Vec3{-49.9f, size.y, size.z}));
    append(p, uniform(rng, 100, Vec3{0.0f, 0.0f, 20.0f}, Vec3{size.x, size.y, 20.1f}));
    append(p, uniform(rng, 50, Vec3{0.0f, 0.0f, 1e6f}, Vec3{0.05f, 0.05f, 1e6f}));
    append(p, {Vec3{0.0f, 0.0f, 3e38f}, Vec3{0.0f, 0.0f, -3e38f}, Vec3{1e30f, -1e30f, 0.0f}});
    CHECK(check_grid(gc.constants, p) > 1000);
  }
}

TEST_CASE("grid neighbour sets equal brute force: empty regions and no particles", "[grid]") {
  const double h = 0.1;
  const Vec3 origin{0.0f, 0.0f, 0.0f};
  for (const GridCase& gc : grid_cases(h, origin)) {
    INFO(gc.name);
    std::mt19937 rng(2024);
    // Two slabs with an empty region (many empty cells, whole empty rows) between them.
    std::vector<Vec3> p = uniform(rng, 500, Vec3{0.0f, 0.0f, 0.0f}, Vec3{0.25f, 0.8f, 0.6f});
    append(p, uniform(rng, 500, Vec3{0.8f, 0.0f, 0.4f}, Vec3{1.0f, 0.8f, 0.6f}));
    CHECK(check_grid(gc.constants, p) > 500);

    // No particles at all: every cell empty, no candidate anywhere.
    CHECK(check_grid(gc.constants, {}) == 0);
    sph::CpuBackend backend(gc.constants);
    backend.upload(make_state({}));
    backend.build_grid();
    CHECK(backend.state().size() == 0);
  }
}

TEST_CASE("neighbour lists: capacity from the expected neighbour count, none where lists would be too long", "[grid]") {
  sph::SimConstants c = make_constants(0.1, Vec3{0.0f, 0.0f, 0.0f}, 10, 10, 10);
  c.num_fluids = 1;
  c.fluids[0].rest_density = 1000.0f;
  const double ball = 4.0 / 3.0 * sph::kPiDouble * 0.001;  // 4/3 pi h^3
  auto with_neighbours = [&](double n) {
    c.fluids[0].mass = float(ball * 1000.0 / n);
    return sph::neighbour_list_capacity(c);
  };
  CHECK(with_neighbours(32.0) == 64);   // twice the expected count
  CHECK(with_neighbours(33.0) == 68);   // a multiple of 4
  CHECK(with_neighbours(5.0) == 32);    // at least 32
  CHECK(with_neighbours(127.0) == 256);
  CHECK(with_neighbours(200.0) == 0);   // no lists: every loop searches
  // A second, denser fluid sets the capacity.
  c.num_fluids = 2;
  c.fluids[0].mass = float(ball * 1000.0 / 20.0);
  c.fluids[1].rest_density = 1000.0f;
  c.fluids[1].mass = float(ball * 1000.0 / 40.0);
  CHECK(sph::neighbour_list_capacity(c) == 80);
}

TEST_CASE("neighbour lists: the faster way is kept, the other probed less often while it keeps losing", "[grid]") {
  sph::NeighbourListChoice choice;
  double cost[2] = {1.0, 2.0};  // seconds per particle: [0] with a branch, [1] branch-free
  std::vector<long> probes;     // builds at which the slower way ran
  auto run = [&](long builds, long from) {
    for (long b = from; b < from + builds; ++b) {
      const bool branch_free = choice.branch_free();
      if (cost[branch_free ? 1 : 0] > cost[branch_free ? 0 : 1]) probes.push_back(b);
      choice.record(branch_free, cost[branch_free ? 1 : 0], 1);
    }
  };
  run(2000, 0);
  // Both timed at the start (the branch-free way first, the choice flips to the branch at build 1), then
  // probes at growing intervals: 32 builds after the flip, then 64, ... up to 512.
  REQUIRE(probes.size() >= 6);
  CHECK(probes[0] == 0);
  std::vector<long> gaps;
  for (std::size_t i = 1; i < probes.size(); ++i) gaps.push_back(probes[i] - probes[i - 1]);
  CHECK(gaps[0] == 1 + 32);
  CHECK(gaps[1] == 64);
  CHECK(gaps[2] == 128);
  CHECK(gaps[3] == 256);
  CHECK(gaps[4] == 512);
  CHECK(gaps.back() == 512);
  CHECK(choice.probe_interval() == sph::NeighbourListChoice::kLastProbe);
  CHECK_FALSE(choice.branch_free());
  // The fluid splashes: the branch used becomes slower than the branch-free way was. The choice flips
  // within a few builds (the averages' lag), not at the next probe 512 builds away, and probing starts
  // again at the first interval.
  cost[0] = 3.0;
  cost[1] = 1.0;
  long flipped_at = -1;
  for (long b = 2000; b < 2600 && flipped_at < 0; ++b) {
    const bool branch_free = choice.branch_free();
    choice.record(branch_free, cost[branch_free ? 1 : 0], 1);
    if (choice.branch_free() && choice.probe_interval() == sph::NeighbourListChoice::kFirstProbe) flipped_at = b;
  }
  CHECK(flipped_at >= 2000);
  CHECK(flipped_at < 2000 + 4);
}
