// Uniform grid (src/common/grid.h, CpuBackend::build_grid): the neighbour sets found through the grid equal
// an O(N^2) brute force, for reach 1 and 2, uniform and clustered particles, particles far outside the grid
// (clamped into its border cells), empty regions and an empty particle set; and the sorted layout is
// consistent (cell_start monotone, ends at N, every particle inside its own cell's range, no particle lost).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "common/grid.h"
#include "common/kernels.h"
#include "common/params.h"
#include "common/particle_state.h"
#include "cpu/cpu_backend.h"

namespace {

using sph::Vec3;

sph::SimConstants make_constants(double h, Vec3 origin, float cell_size, int32_t reach, int32_t nx, int32_t ny,
                                 int32_t nz) {
  sph::SimConstants c{};
  c.kernel = sph::make_kernel_coeffs(h);
  c.grid.origin = origin;
  c.grid.cell_size = cell_size;
  c.grid.reach = reach;
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

  // cell_start: starts at 0, monotone, ends at N; every particle lies in its own cell's range.
  const int64_t ncells = sph::cell_count(g);
  REQUIRE(view.cell_start[0] == 0);
  for (int64_t cell = 0; cell < ncells; ++cell) REQUIRE(view.cell_start[cell] <= view.cell_start[cell + 1]);
  REQUIRE(view.cell_start[ncells] == int32_t(n));
  for (std::size_t i = 0; i < n; ++i) {
    const int32_t cell = sph::cell_index(g, s.pos[i]);
    REQUIRE(cell >= 0);
    REQUIRE(cell < ncells);
    INFO("particle " << i << " in cell " << cell);
    REQUIRE(view.cell_start[cell] <= int32_t(i));
    REQUIRE(int32_t(i) < view.cell_start[cell + 1]);
  }

  // Neighbour sets by id: grid against brute force.
  std::size_t pairs = 0;
  std::vector<int32_t> visited;
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3 pa = s.pos[a];
    std::set<int32_t> from_grid;
    visited.clear();
    sph::for_each_candidate(view, pa, [&](int32_t b) {
      visited.push_back(b);
      if (within(pa, s.pos[std::size_t(b)], h)) from_grid.insert(s.id[std::size_t(b)]);
    });
    std::set<int32_t> brute;
    for (std::size_t b = 0; b < n; ++b)
      if (within(pa, s.pos[b], h)) brute.insert(s.id[b]);
    INFO("particle id " << s.id[a] << " at (" << pa.x << ", " << pa.y << ", " << pa.z << "): grid finds "
                        << from_grid.size() << " neighbours, brute force " << brute.size());
    REQUIRE(from_grid == brute);
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

// The same domain [origin, origin + (1.0, 0.8, 0.6)] at reach 1 (cells of h), reach 2 (cells of h/2) and
// reach 1 with cells wider than h.
std::vector<GridCase> grid_cases(double h, Vec3 origin) {
  const float hf = float(h);
  return {
      {"reach 1", make_constants(h, origin, hf, 1, 10, 8, 6)},
      {"reach 2", make_constants(h, origin, 0.5f * hf, 2, 20, 16, 12)},
      {"reach 1, cells 1.3 h", make_constants(h, origin, 1.3f * hf, 1, 8, 7, 5)},
  };
}

}  // namespace

TEST_CASE("grid neighbour sets equal brute force: uniform random particles", "[grid]") {
  const double h = 0.1;
  const Vec3 origin{-0.3f, 0.1f, -0.2f};
  for (const GridCase& gc : grid_cases(h, origin)) {
    INFO(gc.name);
    std::mt19937 rng(12345);
    const std::vector<Vec3> p = uniform(rng, 1500, origin, Vec3{origin.x + 1.0f, origin.y + 0.8f, origin.z + 0.6f});
    CHECK(check_grid(gc.constants, p) > 1500);  // about 2 neighbours a particle: the case is not vacuous
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
      const int32_t only = sph::cell_index(c.grid, 3, 2, 1);
      for (const Vec3& q : p) REQUIRE(sph::cell_index(c.grid, q) == only);
      CHECK(check_grid(c, p) > 0);
      sph::CpuBackend backend(c);
      backend.upload(make_state(p));
      backend.build_grid();
      const sph::GridView view = backend.grid_view();
      CHECK(view.cell_start[only] == 0);
      CHECK(view.cell_start[only + 1] == 600);
    }
  }
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
    // Far outside in one coordinate only, at different positions along the border cells.
    append(p, uniform(rng, 100, Vec3{-50.0f, 0.0f, 0.0f}, Vec3{-49.9f, size.y, size.z}));
    append(p, uniform(rng, 100, Vec3{0.0f, 0.0f, 20.0f}, Vec3{size.x, size.y, 20.1f}));
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
    int visits = 0;
    for (const Vec3& q : {Vec3{0.5f, 0.4f, 0.3f}, Vec3{-10.0f, 0.0f, 100.0f}})
      sph::for_each_candidate(backend.grid_view(), q, [&](int32_t) { ++visits; });
    CHECK(visits == 0);
  }
}
