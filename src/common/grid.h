// Uniform grid shared by every back end: cell of a position (clamped into the grid, so any position is
// valid) and the neighbour loop. Particles are stored in cell order (x fastest), so the cells x-R .. x+R
// of one row are one contiguous index range: (2R+1)^2 ranges instead of (2R+1)^3 cells.
#pragma once

#include <cstdint>

#include "particle_view.h"
#include "sph_hd.h"

namespace sph {

SPH_HD inline int32_t clamp_cell(float coord, float origin, float inv_cell, int32_t n) {
  int32_t c = int32_t(floorf((coord - origin) * inv_cell));
  return c < 0 ? 0 : (c >= n ? n - 1 : c);
}

struct CellCoord {
  int32_t x, y, z;
};

SPH_HD inline CellCoord cell_of(const GridGeometry& g, Vec3 p) {
  const float inv = 1.0f / g.cell_size;
  return {clamp_cell(p.x, g.origin.x, inv, g.nx), clamp_cell(p.y, g.origin.y, inv, g.ny),
          clamp_cell(p.z, g.origin.z, inv, g.nz)};
}

SPH_HD inline int32_t cell_index(const GridGeometry& g, int32_t x, int32_t y, int32_t z) {
  return (z * g.ny + y) * g.nx + x;
}

SPH_HD inline int32_t cell_index(const GridGeometry& g, Vec3 p) {
  const CellCoord c = cell_of(g, p);
  return cell_index(g, c.x, c.y, c.z);
}

SPH_HD inline int64_t cell_count(const GridGeometry& g) { return int64_t(g.nx) * g.ny * g.nz; }

// Calls f(b) for every particle b in the cells within `reach` of position p's cell (its own included).
// The caller tests the distance: reach cells span at least h, so every particle within h is visited.
template <class F>
SPH_HD inline void for_each_candidate(const GridView& grid, Vec3 p, F&& f) {
  const GridGeometry& g = grid.geom;
  const CellCoord c = cell_of(g, p);
  const int32_t r = g.reach;
  const int32_t x0 = c.x > r ? c.x - r : 0;
  const int32_t x1 = c.x < g.nx - 1 - r ? c.x + r : g.nx - 1;
  const int32_t z0 = c.z > r ? c.z - r : 0, z1 = c.z < g.nz - 1 - r ? c.z + r : g.nz - 1;
  const int32_t y0 = c.y > r ? c.y - r : 0, y1 = c.y < g.ny - 1 - r ? c.y + r : g.ny - 1;
  for (int32_t z = z0; z <= z1; ++z) {
    for (int32_t y = y0; y <= y1; ++y) {
      const int32_t begin = grid.cell_start[cell_index(g, x0, y, z)];
      const int32_t end = grid.cell_start[cell_index(g, x1, y, z) + 1];
      for (int32_t b = begin; b < end; ++b) f(b);
    }
  }
}

// Puts the particles of one cell, order[begin, end), in ascending id order (insertion sort: cells hold a
// few dozen particles and arrive nearly sorted). Both back ends sort every cell this way after binning,
// so the particle order, and with it every floating-point sum, depends only on the particle set, not on
// the previous order or on the timing of atomic operations.
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
