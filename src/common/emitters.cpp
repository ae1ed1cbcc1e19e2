#include "emitters.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sph {

namespace {

// A lattice index from a coordinate already divided by the spacing, clamped so that absurd scenes give
// huge (and refused) counts instead of an overflowing conversion.
long to_index(double x) { return long(std::max(-1e18, std::min(1e18, x))); }

// Lattice points are tested against box faces with this tolerance (in spacings), so a face that lies on
// a half-integer position, as every face aligned with the anchoring container does, is never decided by
// rounding.
constexpr double kIndexTolerance = 1e-9;

}  // namespace

Lattice make_lattice(const Scene& scene, double spacing) {
  Lattice l;
  l.spacing = spacing;
  bool anchored = false;
  for (const BoundarySpec& b : scene.boundaries)
    if (b.shape.type == ShapeType::Box && b.shape.keep_inside) {
      l.origin = {double(b.shape.a.x), double(b.shape.a.y), double(b.shape.a.z)};
      anchored = true;
      break;
    }
  if (!anchored)
    for (const EmitterSpec& e : scene.emitters) {
      if (e.type == EmitterType::Box) l.origin = e.min;
      else if (e.type == EmitterType::Sphere) l.origin = {e.center[0] - e.radius, e.center[1] - e.radius, e.center[2] - e.radius};
      else continue;
      break;
    }
  for (double& o : l.origin) o += 0.5 * spacing;
  return l;
}

double IndexBox::count() const {
  double n = 1.0;
  for (int a = 0; a < 3; ++a) n *= std::max(0.0, double(hi[a]) - double(lo[a]) + 1.0);
  return n;
}

IndexBox emitter_index_box(const EmitterSpec& e, const Lattice& l) {
  IndexBox b;
  for (int a = 0; a < 3; ++a) {
    if (e.type == EmitterType::Box) {
      // Cell centres in [min, max): first index at or above min, last index below max.
      b.lo[a] = to_index(std::ceil((e.min[a] - l.origin[a]) / l.spacing - kIndexTolerance));
      b.hi[a] = to_index(std::ceil((e.max[a] - l.origin[a]) / l.spacing - kIndexTolerance)) - 1;
    } else if (e.type == EmitterType::Sphere) {
      b.lo[a] = to_index(std::floor((e.center[a] - e.radius - l.origin[a]) / l.spacing));
      b.hi[a] = to_index(std::ceil((e.center[a] + e.radius - l.origin[a]) / l.spacing));
    }
  }
  return b;
}

