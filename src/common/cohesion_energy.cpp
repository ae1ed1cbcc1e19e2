#include "cohesion_energy.h"

#include <cmath>
#include <cstdint>

#include "calibration.h"
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

double akinci_adhesion_potential_shape(double q) {
  if (q >= 1.0) return 0.0;
  if (q < 0.5) q = 0.5;
  // s = 3/4 - cos(phi) / 4: phi from phi_q (s = q) to pi (s = 1); a ds = sqrt(sin / 2) sin / 4 dphi.
  const double pi = 3.14159265358979323846;
  const double lo = std::acos(3.0 - 4.0 * q), hi = pi;
  const int n = 512;
  const double step = (hi - lo) / n;
  const auto g = [](double phi) {
    const double s = std::sin(phi);
    return s > 0.0 ? 0.25 * s * std::sqrt(0.5 * s) : 0.0;
  };
  double sum = g(lo) + g(hi);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * g(lo + i * step);
  return sum * step / 3.0;
}

double adhesion_constant(double cohesion, double contact_angle_deg, double spacing, double h) {
  const double cos_theta = std::cos(contact_angle_deg * 3.14159265358979323846 / 180.0);
  const double b_cohesion = half_lattice_binding(spacing, h, [&](double r2) {
    return akinci_cohesion_potential_shape(std::sqrt(r2) / h);
  });
  const double b_adhesion = half_lattice_binding(spacing, h, [&](double r2) {
    return akinci_adhesion_potential_shape(std::sqrt(r2) / h);
  });
  return cohesion * 0.5 * (1.0 + cos_theta) * b_cohesion / b_adhesion;
}

double adhesion_first_layer_energy(double adhesion, double mass, double spacing, double h) {
  // The first layer at d / 2 from the wall, the wall's layers at d / 2, 3 d / 2, ... behind it.
  const double sum = half_lattice_binding(
      spacing, h, [&](double r2) { return akinci_adhesion_potential_shape(std::sqrt(r2) / h); }, true);
  return adhesion * mass * h * sum;
}

double csf_contact_energy(double sigma, double contact_angle_deg, double spacing, double mass) {
  return sigma * (1.0 + std::cos(contact_angle_deg * 3.14159265358979323846 / 180.0)) * spacing * spacing / mass;
}

