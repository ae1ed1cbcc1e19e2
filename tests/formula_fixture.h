// A particle set with its neighbour grid, for testing per-particle formulas (dfsph.h, pbf.h) directly:
// one fluid, the serial reference's grid (CpuBackend::build_grid), and the views the formulas read.
// Particles are reordered by the grid build: index the sorted state (cloud.state()), whose id gives the
// original index.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "common/grid.h"
#include "common/kernels.h"
#include "common/params.h"
#include "common/particle_state.h"
#include "cpu/cpu_backend.h"

namespace sph_test {

// count positions uniform in the cube [0, extent)^3 [m], drawn from rng (which then draws on).
inline std::vector<sph::Vec3> random_positions(std::mt19937& rng, int count, float extent) {
  std::uniform_real_distribution<float> coord(0.0f, extent);
  std::vector<sph::Vec3> pos;
  for (int i = 0; i < count; ++i) pos.push_back(sph::Vec3{coord(rng), coord(rng), coord(rng)});
  return pos;
}

// The cubic spline with support h and its dW/dr, in double, from the seed's form (seed 000 eqs. 5, 6) with
// smoothing length h_s = h / 2 (support 2 h_s = h), s = r / h_s: the reference the kernel and the DFSPH
// formulas are checked against.
inline double seed_cubic_w(double r, double h) {
  const double hs = 0.5 * h, s = r / hs, sigma = 1.0 / (3.14159265358979323846 * hs * hs * hs);
  if (s >= 2.0) return 0.0;
  if (s < 1.0) return sigma * (1.0 - 1.5 * s * s + 0.75 * s * s * s);
  return sigma * 0.25 * (2.0 - s) * (2.0 - s) * (2.0 - s);
}
inline double seed_cubic_dwdr(double r, double h) {
  const double hs = 0.5 * h, s = r / hs, sigma = 1.0 / (3.14159265358979323846 * hs * hs * hs);
  if (s >= 2.0) return 0.0;
  if (s < 1.0) return sigma / hs * (-3.0 * s + 2.25 * s * s);
  return sigma / hs * (-0.75 * (2.0 - s) * (2.0 - s));
}

struct FormulaCloud {
  FormulaCloud(const std::vector<sph::Vec3>& positions, double h, float mass, float rest_density)
      : backend(constants(h, mass, rest_density)) {
    sph::ParticleState s;
    s.resize(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
      s.pos[i] = positions[i];
      s.fluid[i] = 0;
      s.id[i] = int32_t(i);
    }
    backend.upload(s);
    backend.build_grid();
  }

  static sph::SimConstants constants(double h, float mass, float rest_density) {
    sph::SimConstants c{};
    c.kernel = sph::make_kernel_coeffs(h);
    c.density = sph::DensityMethod::Summation;
    c.grid.origin = sph::Vec3{0.0f, 0.0f, 0.0f};
    c.grid.cell_size = float(h) / sph::kGridReach;
    c.grid.reach = sph::kGridReach;
    c.grid.nx = c.grid.ny = c.grid.nz = 64;
    c.num_fluids = 1;
    c.fluids[0].mass = mass;
    c.fluids[0].rest_density = rest_density;
    return c;
  }

  const sph::SimConstants& c() const { return backend.constants(); }
  sph::ParticleState& state() { return backend.state(); }
  sph::ParticleView view() { return backend.state().view(); }
  sph::GridView grid() const { return backend.grid_view(); }
  int32_t size() const { return int32_t(backend.size()); }

  sph::CpuBackend backend;
};

// Points (i, j, k) d + origin of an n x n x n cubic lattice.
inline std::vector<sph::Vec3> cubic_lattice(int n, float d, sph::Vec3 origin) {
  std::vector<sph::Vec3> out;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) out.push_back(origin + d * sph::Vec3{float(i), float(j), float(k)});
  return out;
}

// Particles whose whole support lies inside the lattice: at least `margin` from its bounding box.
inline bool interior(sph::Vec3 x, sph::Vec3 lo, sph::Vec3 hi, float margin) {
  return x.x - lo.x >= margin && x.y - lo.y >= margin && x.z - lo.z >= margin && hi.x - x.x >= margin &&
         hi.y - x.y >= margin && hi.z - x.z >= margin;
}

}  // namespace sph_test
