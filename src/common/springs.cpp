#include "springs.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "host_neighbours.h"
#include "lattice_sum.h"

namespace sph {

SpringLaw spring_law(double modulus, double spacing, double h) {
  if (!(modulus > 0.0)) return SpringLaw{0.0, 0.0};
  const double d = spacing;
  // sum over the bonds b of (d / r_b)^p f(x_b, y_b) / r_b^2
  const auto bond_sum = [&](double p, auto&& f) {
    return lattice_sum_xyz(d, h, [&](double x, double y, double z) {
      const double r2 = x * x + y * y + z * z;
      return r2 > 0.0 ? std::pow(d * d / r2, 0.5 * p) * f(x, y) / r2 : 0.0;
    });
  };
  // The cubic anisotropy C11 - C12 - 2 C44 and the shear modulus C44, times 2 d^3 / k.
  const auto anisotropy = [&](double p) { return bond_sum(p, [](double x, double y) { return x * x * (x * x - 3.0 * y * y); }); };
  const auto shear = [&](double p) { return bond_sum(p, [](double x, double y) { return x * x * y * y; }); };
  if (!(shear(0.0) > 0.0))
    throw std::invalid_argument("springs need bonds off the lattice's axes to carry shear: h must exceed sqrt(2) "
                                "times the spacing (raise resolution.neighbours)");
  // The first sign change on a scan of p, then bisection: the anisotropy is a sum of exponentials in p.
  double lo = -8.0, hi = lo;
  double g_lo = anisotropy(lo);
  bool found = g_lo == 0.0;
  for (double p = lo + 0.5; p <= 24.0 && !found; p += 0.5) {
    const double g = anisotropy(p);
    if ((g > 0.0) != (g_lo > 0.0) || g == 0.0) {
      hi = p;
      found = true;
    } else {
      lo = p;
      g_lo = g;
    }
  }
  if (!found)
    throw std::invalid_argument("no spring law k (d / L)^p with p in [-8, 24] makes the spring network isotropic at "
                                "this support (change resolution.neighbours)");
  for (int it = 0; it < 60 && hi > lo; ++it) {
    const double mid = 0.5 * (lo + hi);
    if ((anisotropy(mid) > 0.0) == (g_lo > 0.0)) lo = mid;
    else hi = mid;
  }
  const double p = 0.5 * (lo + hi);
  return SpringLaw{2.0 * d * d * d * modulus / shear(p), p};
}

double spring_rate(double stiffness_per_mass, double exponent, double spacing, double h) {
  if (!(stiffness_per_mass > 0.0)) return 0.0;
  const double d = spacing;
  const double bonds = lattice_sum(d, h, [&](double r2) { return r2 > 0.0 ? std::pow(d * d / r2, 0.5 * exponent) : 0.0; });
  return std::sqrt(2.0 / 3.0 * stiffness_per_mass * bonds);
}

SpringNetwork create_springs(const SimConstants& c, const ParticleState& ps, double spacing) {
  SpringNetwork net;
  bool any = false;
  for (int32_t f = 0; f < c.num_fluids; ++f) any = any || c.fluids[f].spring_stiffness > 0.0f;
  if (!any || ps.size() == 0) return net;
  const double h = c.kernel.h;
  int32_t num_ids = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) num_ids = std::max(num_ids, ps.id[a] + 1);
  const auto elastic = [&](std::size_t a) { return c.fluids[ps.fluid[a]].spring_stiffness > 0.0f; };
  const HostNeighbours neighbours(ps, h, elastic);
  // Each particle's partners (same fluid, closer than h), in the order of their ids.
  std::vector<std::vector<std::pair<int32_t, float>>> springs(ps.size());
  std::size_t most = 0;
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (!elastic(a)) continue;
    neighbours.for_each_same_fluid(a, [&](std::size_t b, Vec3 x) {
      const float r = sqrtf(dot(x, x));  // as spring_acceleration measures it
      if (r < float(h) && r > 0.0f) springs[a].push_back({ps.id[b], r});
    });
    std::sort(springs[a].begin(), springs[a].end());
    most = std::max(most, springs[a].size());
  }
  if (most > std::size_t(kMaxSpringsPerParticle))
    throw std::invalid_argument("a particle of an elastic fluid has " + std::to_string(most) + " neighbours within h; springs are " +
                                "kept for at most " + std::to_string(kMaxSpringsPerParticle) +
                                " (lower resolution.neighbours)");
  net.capacity = int32_t(std::max<std::size_t>(most, 1));
  net.partner.assign(std::size_t(num_ids) * std::size_t(net.capacity), -1);
  net.rest.assign(net.partner.size(), 0.0f);
  net.stiffness.assign(net.partner.size(), 0.0f);
  net.index_of_id.assign(std::size_t(num_ids), -1);
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const std::size_t base = std::size_t(ps.id[a]) * std::size_t(net.capacity);
    for (std::size_t s = 0; s < springs[a].size(); ++s) {
      net.partner[base + s] = springs[a][s].first;
      const float rest = springs[a][s].second;
      const FluidConstants& f = c.fluids[ps.fluid[a]];
      net.rest[base + s] = rest;
      net.stiffness[base + s] =
          float(double(f.spring_stiffness) * std::pow(spacing / double(rest), double(f.spring_exponent)));
    }
    net.index_of_id[std::size_t(ps.id[a])] = int32_t(a);
  }
  return net;
}

}  // namespace sph