std::vector<double> cohesion_excess_energy(const SimConstants& c, const ParticleState& ps, double spacing) {
  std::vector<double> excess(ps.size(), 0.0);
  // PBF has no cohesion (it ignores surface_tension under that model, said at set-up): nothing to release.
  // Under the continuum surface force it is counted as under the other solvers. Either surface-tension model: the cohesion constant calibrated to sigma measures the surface energy.
  // The cohesion between two fluids (an interface tension): as a force under the cohesion model, for this
  // estimate of the interface's energy under either.
  bool cross = false;
  for (int32_t a = 0; a < c.num_fluids; ++a)
    for (int32_t b = 0; b < c.num_fluids; ++b) cross = cross || c.cross_cohesion[a][b] != 0.0f;
  if (!(c.surface_tension_enabled || c.csf_enabled || cross) || (c.solver == Solver::Pbf && !c.csf_enabled) || ps.size() == 0)
    return excess;
  const double h = c.kernel.h;
  // A particle's share in the bulk: half the sum over a full cubic lattice of spacing d, per unit mass^2.
  const double lattice = lattice_sum(spacing, h, [&](double r2) {
    return r2 > 0.0 ? akinci_cohesion_potential_shape(std::sqrt(r2) / h) : 0.0;
  });
  const HostNeighbours neighbours(ps, h, [&](std::size_t a) { return ps.age[a] < kRemovedAge; });
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const FluidConstants& f = c.fluids[ps.fluid[a]];
    bool with_others = false;
    for (int32_t k = 0; cross && k < c.num_fluids; ++k) with_others = with_others || c.cross_cohesion[ps.fluid[a]][k] != 0.0f;
    if ((f.cohesion == 0.0f && !with_others) || ps.age[a] >= kRemovedAge) continue;
    double sum = 0.0;  // sum_b int_{r/h}^1 c over a's fluid
    double other = 0.0;  // sum_b K_ab m_b int_{r/h}^1 c over the other fluids
    neighbours.for_each(a, [&](std::size_t b, Vec3 x) {
      const double r = std::sqrt(double(x.x) * x.x + double(x.y) * x.y + double(x.z) * x.z);
      if (!(r < h)) return;
      if (ps.fluid[b] == ps.fluid[a]) sum += akinci_cohesion_potential_shape(r / h);
      else if (cross) other += double(c.cross_cohesion[ps.fluid[a]][ps.fluid[b]]) * double(c.fluids[ps.fluid[b]].mass) *
                               akinci_cohesion_potential_shape(r / h);
    });
    // (e_a - e_bulk) / m_a = 1/2 m (-constant h) (sum - lattice): u / (m_a m_b) = -constant h int_{r/h}^1 c,
    // the fluid's cohesion constant being gamma 32 / (pi h^3), and the neighbours have a's mass (one fluid);
    // a pair with another fluid adds 1/2 (-K_ab m_b h) int c (negative where they attract: an interface costs
    // less than the two surfaces, positive where they repel).
    const double e = 0.5 * double(f.mass) * (-double(f.cohesion) * h) * (sum - lattice) - 0.5 * h * other;
    excess[a] = e > 0.0 ? e : 0.0;
  }
  return excess;
}

std::vector<double> lattice_surface_energy(const Scene& scene, const SimConstants& c, const ParticleState& ps, double spacing) {
  std::vector<double> energy(ps.size(), 0.0);
  if (ps.size() == 0) return energy;
  const HostNeighbours neighbours(ps, c.kernel.h, [&](std::size_t a) { return ps.age[a] < kRemovedAge; });
  const double d = spacing, tolerance2 = 0.0625 * d * d;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const double sigma = scene.fluids[ps.fluid[a]].surface_tension;
    if (sigma == 0.0 || ps.age[a] >= kRemovedAge) continue;
    bool covered[6] = {};  // +x, -x, +y, -y, +z, -z
    neighbours.for_each_same_fluid(a, [&](std::size_t, Vec3 x) {  // x = x_a - x_b: b at the site x_a + d e
      const double bx = -double(x.x), by = -double(x.y), bz = -double(x.z);
      for (int e = 0; e < 6; ++e) {
        const double s = e % 2 ? -d : d;
        const double ex = bx - (e / 2 == 0 ? s : 0.0), ey = by - (e / 2 == 1 ? s : 0.0), ez = bz - (e / 2 == 2 ? s : 0.0);
        if (ex * ex + ey * ey + ez * ez < tolerance2) covered[e] = true;
      }
    });
    int open = 0;
    for (bool k : covered) open += k ? 0 : 1;
    energy[a] = sigma * d * d * open / double(c.fluids[ps.fluid[a]].mass);
  }
  return energy;
}

std::optional<double> least_surface_energy(const Scene& scene, const SimConstants& c, const ParticleState& ps) {
  if (!csf_free_drop(scene)) return std::nullopt;
  double volume[kMaxFluids] = {};
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.age[i] < kRemovedAge) volume[ps.fluid[i]] += double(c.fluids[ps.fluid[i]].mass) / c.fluids[ps.fluid[i]].rest_density;
  const double pi = 3.14159265358979323846;
  double least = 0.0;
  for (int32_t f = 0; f < c.num_fluids; ++f)
    least += scene.fluids[std::size_t(f)].surface_tension * 4.0 * pi * std::pow(3.0 * volume[f] / (4.0 * pi), 2.0 / 3.0);
  return least;
}

}  // namespace sph
