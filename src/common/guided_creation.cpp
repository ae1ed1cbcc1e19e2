#include "guided_creation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unistd.h>

#include "frame_reader.h"
#include "obstacle_contacts.h"
#include "viscous_limit.h"

namespace sph {

double smoothing_length(double spacing, double neighbours) {
  const double pi = 3.14159265358979323846;
  return std::cbrt(3.0 * neighbours / (4.0 * pi)) * spacing;
}

double lattice_density_factor(double d, double h) {
  const double pi = 3.14159265358979323846;
  const double c = 315.0 / (64.0 * pi * std::pow(h, 9));
  const long n = long(std::ceil(h / d));
  double sum = 0.0;
  for (long k = -n; k <= n; ++k)
    for (long j = -n; j <= n; ++j)
      for (long i = -n; i <= n; ++i) {
        const double r2 = (i * i + j * j + k * k) * d * d;
        if (r2 < h * h) sum += c * std::pow(h * h - r2, 3);
      }
  return sum * d * d * d;
}

double cohesion_from_surface_tension(double sigma, double mass, double rest_density, double h) {
  return sigma * mass / ((315.0 / 61440.0) * rest_density * rest_density * h * h * h);
}

namespace {

Vec3 f3(const Vec3d& v) { return Vec3{float(v[0]), float(v[1]), float(v[2])}; }

std::size_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? std::size_t(pages) * std::size_t(page) : std::size_t(8) << 30;
}

void check_particle_budget(const Scene& scene, double count) {
  std::ostringstream os;
  if (count > scene.max_particles) {
    os << scene.source << ": the scene needs about " << std::llround(count) << " particles, more than limits.max_particles = "
       << std::llround(scene.max_particles) << "; lower the resolution or raise the limit";
    throw SceneError(os.str());
  }
  const double bytes = count * double(kBytesPerParticle);
  const double avail = 0.5 * double(physical_memory_bytes());
  if (bytes > avail) {
    os << scene.source << ": " << std::llround(count) << " particles need about " << bytes / 1e9
       << " GB, more than half of this machine's memory (" << avail * 2 / 1e9 << " GB); lower the resolution";
    throw SceneError(os.str());
  }
}

GridGeometry make_grid(const Scene& scene, const ParticleState& ps, const std::vector<JetEmitter>& jets, double h,
                       double expected) {
  Vec3d lo{1e30, 1e30, 1e30}, hi{-1e30, -1e30, -1e30};
  auto grow = [&](double x, double y, double z) {
    const double p[3] = {x, y, z};
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  };
  bool have_box = false;
  if (scene.has_domain) {
    lo = scene.domain_min;
    hi = scene.domain_max;
  } else {
    for (const BoundarySpec& b : scene.boundaries)
      if (b.shape.type == ShapeType::Box && b.shape.keep_inside && !have_box) {
        have_box = true;
        lo = {b.shape.a.x, b.shape.a.y, b.shape.a.z};
        hi = {b.shape.b.x, b.shape.b.y, b.shape.b.z};
      }
    if (!have_box) {
      for (std::size_t i = 0; i < ps.size(); ++i) grow(ps.pos[i].x, ps.pos[i].y, ps.pos[i].z);
      for (const JetEmitter& j : jets) grow(j.spec().position[0], j.spec().position[1], j.spec().position[2]);
      // Free fluid spreads: leave room around it; particles beyond are clamped into border cells.
      for (int i = 0; i < 3; ++i) {
        const double margin = std::max(0.5 * (hi[i] - lo[i]), 4.0 * h);
        lo[i] -= margin;
        hi[i] += margin;
      }
    }
  }
  for (int i = 0; i < 3; ++i) {  // a band of 2h so particles pushed slightly out still sort correctly
    lo[i] -= 2.0 * h;
    hi[i] += 2.0 * h;
  }
  // Cells at least h / reach wide; coarser when the domain would need an absurd number of cells.
  const int reach = 2;
  const double max_cells = std::max(1.0 * (1 << 22), 16.0 * expected);
  double cell = h / reach;
  const double volume = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  if (volume / (cell * cell * cell) > max_cells) cell = std::cbrt(volume / max_cells);
  GridGeometry g{};
  g.origin = f3(lo);
  g.cell_size = float(cell);
  g.reach = reach;
  g.nx = std::max(1, int(std::ceil((hi[0] - lo[0]) / cell)));
  g.ny = std::max(1, int(std::ceil((hi[1] - lo[1]) / cell)));
  g.nz = std::max(1, int(std::ceil((hi[2] - lo[2]) / cell)));
  return g;
}

}  // namespace

