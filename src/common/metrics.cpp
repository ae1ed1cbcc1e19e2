#include "metrics.h"

#include <algorithm>
#include <cmath>

namespace sph {

double robust_max(std::vector<float> v) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size(), std::max<std::size_t>(3, v.size() / 1000));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k - 1), v.end(), std::greater<float>());
  return v[k - 1];
}

Metrics measure(const SimConstants& c, const ParticleState& ps) {
  Metrics m;
  std::vector<float> xs, ys, wall_ys;
  xs.reserve(ps.size());
  ys.reserve(ps.size());
  long fluid = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.age[i] < 0.0f) continue;  // still in a jet's inlet
    const FluidConstants& f = c.fluids[ps.fluid[i]];
    const Vec3 v = ps.vel[i];
    const double v2 = double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z;
    m.kinetic_energy += 0.5 * f.mass * v2;
    m.momentum[0] += double(f.mass) * v.x;
    m.momentum[1] += double(f.mass) * v.y;
    m.momentum[2] += double(f.mass) * v.z;
    m.v_max = std::max(m.v_max, std::sqrt(v2));
    const double err = std::fabs(double(ps.density[i]) - f.rest_density) / f.rest_density;
    m.density_error_mean += err;
    m.density_error_max = std::max(m.density_error_max, err);
    xs.push_back(ps.pos[i].x);
    ys.push_back(ps.pos[i].y);
    if (std::fabs(ps.pos[i].x) < c.kernel.h) wall_ys.push_back(ps.pos[i].y);
    ++fluid;
  }
  if (fluid > 0) m.density_error_mean /= double(fluid);
  m.front_x = robust_max(std::move(xs));
  m.top_y = robust_max(std::move(ys));
  m.height_at_x0 = robust_max(std::move(wall_ys));
  m.particles = fluid;
  return m;
}

}  // namespace sph
