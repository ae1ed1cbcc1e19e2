#include "guided_creation.h"

#include "scene_fluids.h"
#include "surface_tension_csf.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <sstream>

#include "setup_budget.h"
#include "rigid_body_setup.h"
#include "scene_fluids.h"
#include "setup_checks.h"
#include "solver_notes.h"

#include "cohesion_energy.h"
#include "frame_reader.h"
#include "grid.h"
#include "obstacle_contacts.h"
#include "time_step.h"
#include "viscous_limit.h"

namespace sph {

namespace {

Vec3 f3(const Vec3d& v) { return Vec3{float(v[0]), float(v[1]), float(v[2])}; }

std::string metres(double x) {
  std::ostringstream os;
  os.precision(4);
  os << x;
  return os.str();
}

// The neighbour grid's origin and cells (grid.h), and the domain the fluid is expected in: the container
// (or "domain", or the fluid with room to spread) with a band of 2 h. Refused when the domain is wider
// than the grid's keys reach.
GridGeometry make_grid(const Scene& scene, const ParticleState& ps, const std::vector<JetEmitter>& jets, double h) {
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
  // Cells of h / 2 whatever the domain's size: the grid holds only occupied blocks (grid.h). The keys
  // reach 2^17 blocks from the origin on each side (at least 2^18 h along y and z): beyond that particles
  // would share border cells and the search would slow down, so such a domain is refused.
  const double cell = h / kGridReach;
  auto cells = [&](int axis) { return std::max(1.0, std::ceil((hi[axis] - lo[axis]) / cell)); };
  const double key_range = double(1 << (kBlockBits - 1)) * kBlockY;  // cells on the positive side, y and z
  if (std::max({cells(0), cells(1), cells(2)}) > key_range) {
    std::ostringstream os;
    os << scene.source << ": the simulation domain " << metres(hi[0] - lo[0]) << " x " << metres(hi[1] - lo[1]) << " x "
       << metres(hi[2] - lo[2]) << " m (with a band of 2 h) is wider than the neighbour grid reaches: "
       << count_text(key_range) << " grid cells of h / 2 = " << metres(cell)
       << " m along each axis; make the domain (\"domain\" or the box container) fit the fluid more closely, or coarsen "
          "the resolution";
    throw SceneError(os.str());
  }
  GridGeometry g{};
  g.origin = f3(lo);
  g.cell_size = float(cell);
  g.reach = kGridReach;
  g.nx = int32_t(cells(0));
  g.ny = int32_t(cells(1));
  g.nz = int32_t(cells(2));
  return g;
}

// Volume [m^3] an instant emitter asks for (overlaps with other emitters included).
double emitter_volume(const EmitterSpec& e) {
  if (e.type == EmitterType::Box) return (e.max[0] - e.min[0]) * (e.max[1] - e.min[1]) * (e.max[2] - e.min[2]);
  return 4.0 / 3.0 * kPiDouble * e.radius * e.radius * e.radius;
}

// Most particles an instant emitter can create, from its index box alone: exact for a box, the volume
// of a sphere one spacing larger for a sphere.
double instant_count_bound(const EmitterSpec& e, const Lattice& lattice) {
  const double box = emitter_index_box(e, lattice).count();
  if (e.type == EmitterType::Box) return box;
  const double r = e.radius / lattice.spacing + 1.0;
  return std::min(box, 4.19 * r * r * r);
}

// Set-up report lines for the instant emitters: layers and filled extent of boxes where the extent is not
// a whole number of spacings, shared lattice points, mass against rho0 times the asked volume. Returns
// whether any emitter was refit or shared points.
bool report_fill(const Scene& scene, const Lattice& lattice, const SimConstants& c,
                 const std::vector<EmitterFill>& stats, std::vector<std::string>& report) {
  bool adjusted = false;
  for (std::size_t e = 0; e < scene.emitters.size(); ++e) {
    const EmitterSpec& em = scene.emitters[e];
    if (em.type == EmitterType::Jet) continue;
    std::ostringstream os;
    os << emitter_label(scene.emitters, e) << ": " << stats[e].created << " particles";
    bool refit = false;
    if (em.type == EmitterType::Box) {
      const IndexBox b = emitter_index_box(em, lattice);
      double filled[3];
      bool whole = true;
      for (int a = 0; a < 3; ++a) {
        filled[a] = double(b.hi[a] - b.lo[a] + 1) * lattice.spacing;
        whole = whole && std::fabs(filled[a] - (em.max[a] - em.min[a])) < 1e-6 * lattice.spacing;
      }
      os << " on " << (b.hi[0] - b.lo[0] + 1) << " x " << (b.hi[1] - b.lo[1] + 1) << " x " << (b.hi[2] - b.lo[2] + 1)
         << " layers";
      refit = !whole;
      if (!whole)
        os << " filling " << metres(filled[0]) << " x " << metres(filled[1]) << " x " << metres(filled[2])
           << " m (asked " << metres(em.max[0] - em.min[0]) << " x " << metres(em.max[1] - em.min[1]) << " x "
           << metres(em.max[2] - em.min[2]) << " m: not whole numbers of the spacing " << metres(lattice.spacing) << " m)";
    }
    const FluidConstants& fc = c.fluids[em.fluid];
    os << ", mass " << metres(double(stats[e].created) * double(fc.mass)) << " kg (rho0 x asked volume: "
       << metres(double(fc.rest_density) * emitter_volume(em)) << " kg)";
    // Shared points belong to the earlier emitter: the asked volume above still counts them.
    if (stats[e].shared > 0)
      os << "; " << stats[e].shared << " lattice points shared with earlier emitters, filled once by them ("
         << metres(double(stats[e].shared) * double(fc.mass)) << " kg of this emitter's asked volume)";
    adjusted = adjusted || refit || stats[e].shared > 0;
    report.push_back(os.str());
  }
  return adjusted;
}

// A relative difference as a signed percentage with one decimal ("+3.2%", "+0.0%").
std::string percent_text(double relative) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f%%", std::round(1000.0 * relative) / 10.0 + 0.0);  // -0.0 + 0.0 = +0.0
  return text;
}

// Everything but the memory guard of create_setup. `estimate` holds the particle count known so far, for
// an out-of-memory message.
// The scene's meshes, loaded and checked closed; SceneError naming meshes.N and the file otherwise.
std::vector<MeshSolid> load_meshes(const Scene& scene) {
  std::vector<MeshSolid> out;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshSpec& m = scene.meshes[i];
    const std::string label = scene.source + ": meshes." + std::to_string(i);
    MeshSolid solid;
    try {
      solid.mesh = load_obj_mesh(m.file, MeshPoint{m.scale[0], m.scale[1], m.scale[2]},
                                 MeshPoint{m.translate[0], m.translate[1], m.translate[2]});
    } catch (const std::exception& e) {
      throw SceneError(label + ": " + e.what());
    }
    const std::string problem = mesh_closure_problem(solid.mesh);
    if (!problem.empty())
      throw SceneError(label + ": " + m.file + ": " + problem +
                       "; a mesh must bound a solid: closed, every edge shared by two triangles of consistent orientation");
    solid.inside = m.inside;
    solid.slip = float(m.slip);
    out.push_back(std::move(solid));
  }
  return out;
}