EmitterRegion::EmitterRegion(const EmitterSpec& e, const Lattice& lattice)
    : spec_(e), lattice_(lattice), box_(emitter_index_box(e, lattice)) {
  if (spec_.type != EmitterType::Sphere || box_.count() <= 0.0) return;
  mask_.assign(std::size_t(box_.count()), 0);
  for (long k = box_.lo[2]; k <= box_.hi[2]; ++k)
    for (long j = box_.lo[1]; j <= box_.hi[1]; ++j)
      for (long i = box_.lo[0]; i <= box_.hi[0]; ++i) mask_[mask_index(i, j, k)] = strictly_inside(i, j, k);
  // Peel points with fewer than 3 of their 6 lattice neighbours in the fill until none is left: a point
  // held by one or two neighbours only (the poles of a sphere whose radius is near a whole number of
  // spacings) has no support in the fluid and is flung off by the first pressure step.
  const long off[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (;;) {
    std::vector<std::size_t> peel;
    for (long k = box_.lo[2]; k <= box_.hi[2]; ++k)
      for (long j = box_.lo[1]; j <= box_.hi[1]; ++j)
        for (long i = box_.lo[0]; i <= box_.hi[0]; ++i) {
          if (!contains(i, j, k)) continue;
          int neighbours = 0;
          for (const auto& o : off) neighbours += contains(i + o[0], j + o[1], k + o[2]) ? 1 : 0;
          if (neighbours < 3) peel.push_back(mask_index(i, j, k));
        }
    if (peel.empty()) break;
    for (std::size_t m : peel) mask_[m] = 0;
  }
}

std::size_t EmitterRegion::mask_index(long i, long j, long k) const {
  const std::size_t nx = std::size_t(box_.hi[0] - box_.lo[0] + 1), ny = std::size_t(box_.hi[1] - box_.lo[1] + 1);
  return (std::size_t(k - box_.lo[2]) * ny + std::size_t(j - box_.lo[1])) * nx + std::size_t(i - box_.lo[0]);
}

bool EmitterRegion::strictly_inside(long i, long j, long k) const {
  const Vec3d p = lattice_.point(i, j, k);
  double r2 = 0.0;
  for (int a = 0; a < 3; ++a) r2 += (p[a] - spec_.center[a]) * (p[a] - spec_.center[a]);
  return r2 < spec_.radius * spec_.radius;
}

bool EmitterRegion::contains(long i, long j, long k) const {
  const long idx[3] = {i, j, k};
  for (int a = 0; a < 3; ++a)
    if (idx[a] < box_.lo[a] || idx[a] > box_.hi[a]) return false;
  return spec_.type == EmitterType::Box || (spec_.type == EmitterType::Sphere && mask_[mask_index(i, j, k)] != 0);
}

std::vector<FilledPoint> fill_instant_emitters(const std::vector<EmitterSpec>& emitters, const Lattice& lattice,
                                               std::vector<EmitterFill>& stats) {
  stats.assign(emitters.size(), EmitterFill{});
  std::vector<EmitterRegion> regions;
  std::vector<int> owner_index;  // scene index of each region
  for (std::size_t e = 0; e < emitters.size(); ++e)
    if (emitters[e].type != EmitterType::Jet) {
      regions.emplace_back(emitters[e], lattice);
      owner_index.push_back(int(e));
    }
  std::vector<FilledPoint> out;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const IndexBox& b = regions[r].box();
    // Earlier regions whose index boxes meet this one: only they can already own one of its points.
    std::vector<std::size_t> earlier;
    for (std::size_t q = 0; q < r; ++q) {
      const IndexBox& o = regions[q].box();
      bool meet = true;
      for (int a = 0; a < 3; ++a) meet = meet && o.lo[a] <= b.hi[a] && b.lo[a] <= o.hi[a];
      if (meet) earlier.push_back(q);
    }
    EmitterFill& st = stats[std::size_t(owner_index[r])];
    for (long k = b.lo[2]; k <= b.hi[2]; ++k)
      for (long j = b.lo[1]; j <= b.hi[1]; ++j)
        for (long i = b.lo[0]; i <= b.hi[0]; ++i) {
          if (!regions[r].contains(i, j, k)) continue;
          bool owned = false;
          for (std::size_t q : earlier)
            if (regions[q].contains(i, j, k)) {
              owned = true;
              break;
            }
          if (owned) {
            ++st.shared;
          } else {
            ++st.created;
            out.push_back({lattice.point(i, j, k), owner_index[r]});
          }
        }
  }
  return out;
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

// Points across the section's side 2r: the nearest whole number, at least one.
double JetEmitter::section_candidates(const EmitterSpec& spec, double spacing) {
  const double across = std::max(1.0, std::round(2.0 * spec.radius / spacing));
  return across * across;
}

JetEmitter::JetEmitter(const EmitterSpec& spec, double spacing, double inlet_length, float density,
                       double max_particles, std::string source, int index)
    : spec_(spec),
      spacing_(spacing),
      inlet_length_(inlet_length),
      density_(density),
      max_particles_(max_particles),
      source_(std::move(source)),
      index_(index) {
  // Orthonormal basis (u, w) of the section plane.
  const Vec3d& dir = spec_.direction;
  const Vec3d helper = std::fabs(dir[1]) < 0.9 ? Vec3d{0.0, 1.0, 0.0} : Vec3d{1.0, 0.0, 0.0};
  const Vec3d u = unit(cross(dir, helper));
  const Vec3d w = cross(dir, u);
  // A lattice of m = round(2r / d) points across, centred on the axis: a square section gets exactly m^2
  // points (its flow area (2r)^2 to within one row), a circle the points within r of the axis.
  const long across = long(std::sqrt(section_candidates(spec_, spacing_)) + 0.5);
  for (long j = 0; j < across; ++j)
    for (long i = 0; i < across; ++i) {
      const double a = (double(i) - 0.5 * double(across - 1)) * spacing_;
      const double b = (double(j) - 0.5 * double(across - 1)) * spacing_;
      const bool inside = spec_.section == JetSection::Square || a * a + b * b <= spec_.radius * spec_.radius;
      if (inside) section_.push_back({a * u[0] + b * w[0], a * u[1] + b * w[1], a * u[2] + b * w[2]});
    }
  if (section_.empty()) section_.push_back({0.0, 0.0, 0.0});
}

long JetEmitter::inlet_layers() const {
  return std::max(0L, long(std::ceil(inlet_length_ / spacing_ - kIndexTolerance)));
}

Vec3d JetEmitter::inlet_point(long layer, std::size_t s) const {
  const double back = inlet_length_ - double(layer) * spacing_;  // distance still to travel before the outlet
  const Vec3d& dir = spec_.direction;
  const Vec3d& q = section_[s];
  return {spec_.position[0] - dir[0] * back + q[0], spec_.position[1] - dir[1] * back + q[1],
          spec_.position[2] - dir[2] * back + q[2]};
}

// One layer at distance `offset` past the start of the inlet.
void JetEmitter::layer(double offset, std::vector<Spawn>& out, int32_t& next_id) const {
  const Vec3d& dir = spec_.direction;
  const double back = inlet_length_ - offset;
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
  const long layers = inlet_layers();
  out.reserve(std::size_t(layers) * section_.size());
  for (long l = 0; l < layers; ++l) layer(double(l) * spacing_, out, next_id);
  return out;
}

std::vector<Spawn> JetEmitter::advance(double t, double dt, int32_t& next_id) {
  std::vector<Spawn> out;
  const double t0 = std::max(t, spec_.start), t1 = std::min(t + dt, spec_.stop);
  if (t1 <= t0) return out;
  travelled_ += spec_.speed * (t1 - t0);
  // Checked before allocating: one long step of a fast jet could otherwise ask for gigabytes.
  const double layers = std::floor(travelled_ / spacing_);
  if (layers * double(section_.size()) > max_particles_) {
    std::ostringstream os;
    os << source_ << ": emitters." << index_ << " (jet) would create " << layers * double(section_.size())
       << " particles in one step of " << dt << " s (" << spec_.speed << " m/s over " << dt
       << " s is " << layers << " layers of spacing " << spacing_ << " m), more than limits.max_particles = "
       << max_particles_ << "; lower time_step.dt / time_step.max or the jet's speed";
    throw SceneError(os.str());
  }
  out.reserve(std::size_t(layers) * section_.size());
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
