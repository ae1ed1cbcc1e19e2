#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sph {

double robust_max(std::vector<float> v) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size(), std::max<std::size_t>(3, v.size() / 1000));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k - 1), v.end(), std::greater<float>());
  return v[k - 1];
}

PotentialFloor lowest_reachable_potential(const SimConstants& c) {
  const double g = std::sqrt(double(c.gravity.x) * c.gravity.x + double(c.gravity.y) * c.gravity.y +
                             double(c.gravity.z) * c.gravity.z);
  PotentialFloor out;
  if (g == 0.0) return out;
  bool any = false;
  double level = -std::numeric_limits<double>::infinity();
  auto bound = [&](double floor) {
    any = true;
    level = std::max(level, floor);
  };
  for (int32_t s = 0; s < c.num_shapes; ++s) {
    const Shape& sh = c.shapes[s];
    if (sh.type == ShapeType::Box && sh.keep_inside) {
      double lowest = std::numeric_limits<double>::infinity();
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3 x{corner & 1 ? sh.b.x : sh.a.x, corner & 2 ? sh.b.y : sh.a.y, corner & 4 ? sh.b.z : sh.a.z};
        lowest = std::min(lowest, specific_potential(c, x));
      }
      bound(lowest);
    } else if (sh.type == ShapeType::Plane) {
      // -g.x is bounded below on the side n points to only when n points against gravity: n.(-g) = |g|.
      const double up = -(double(sh.b.x) * c.gravity.x + double(sh.b.y) * c.gravity.y + double(sh.b.z) * c.gravity.z);
      if (up >= g * (1.0 - 1.5e-6)) bound(specific_potential(c, sh.a));  // cos(0.1 degree) = 1 - 1.5e-6
    } else if (sh.type == ShapeType::Sphere && sh.keep_inside) {
      bound(specific_potential(c, sh.a) - g * sh.radius);
    }
  }
  out.bounded = any;
  out.level = any ? level : 0.0;
  return out;
}

Metrics measure(const SimConstants& c, const ParticleState& ps, double potential_reference) {
  Metrics m;
  std::vector<float> xs, ys, wall_ys;
  xs.reserve(ps.size());
  ys.reserve(ps.size());
  long fluid = 0;
  const GridGeometry& g = c.grid;
  const Vec3 lo = g.origin, hi = g.origin + g.cell_size * Vec3{float(g.nx), float(g.ny), float(g.nz)};
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Vec3 x = ps.pos[i];
    const bool inside = x.x >= lo.x && x.y >= lo.y && x.z >= lo.z && x.x <= hi.x && x.y <= hi.y && x.z <= hi.z;
    if (!inside) ++m.outside_domain;  // NaN included
    if (ps.age[i] < 0.0f) continue;  // still in a jet's inlet
    const FluidConstants& f = c.fluids[ps.fluid[i]];
    const Vec3 v = ps.vel[i];
    const double v2 = double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z;
    m.kinetic_energy += particle_kinetic_energy(c, ps, i);
    m.potential_energy += f.mass * (specific_potential(c, ps.pos[i]) - potential_reference);
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

double probe_depth(const SimConstants& c, const ParticleState& ps, const std::array<double, 3>& base) {
  const double gx = c.gravity.x, gy = c.gravity.y, gz = c.gravity.z;
  const double g = std::sqrt(gx * gx + gy * gy + gz * gz);
  if (g == 0.0) return 0.0;
  const double ux = -gx / g, uy = -gy / g, uz = -gz / g;  // up
  const double h2 = 2.25 * double(c.kernel.h) * c.kernel.h;  // R = 1.5 h, R^2
  const double norm = 4.0 / (kPiDouble * h2 * h2 * h2 * h2);
  double depth = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.age[i] < 0.0f) continue;  // still in a jet's inlet
    const double dx = ps.pos[i].x - base[0], dy = ps.pos[i].y - base[1], dz = ps.pos[i].z - base[2];
    const double up = dx * ux + dy * uy + dz * uz;
    if (!(up >= 0.0)) continue;  // below the gauge (NaN positions too)
    const double r2 = dx * dx + dy * dy + dz * dz - up * up;
    if (r2 >= h2) continue;
    const FluidConstants& f = c.fluids[ps.fluid[i]];
    const double w = h2 - r2;
    depth += double(f.mass) / f.rest_density * norm * w * w * w;
  }
  return depth;
}

}  // namespace sph