// Removes the filled points inside a mesh's solid or closer than kMinWallClearance d to its surface, as
// remove_blocked_points does for the shapes, with a report line per mesh (SceneError with on_overlap "error").
void remove_points_in_meshes(const Scene& scene, const std::vector<MeshSolid>& meshes, double spacing,
                             std::vector<FilledPoint>& points, std::vector<std::string>& report) {
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const MeshSolid& ms = meshes[m];
    const std::size_t before = points.size();
    points.erase(std::remove_if(points.begin(), points.end(),
                                [&](const FilledPoint& p) {
                                  const double sd = mesh_signed_distance(ms.mesh, MeshPoint{p.pos[0], p.pos[1], p.pos[2]});
                                  return (ms.inside ? -sd : sd) < kMinWallClearance * spacing;
                                }),
                 points.end());
    const std::size_t removed = before - points.size();
    if (removed == 0) continue;
    std::ostringstream os;
    os << "meshes." << m << ": " << removed << " filled particles lie in its solid or within " << kMinWallClearance
       << " d of its surface";
    if (scene.overlap_error) throw SceneError(scene.source + ": " + os.str() + " (\"on_overlap\": \"error\" refuses them)");
    report.push_back(os.str() + "; removed");
  }
}

// Removes the filled points inside a rigid body or closer than kMinWallClearance d to it, as for the shapes.
void remove_points_in_bodies(const Scene& scene, const std::vector<RigidBody>& bodies, double spacing,
                             std::vector<FilledPoint>& points, std::vector<std::string>& report) {
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const std::size_t before = points.size();
    points.erase(std::remove_if(points.begin(), points.end(),
                                [&](const FilledPoint& p) { return depth_in_body(bodies[k], p.pos) > -kMinWallClearance * spacing; }),
                 points.end());
    const std::size_t removed = before - points.size();
    if (removed == 0) continue;
    std::ostringstream os;
    os << "bodies." << k << ": " << removed << " filled particles lie in it or within " << kMinWallClearance << " d of it";
    if (scene.overlap_error) throw SceneError(scene.source + ": " + os.str() + " (\"on_overlap\": \"error\" refuses them)");
    report.push_back(os.str() + "; removed");
  }
}

