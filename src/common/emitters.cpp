#include "emitters.h"

#include <algorithm>
#include <cmath>

namespace sph {

std::vector<Vec3d> fill_emitter(const EmitterSpec& e, double d) {
  std::vector<Vec3d> pts;
  if (e.type == EmitterType::Box) {
    long n[3];
    double start[3];
    for (int i = 0; i < 3; ++i) {
      const double len = e.max[i] - e.min[i];
      n[i] = std::max(1L, std::lround(len / d));
      start[i] = e.min[i] + 0.5 * (len - double(n[i]) * d) + 0.5 * d;  // centred, half a spacing from walls
    }
    pts.reserve(std::size_t(n[0] * n[1] * n[2]));
    for (long k = 0; k < n[2]; ++k)
      for (long j = 0; j < n[1]; ++j)
        for (long i = 0; i < n[0]; ++i) pts.push_back({start[0] + i * d, start[1] + j * d, start[2] + k * d});
  } else if (e.type == EmitterType::Sphere) {
    const long n = long(std::ceil(e.radius / d));
    for (long k = -n; k <= n; ++k)
      for (long j = -n; j <= n; ++j)
        for (long i = -n; i <= n; ++i) {
          const double x = i * d, y = j * d, z = k * d;
          if (x * x + y * y + z * z <= e.radius * e.radius)
            pts.push_back({e.center[0] + x, e.center[1] + y, e.center[2] + z});
        }
  }
  return pts;
}

namespace {
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3d unit(const Vec3d& a) {
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / n, a[1] / n, a[2] / n};
}
}  // namespace

JetEmitter::JetEmitter(const EmitterSpec& spec, double spacing, double inlet_length, float density)
    : spec_(spec), spacing_(spacing), inlet_length_(inlet_length), density_(density) {
  // Orthonormal basis (u, w) of the section plane.
  const Vec3d& dir = spec_.direction;
  const Vec3d helper = std::fabs(dir[1]) < 0.9 ? Vec3d{0.0, 1.0, 0.0} : Vec3d{1.0, 0.0, 0.0};
  const Vec3d u = unit(cross(dir, helper));
  const Vec3d w = cross(dir, u);
  const long n = long(std::ceil(spec_.radius / spacing_));
  for (long j = -n; j <= n; ++j)
    for (long i = -n; i <= n; ++i) {
      // Cell-centred lattice: a square of side 2r holds exactly (2r / d)^2 points.
      const double a = (i + 0.5) * spacing_, b = (j + 0.5) * spacing_;
      const bool inside = spec_.section == JetSection::Circle
                              ? a * a + b * b <= spec_.radius * spec_.radius
                              : std::fabs(a) <= spec_.radius && std::fabs(b) <= spec_.radius;
      if (inside) section_.push_back({a * u[0] + b * w[0], a * u[1] + b * w[1], a * u[2] + b * w[2]});
    }
  if (section_.empty()) section_.push_back({0.0, 0.0, 0.0});
}

// One layer at distance `offset` past the start of the inlet.
void JetEmitter::layer(double offset, std::vector<Spawn>& out, int32_t& next_id) const {
  const Vec3d& dir = spec_.direction;
  const double back = inlet_length_ - offset;  // distance still to travel before the outlet
  const float age = float(-back / spec_.speed);
  const Vec3 vel{float(dir[0] * spec_.speed), float(dir[1] * spec_.speed), float(dir[2] * spec_.speed)};
  for (const Vec3d& s : section_) {
    Spawn p;
    p.pos = Vec3{float(spec_.position[0] - dir[0] * back + s[0]), float(spec_.position[1] - dir[1] * back + s[1]),
                 float(spec_.position[2] - dir[2] * back + s[2])};
    p.vel = vel;
    p.age = age;
    p.density = density_;
    p.fluid = uint8_t(spec_.fluid);
    p.id = next_id++;
    out.push_back(p);
  }
}

std::vector<Spawn> JetEmitter::prefill(int32_t& next_id) {
  std::vector<Spawn> out;
  if (spec_.start > 0.0) return out;
  for (double offset = 0.0; offset < inlet_length_ - 1e-9 * spacing_; offset += spacing_) layer(offset, out, next_id);
  return out;
}

std::vector<Spawn> JetEmitter::advance(double t, double dt, int32_t& next_id) {
  std::vector<Spawn> out;
  const double t0 = std::max(t, spec_.start), t1 = std::min(t + dt, spec_.stop);
  if (t1 <= t0) return out;
  travelled_ += spec_.speed * (t1 - t0);
  while (travelled_ >= spacing_) {
    travelled_ -= spacing_;
    layer(travelled_, out, next_id);  // born one spacing ago would have moved travelled_ since
  }
  return out;
}

double JetEmitter::steady_count(double run_time) const {
  const double inlet_time = inlet_length_ / spec_.speed;
  double alive = spec_.lifetime > 0.0 ? spec_.lifetime + inlet_time
                                      : std::min(spec_.stop, run_time) - spec_.start + inlet_time;
  alive = std::max(alive, inlet_time);
  return double(section_.size()) * (alive * spec_.speed / spacing_ + 1.0);
}

}  // namespace sph
