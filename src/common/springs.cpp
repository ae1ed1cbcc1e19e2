#include "springs.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "host_neighbours.h"
#include "lattice_sum.h"

namespace sph {

double spring_constant(double modulus, double spacing, double h) {
  const double sum_r2 = lattice_sum(spacing, h, [](double r2) { return r2; });  // the point itself adds 0
  return sum_r2 > 0.0 ? 30.0 * modulus * spacing * spacing * spacing / sum_r2 : 0.0;
}

SpringNetwork create_springs(const SimConstants& c, const ParticleState& ps) {
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
  net.index_of_id.assign(std::size_t(num_ids), -1);
  for (std::size_t a = 0; a < ps.size(); ++a) {
    const std::size_t base = std::size_t(ps.id[a]) * std::size_t(net.capacity);
    for (std::size_t s = 0; s < springs[a].size(); ++s) {
      net.partner[base + s] = springs[a][s].first;
      net.rest[base + s] = springs[a][s].second;
    }
    net.index_of_id[std::size_t(ps.id[a])] = int32_t(a);
  }
  return net;
}

}  // namespace sph