Setup create_setup(const Scene& scene, double run_time) {
  Setup s;
  // Spacing: given, or particles across the smallest extent of the first emitter (thesis 4.1.4 nClass).
  s.spacing = scene.spacing > 0.0 ? scene.spacing : scene.emitters.front().min_extent() / scene.particles_across;
  if (!(s.spacing > 0.0) || !std::isfinite(s.spacing)) throw SceneError(scene.source + ": resolution gives no valid spacing");
  s.h = smoothing_length(s.spacing, scene.neighbours);
  s.lattice_density = lattice_density_factor(s.spacing, s.h);

  SimConstants& c = s.constants;
  c.kernel = make_kernel_coeffs(s.h);
  c.density = scene.density;
  c.eos = scene.eos;
  c.pressure_form = scene.pressure_form;
  c.viscosity = scene.viscosity;
  c.integrator = scene.integrator;
  c.clamp_negative_pressure = scene.clamp_negative_pressure;
  c.mirror_walls = scene.mirror_walls;
  c.gravity = f3(scene.gravity);
  c.num_fluids = int32_t(scene.fluids.size());
  const double d3 = s.spacing * s.spacing * s.spacing;
  for (std::size_t i = 0; i < scene.fluids.size(); ++i) {
    const FluidSpec& f = scene.fluids[i];
    FluidConstants& fc = c.fluids[i];
    fc.rest_density = float(f.rest_density);
    // Thesis 4.1.5: m = V rho0 / N = rho0 d^3. The default divides by the lattice's kernel sum instead, so
    // the initial lattice sits exactly at rest density (thesis 4.1.5, fixed inter-particle distance).
    fc.mass = float(scene.mass_rule == MassRule::Volume ? f.rest_density * d3 : f.rest_density * d3 / s.lattice_density);
    fc.speed_of_sound = float(f.speed_of_sound);
    fc.tait_b = float(f.rest_density * f.speed_of_sound * f.speed_of_sound / 7.0);
    fc.viscosity = float(f.viscosity);
    fc.artificial_alpha = float(f.artificial_viscosity);
    fc.near_stiffness = float(f.near_stiffness);
    fc.cohesion = float(cohesion_from_surface_tension(f.surface_tension, fc.mass, f.rest_density, s.h));
    fc.xsph = float(f.xsph);
    fc.lifetime = 0.0f;
    if (f.near_stiffness > 0.0) c.near_enabled = 1;
    if (f.surface_tension > 0.0) c.surface_tension_enabled = 1;
    if (f.xsph > 0.0) c.xsph_enabled = 1;
    s.max_speed_of_sound = std::max(s.max_speed_of_sound, f.speed_of_sound);
  }
  s.viscous_rate = viscous_rate(c, s.spacing, s.h, s.lattice_density);
  c.num_shapes = int32_t(scene.boundaries.size());
  for (std::size_t i = 0; i < scene.boundaries.size(); ++i) c.shapes[i] = scene.boundaries[i].shape;
  seal_obstacle_contacts(c.shapes, c.num_shapes, float(0.5 * s.spacing));

  // Count first, so an absurd resolution is refused before anything large is allocated.
  double instant = 0.0;
  const bool from_frame = !scene.initial_state.empty();  // the frame replaces the instant emitters' fill
  for (const EmitterSpec& e : scene.emitters) {
    if (e.type == EmitterType::Jet || from_frame) continue;
    if (e.type == EmitterType::Box) {
      double n = 1.0;
      for (int i = 0; i < 3; ++i) n *= std::max(1.0, std::round((e.max[i] - e.min[i]) / s.spacing));
      instant += n;
    } else {
      instant += 4.19 * std::pow(e.radius / s.spacing + 1.0, 3);
    }
  }
  check_particle_budget(scene, instant);

  for (const EmitterSpec& e : scene.emitters) {
    if (e.type == EmitterType::Jet) {
      const double inlet = e.inlet_length >= 0.0 ? e.inlet_length : 4.0 * s.h;  // thesis 4.1.6: 4 h
      s.jets.emplace_back(e, s.spacing, inlet, float(scene.fluids[std::size_t(e.fluid)].rest_density));
      FluidConstants& fc = c.fluids[e.fluid];
      if (fc.lifetime != 0.0f && fc.lifetime != float(e.lifetime))
        throw SceneError(scene.source + ": two jets of fluid \"" + scene.fluids[std::size_t(e.fluid)].name +
                         "\" have different lifetimes; particle lifetime is a property of the fluid");
      fc.lifetime = float(e.lifetime);
      continue;
    }
    if (from_frame) continue;
    const std::vector<Vec3d> pts = fill_emitter(e, s.spacing);
    const float rho0 = float(scene.fluids[std::size_t(e.fluid)].rest_density);
    for (const Vec3d& p : pts) {
      Spawn sp{f3(p), f3(e.velocity), 0.0f, rho0, uint8_t(e.fluid), s.next_id++};
      s.particles.append(sp);
    }
  }
  if (from_frame) s.particles = initial_state_particles(scene, s.spacing, s.next_id);
  for (JetEmitter& j : s.jets)
    for (const Spawn& sp : j.prefill(s.next_id)) s.particles.append(sp);

  s.expected_particles = double(s.particles.size());
  for (const JetEmitter& j : s.jets) s.expected_particles += j.steady_count(run_time);
  check_particle_budget(scene, s.expected_particles);
  if (s.particles.size() == 0 && s.jets.empty())
    throw SceneError(scene.source + ": the emitters create no particle at spacing " + std::to_string(s.spacing));

  c.grid = make_grid(scene, s.particles, s.jets, s.h, s.expected_particles);
  // Weakly compressible SPH assumes flow speeds well below c0; ten times c0 (or a jet's speed) is a blow-up.
  double fastest = s.max_speed_of_sound;
  for (const JetEmitter& j : s.jets) fastest = std::max(fastest, j.spec().speed);
  s.blowup_speed = scene.blowup_speed > 0.0 ? scene.blowup_speed : 10.0 * fastest;
  return s;
}

}  // namespace sph
