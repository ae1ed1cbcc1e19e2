#include "cohesion_energy.h"

#include <cmath>
#include <cstdint>

#include "host_neighbours.h"
#include "lattice_sum.h"

namespace sph {

namespace {

// Antiderivative of s^3 (1 - s)^3.
double shape_antiderivative(double s) {
  const double s4 = s * s * s * s;
  return s4 * (0.25 - 0.6 * s + 0.5 * s * s - s * s * s / 7.0);
}

}  // namespace

double akinci_cohesion_potential_shape(double q) {
  if (q >= 1.0) return 0.0;
  const double full = shape_antiderivative(1.0);  // 1 / 140
  if (q > 0.5) return full - shape_antiderivative(q);
  const double outer = full - shape_antiderivative(0.5);
  return outer + 2.0 * (shape_antiderivative(0.5) - shape_antiderivative(q)) - (0.5 - q) / 64.0;
}

std::vector<double> cohesion_excess_energy(const SimConstants& c, const ParticleState& ps, double spacing) {
  std::vector<double> excess(ps.size(), 0.0);
  // PBF has no cohesion (it ignores surface_tension, said at set-up): nothing to release.
  // Either surface-tension model: the cohesion constant calibrated to sigma measures the surface energy.
  if (!(c.surface_tension_enabled || c.csf_enabled) || c.solver == Solver::Pbf || ps.size() == 0) return excess;
  const double h = c.kernel.h;
  // A particle's share in the bulk: half the sum over a full cubic lattice of spacing d, per unit mass^2.
  const double lattice = lattice_sum(spacing, h, [&](double r2) {
    return r2 > 0.0 ? akinci_cohesion_potential_shape(std::sqrt(r2) / h) : 0.0;
  });
  const HostNeighbours neighbours(ps, h, [&](std::size_t a) { return ps.age[a] < kRemovedAge; });
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const FluidConstants& f = c.fluids[ps.fluid[a]];
    if (f.cohesion == 0.0f || ps.age[a] >= kRemovedAge) continue;
    double sum = 0.0;  // sum_b int_{r/h}^1 c over a's fluid
    neighbours.for_each_same_fluid(a, [&](std::size_t, Vec3 x) {
      const double r = std::sqrt(double(x.x) * x.x + double(x.y) * x.y + double(x.z) * x.z);
      if (r < h) sum += akinci_cohesion_potential_shape(r / h);
    });
    // (e_a - e_bulk) / m_a = 1/2 m (-constant h) (sum - lattice): u / (m_a m_b) = -constant h int_{r/h}^1 c,
    // the fluid's cohesion constant being gamma 32 / (pi h^3), and the neighbours have a's mass (one fluid).
    const double e = 0.5 * double(f.mass) * (-double(f.cohesion) * h) * (sum - lattice);
    excess[a] = e > 0.0 ? e : 0.0;
  }
  return excess;
}

}  // namespace sph