void build_setup(const Scene& scene, double run_time, Setup& s, double& estimate) {
  // Spacing: given, or particles across the smallest extent of the first emitter (thesis 4.1.4 nClass).
  s.spacing = scene.spacing > 0.0 ? scene.spacing : scene.emitters.front().min_extent() / scene.particles_across;
  if (!(s.spacing > 0.0) || !std::isfinite(s.spacing)) throw SceneError(scene.source + ": resolution gives no valid spacing");
  s.h = smoothing_length(s.spacing, scene.neighbours);

  // Count first, so an absurd resolution is refused before anything large is allocated or looped over:
  // the instant emitters from their lattice index boxes, the jets' sections from their candidates.
  const Lattice lattice = make_lattice(scene, s.spacing);
  const bool from_frame = !scene.initial_state.empty();  // the frame replaces the instant emitters' fill
  for (const EmitterSpec& e : scene.emitters)
    if (e.type != EmitterType::Jet && !from_frame) estimate += instant_count_bound(e, lattice);
  check_particle_budget(scene, estimate, "filling the instant emitters (box, sphere) at spacing " + metres(s.spacing) + " m");
  for (std::size_t i = 0; i < scene.emitters.size(); ++i)
    if (scene.emitters[i].type == EmitterType::Jet)
      check_particle_budget(scene, JetEmitter::section_candidates(scene.emitters[i], s.spacing),
                            emitter_label(scene.emitters, i) + ": its section lattice (radius " +
                                metres(scene.emitters[i].radius) + " m at spacing " + metres(s.spacing) + " m)");

  SimConstants& c = s.constants;
  c.solver = scene.solver;
  c.cubic_spline = wcsph_cubic_spline(scene) ? 1 : 0;
  c.dfsph_poly6_spiky = dfsph_poly6_spiky(scene) ? 1 : 0;
  // The kernel sum over the lattice depends on h / d only: computed at d = 1 it cannot overflow.
  // With the run's density kernel (params.h, density_cubic_spline), so that its lattice start reads rho0.
  s.lattice_density = lattice_density_factor(1.0, s.h / s.spacing, density_cubic_spline(c));
  check_float_range(scene, s.spacing, s.h, s.lattice_density);
  check_incompressible_step(scene, s.spacing);
  check_surface_tension(scene, s.h);
  check_springs(scene);
  check_interface_tension(scene);  // before the contact angle's walls: the combination is the first thing to say
  check_contact_angle(scene);
  report_ignored_settings(scene, s.report);
  s.meshes = load_meshes(scene);

  c.kernel = make_kernel_coeffs(s.h);
  c.density = scene.density;
  c.eos = scene.eos;
  c.pressure_form = scene.pressure_form;
  c.csf_curvature_spread = scene.csf_curvature_limit ? kCsfCurvatureSpread : -1.0f;
  c.viscosity = scene.viscosity;
  c.integrator = scene.integrator;
  c.clamp_negative_pressure = scene.clamp_negative_pressure;
  c.mirror_walls = scene.mirror_walls;
  c.mirror_wall_distance = float(0.5 * s.spacing);
  c.dfsph = scene.dfsph;
  c.pbf = scene.pbf;
  c.gravity = f3(scene.gravity);
  c.num_fluids = int32_t(scene.fluids.size());
  const bool csf = scene.surface_tension_model == SurfaceTensionModel::Csf;
  const double chi = csf_band_integral(s.spacing, s.h, s.lattice_density);
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
    fc.cohesion = float(cohesion_from_surface_tension(f.surface_tension, f.rest_density, s.h));
    const bool contact = f.contact_angle > 0.0;
    fc.adhesion = contact && !csf ? float(adhesion_constant(fc.cohesion, f.contact_angle, s.spacing, s.h)) : 0.0f;
    fc.csf_contact = contact && csf ? 1 : 0;
    fc.csf_contact_cot = contact ? float(1.0 / std::tan(f.contact_angle * kPiDouble / 180.0)) : 0.0f;
    if (fc.csf_contact) c.csf_contact_enabled = 1;
    if (fc.adhesion > 0.0f) c.adhesion_enabled = 1;
    fc.xsph = float(f.xsph);
    fc.lifetime = 0.0f;
    // Springs: k / m from the shear modulus (springs.h).
    SpringLaw law{0.0, 0.0};
    try {
      law = spring_law(f.spring_modulus, s.spacing, s.h);
    } catch (const std::invalid_argument& e) {
      throw SceneError(scene.source + ": fluids." + std::to_string(i) + ".spring_modulus: " + e.what());
    }
    fc.spring_stiffness = float(law.stiffness / double(fc.mass));
    fc.spring_exponent = float(law.exponent);
    s.spring_rate = std::max(s.spring_rate, spring_rate(double(fc.spring_stiffness), law.exponent, s.spacing, s.h));
    fc.spring_yield = float(f.spring_yield);
    fc.spring_plasticity = float(f.spring_plasticity);
    if (f.near_stiffness > 0.0) c.near_enabled = 1;
    fc.csf_sigma = float(f.surface_tension / chi);
    fc.particle_side = float(std::cbrt(double(fc.mass) / f.rest_density));
    if (f.surface_tension > 0.0) (csf ? c.csf_enabled : c.surface_tension_enabled) = 1;
    if (f.xsph > 0.0) c.xsph_enabled = 1;
    // Under PBF only with pbf.artificial_viscosity (params.h, PbfConstants).
    if (f.artificial_viscosity > 0.0 && (scene.solver != Solver::Pbf || scene.pbf.artificial_viscosity != 0))
      c.artificial_enabled = 1;
    s.max_speed_of_sound = std::max(s.max_speed_of_sound, f.speed_of_sound);
  }
  check_spring_step(scene, s.spring_rate);
  // Where the springs hold the adaptive step of DFSPH or PBF below its max, say so: a stiff jelly can take
  // many steps per simulated second (a 1 GPa jelly at 5 mm spacing: about 6e5), which the run would not
  // explain otherwise.
  if (scene.solver != Solver::Wcsph && s.spring_rate > 0.0 && scene.time_step.mode == TimeStepMode::Adaptive &&
      spring_step_bound(s.spring_rate) < scene.time_step.max) {
    const double bound = spring_step_bound(s.spring_rate);
    std::ostringstream os;
    os << "note: the springs (spring_modulus) hold the step at or below " << bound << " s (their fastest mode, "
       << s.spring_rate << " rad/s): at least " << std::ceil(1.0 / bound) << " steps per simulated second";
    s.report.push_back(os.str());
  }
  for (int32_t i = 1; i < c.num_fluids; ++i)
    if (c.fluids[i].mass != c.fluids[0].mass) c.number_density = scene.number_density ? 1 : 0;
  for (const InterfaceTensionSpec& t : scene.interface_tensions) {
    const FluidSpec &fa = scene.fluids[std::size_t(t.a)], &fb = scene.fluids[std::size_t(t.b)];
    const float k = float(cross_cohesion(fa.surface_tension, fb.surface_tension, t.sigma, fa.rest_density, fb.rest_density, s.h));
    c.cross_cohesion[t.a][t.b] = c.cross_cohesion[t.b][t.a] = k;
    if (csf) {  // each particle's share of the interface's tension (surface_tension_csf.h)
      c.fluids[t.a].csf_interface_sigma = c.fluids[t.b].csf_interface_sigma = float(t.sigma / chi);
      c.csf_interface_enabled = c.csf_enabled = 1;
    }
    // Under the continuum surface force the cross cohesion stays for the energy budget only
    // (cohesion_energy.h), as a fluid's own cohesion does.
    if (k != 0.0f && !csf) c.interface_cohesion_enabled = 1;
  }
  // Not under PBF, which applies the force at the end of its step: with the correction its 12-across drop
  // under the paper's plain iteration lost a particle that it keeps without (docs/results.md, "A free drop
  // keeps its momentum").
  c.csf_momentum = csf_free_drop(scene) && scene.solver != Solver::Pbf ? 1 : 0;
  s.viscous_rate = viscous_rate(c, s.spacing, s.h, s.lattice_density);
  c.artificial_rate = float(artificial_viscous_rate(c, s.spacing, s.h, s.lattice_density));
  c.substep_rate = float(double(c.artificial_rate) + s.viscous_rate);
  c.num_shapes = int32_t(scene.boundaries.size());
  for (std::size_t i = 0; i < scene.boundaries.size(); ++i) c.shapes[i] = scene.boundaries[i].shape;
  seal_obstacle_contacts(c.shapes, c.num_shapes, float(0.5 * s.spacing));

  // The jets: the inlet holds ceil(L / d) layers of the section, and one step of dt_max emits
  // speed dt_max / d layers (plus one carried over).
  const double budget = particle_budget(scene);
  const double dt_max = scene.time_step.mode == TimeStepMode::Fixed ? scene.time_step.dt : scene.time_step.max;
  std::vector<int> jet_index;
  for (std::size_t i = 0; i < scene.emitters.size(); ++i) {
    const EmitterSpec& e = scene.emitters[i];
    if (e.type != EmitterType::Jet) continue;
    const std::string label = emitter_label(scene.emitters, i);
    const double inlet = e.inlet_length >= 0.0 ? e.inlet_length : 4.0 * s.h;  // thesis 4.1.6: 4 h
    s.jets.emplace_back(e, s.spacing, inlet, float(scene.fluids[std::size_t(e.fluid)].rest_density), budget,
                        scene.source, int(i));
    jet_index.push_back(int(i));
    const double section = double(s.jets.back().section_size());
    estimate += section * std::ceil(inlet / s.spacing);
    check_particle_budget(scene, estimate,
                          label + ": its inlet (emitters." + std::to_string(i) + ".inlet_length " + metres(inlet) +
                              " m), with the emitters before it,",
                          "shorten the inlet or lower the resolution");
    check_particle_budget(scene, section * (std::floor(e.speed * dt_max / s.spacing) + 1.0),
                          label + ": one time step (speed " + metres(e.speed) + " m/s x largest dt " + metres(dt_max) +
                              " s at spacing " + metres(s.spacing) + " m)",
                          "lower time_step.dt and time_step.max, the jet's speed or the resolution");
    FluidConstants& fc = c.fluids[e.fluid];
    if (fc.lifetime != 0.0f && fc.lifetime != float(e.lifetime))
      throw SceneError(scene.source + ": two jets of fluid \"" + scene.fluids[std::size_t(e.fluid)].name +
                       "\" have different lifetimes; particle lifetime is a property of the fluid");
    fc.lifetime = float(e.lifetime);
    // The flow the lattice carries against the asked one: section area d^2 per particle.
    const double asked_area = e.section == JetSection::Square ? 4.0 * e.radius * e.radius : kPiDouble * e.radius * e.radius;
    const double area = double(s.jets.back().section_size()) * s.spacing * s.spacing;
    s.report.push_back(label + ": " + std::to_string(s.jets.back().section_size()) + " particles per layer (flow area " +
                       metres(area) + " m^2, asked " + metres(asked_area) + " m^2: " + percent_text(area / asked_area - 1.0) +
                       "), inlet " +
                       metres(inlet) + " m (" + std::to_string(s.jets.back().inlet_layers()) + " layers" +
                       (e.start > 0.0 ? ", not prefilled: the jet starts at " + metres(e.start) + " s)" : ", prefilled)"));
  }
  check_jet_inlets(scene, s.jets, jet_index);
  double steady = estimate;
  for (const JetEmitter& j : s.jets) steady += j.steady_count(run_time);
  check_particle_budget(scene, steady, "the emitters, with the jets running for " + metres(run_time) + " s,",
                        "give the jets a lifetime or a stop time, lower the resolution");
  // The bodies before the fluid (the fluid filled where they are is removed), their particles once the
  // domain is known.
  s.bodies = place_rigid_bodies(scene, c, s.spacing);

  if (from_frame) {
    s.particles = initial_state_particles(scene, s.spacing, s.next_id);
    s.report.push_back("initial state: " + std::to_string(s.particles.size()) + " particles from " + scene.initial_state);
  } else {
    std::vector<EmitterFill> stats;
    std::vector<FilledPoint> points = fill_instant_emitters(scene.emitters, lattice, stats);
    for (std::size_t e = 0; e < scene.emitters.size(); ++e)
      if (scene.emitters[e].type != EmitterType::Jet && stats[e].created + stats[e].shared == 0)
        throw SceneError(scene.source + ": " + emitter_label(scene.emitters, e) + " holds no lattice point at spacing " +
                         metres(s.spacing) + " m; make it larger than the spacing or refine the resolution");
    s.adjusted = report_fill(scene, lattice, c, stats, s.report);
    const std::size_t filled = points.size();
    remove_blocked_points(scene, s.spacing, stats, points, s.report);
    remove_points_in_meshes(scene, s.meshes, s.spacing, points, s.report);
    remove_points_in_bodies(scene, s.bodies, s.spacing, points, s.report);
    s.adjusted = s.adjusted || points.size() != filled;
    double mass = 0.0;
    for (const FilledPoint& p : points) {
      const EmitterSpec& e = scene.emitters[std::size_t(p.emitter)];
      s.particles.append(Spawn{f3(p.pos), f3(e.velocity), 0.0f, float(scene.fluids[std::size_t(e.fluid)].rest_density),
                               uint8_t(e.fluid), s.next_id++});
      mass += double(c.fluids[e.fluid].mass);
    }
    if (points.size() != filled)
      s.report.push_back("after the checks: " + std::to_string(points.size()) + " particles, " + metres(mass) +
                         " kg of fluid");
  }
  for (JetEmitter& j : s.jets)
    for (const Spawn& sp : j.prefill(s.next_id)) s.particles.append(sp);

  s.expected_particles = double(s.particles.size());
  for (const JetEmitter& j : s.jets) s.expected_particles += j.steady_count(run_time);
  if (s.particles.size() == 0 && s.jets.empty())
    throw SceneError(scene.source + ": the emitters create no particle at spacing " + metres(s.spacing) +
                     " m once the particles inside solids are removed");

  c.grid = make_grid(scene, s.particles, s.jets, s.h);
  if (scene.solver == Solver::Pbf && scene.pbf.coarse_grid != 0) check_coarse_grid(scene, c.grid, s.report);
  // The walls' boundary particles, over the domain the grid now spans (planes and quadrics reach that far).
  if (scene.boundary_particles) {
    try {
      s.boundary = sample_boundary_particles(c, s.meshes, s.spacing, particle_budget(scene), s.report);
    } catch (const std::invalid_argument& e) {
      throw SceneError(scene.source + ": sph.walls: " + e.what());
    }
    std::ostringstream os;
    os << s.boundary.size() << " boundary particles in all (sph.walls = \"particles\")";
    s.report.push_back(os.str());
  }
  sample_rigid_bodies(scene, c, s.spacing, particle_budget(scene), s.bodies, s.report);
  check_interface_gas(scene, s);
  try {
    s.springs = create_springs(c, s.particles, s.spacing);
  } catch (const std::invalid_argument& e) {
    throw SceneError(scene.source + ": resolution.neighbours: " + e.what());
  }
  if (!s.springs.empty()) {
    const long ends = long(std::count_if(s.springs.partner.begin(), s.springs.partner.end(), [](int32_t p) { return p >= 0; }));
    std::ostringstream os;
    os << "springs: " << ends / 2 << " between the particles of the elastic fluids, up to " << s.springs.capacity
       << " per particle (" << (s.springs.bytes() >> 20) << " MiB)";
    s.report.push_back(os.str());
  }
  // Spring settings on a fluid without springs do nothing: said, not silently dropped.
  for (std::size_t i = 0; i < scene.fluids.size(); ++i) {
    const FluidSpec& f = scene.fluids[i];
    if (f.spring_modulus > 0.0 || (f.spring_yield == FluidSpec{}.spring_yield && f.spring_plasticity == 0.0)) continue;
    s.report.push_back("note: fluids." + std::to_string(i) + " has no springs (spring_modulus 0): its spring_yield and "
                       "spring_plasticity do nothing");
  }
  s.blowup_speed = fallback_blowup_speed(scene, s.max_speed_of_sound, s.jets);
}

}  // namespace

double fallback_blowup_speed(const Scene& scene, double max_speed_of_sound, const std::vector<JetEmitter>& jets) {
  double fastest = max_speed_of_sound;
  for (const JetEmitter& j : jets) fastest = std::max(fastest, j.spec().speed);
  return scene.blowup_speed > 0.0 ? scene.blowup_speed : 10.0 * fastest;
}

Setup create_setup(const Scene& scene, double run_time) {
  Setup s;
  double estimate = 0.0;
  try {
    build_setup(scene, run_time, s, estimate);
  } catch (const std::bad_alloc&) {
    throw SceneError(out_of_memory_text(scene, std::max(estimate, double(s.particles.size()))));
  }
  return s;
}

}  // namespace sph
