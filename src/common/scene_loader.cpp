// Scene files: JSON with string names for every choice, defaults in code, strict validation. Unknown keys,
// unknown names, wrong types, non-finite or out-of-range numbers are errors that name the file and the key.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scene.h"
#include "scene_file.h"
#include "scene_fluids.h"
#include "scene_overrides.h"
#include "scene_reader.h"

namespace sph {

using namespace scene_reading;

namespace {


FluidSpec read_fluid(ObjectReader& r) {
  r.allow({"name", "rest_density", "speed_of_sound", "viscosity", "artificial_viscosity", "near_stiffness",
           "surface_tension", "contact_angle", "xsph", "spring_modulus", "spring_yield", "spring_plasticity"});
  FluidSpec f;
  f.name = r.string("name", f.name);
  f.rest_density = r.number("rest_density", f.rest_density, 0.0, 1e5, true);
  f.speed_of_sound = r.number("speed_of_sound", f.speed_of_sound, 0.0, 1e4, true);
  f.viscosity = r.number("viscosity", f.viscosity, 0.0, 1e5);
  f.artificial_viscosity = r.number("artificial_viscosity", f.artificial_viscosity, 0.0, 10.0);
  f.near_stiffness = r.number("near_stiffness", f.near_stiffness, 0.0, 1e8);
  f.surface_tension = r.number("surface_tension", f.surface_tension, 0.0, 1e6);
  f.contact_angle = r.number("contact_angle", f.contact_angle, 0.0, 180.0, true);
  f.xsph = r.number("xsph", f.xsph, 0.0, 1.0);
  f.spring_modulus = r.number("spring_modulus", f.spring_modulus, 0.0, 1e9);
  f.spring_yield = r.number("spring_yield", f.spring_yield, 0.0, 10.0);
  f.spring_plasticity = r.number("spring_plasticity", f.spring_plasticity, 0.0, 1e4);
  r.finish();
  return f;
}

// A fluid named by its name or its index in "fluids" (key: the value's path, for messages).
int fluid_index(const json& v, const std::vector<FluidSpec>& fluids, const std::string& source, const std::string& key) {
  if (v.is_number_integer()) {
    const long i = v.get<long>();
    if (i < 0 || i >= long(fluids.size())) fail(source, key, "index " + std::to_string(i) + " does not name a fluid");
    return int(i);
  }
  if (v.is_string()) {
    for (std::size_t i = 0; i < fluids.size(); ++i)
      if (fluids[i].name == v.get<std::string>()) return int(i);
    std::string names;
    for (const FluidSpec& f : fluids) names += (names.empty() ? "\"" : ", \"") + f.name + "\"";
    fail(source, key, "no fluid named \"" + v.get<std::string>() + "\"; the fluids: " + names);
  }
  fail(source, key, "expected a fluid name or an integer index");
}

int read_fluid_ref(ObjectReader& r, const std::vector<FluidSpec>& fluids) {
  if (!r.has("fluid")) return 0;
  return fluid_index(r.raw("fluid"), fluids, r.source(), r.key_path("fluid"));
}

// "interface_tension": [{"fluids": [A, B], "sigma": N/m}, ...], each pair of different fluids at most once.
void read_interface_tensions(const json& list, const std::string& source, Scene& s) {
  if (!list.is_array())
    fail(source, "interface_tension", "expected a list of {\"fluids\": [A, B], \"sigma\": N/m} (A, B: fluid names or indices)");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "interface_tension." + std::to_string(i);
    ObjectReader r(list[i], source, path);
    r.allow({"fluids", "sigma"});
    if (!r.has("fluids")) r.missing("fluids", "is required: the two fluids, [A, B], by name or index");
    if (!r.has("sigma")) r.missing("sigma", "is required: the interface tension in N/m, >= 0");
    const json& pair = r.raw("fluids");
    if (!pair.is_array() || pair.size() != 2) fail(source, path + ".fluids", "expected two fluids, [A, B], by name or index");
    InterfaceTensionSpec t;
    t.a = fluid_index(pair[0], s.fluids, source, path + ".fluids.0");
    t.b = fluid_index(pair[1], s.fluids, source, path + ".fluids.1");
    if (t.a == t.b) fail(source, path + ".fluids", "names one fluid twice; an interface is between two different fluids");
    t.sigma = r.number("sigma", 0.0, 0.0, 1e6);
    for (const InterfaceTensionSpec& u : s.interface_tensions)
      if ((u.a == t.a && u.b == t.b) || (u.a == t.b && u.b == t.a))
        fail(source, path + ".fluids", "this pair of fluids is given twice");
    r.finish();
    s.interface_tensions.push_back(t);
  }
}

EmitterSpec read_emitter(ObjectReader& r, const std::vector<FluidSpec>& fluids) {
  EmitterSpec e;
  e.type = r.choice<EmitterType>("type", EmitterType::Box,
                                 {{"box", EmitterType::Box}, {"sphere", EmitterType::Sphere}, {"jet", EmitterType::Jet}});
  if (!r.has("type")) r.missing("type", "is required (\"box\", \"sphere\" or \"jet\")");
  e.fluid = read_fluid_ref(r, fluids);
  switch (e.type) {
    case EmitterType::Box:
      r.allow({"type", "fluid", "min", "max", "velocity"});
      e.min = r.required_vec3("min");
      e.max = r.required_vec3("max");
      check_box(e.min, e.max, r.source(), r.key_path("max"));
      e.velocity = r.vec3("velocity", e.velocity);
      break;
    case EmitterType::Sphere:
      r.allow({"type", "fluid", "center", "radius", "velocity"});
      e.center = r.required_vec3("center");
      if (!r.has("radius")) r.missing("radius", "is required");
      e.radius = r.number("radius", 0.0, 0.0, kHuge, true);
      e.velocity = r.vec3("velocity", e.velocity);
      break;
    case EmitterType::Jet:
      r.allow({"type", "fluid", "section", "position", "direction", "radius", "speed", "lifetime",
               "inlet_length", "start", "stop"});
      e.section = r.choice<JetSection>("section", JetSection::Circle,
                                       {{"circle", JetSection::Circle}, {"square", JetSection::Square}});
      e.position = r.required_vec3("position");
      e.direction = normalised(r.vec3("direction", e.direction), r.source(), r.key_path("direction"));
      if (!r.has("radius")) r.missing("radius", "is required");
      e.radius = r.number("radius", 0.0, 0.0, kHuge, true);
      if (!r.has("speed")) r.missing("speed", "is required");
      e.speed = r.number("speed", 0.0, 0.0, 1e4, true);
      e.lifetime = r.number("lifetime", 0.0, 0.0, 1e6);
      e.inlet_length = r.number("inlet_length", -1.0, -1.0, kHuge);
      e.start = r.number("start", 0.0, 0.0, 1e9);
      e.stop = r.has("stop") ? r.number("stop", 0.0, 0.0, 1e9) : e.stop;
      if (e.stop <= e.start) fail(r.source(), r.key_path("stop"), "must be later than start");
      break;
  }
  r.finish();
  return e;
}

void read_coefficients(ObjectReader& r, Shape& s) {
  s.bounce = float(r.number("bounce", 0.0, 0.0, 1.0));
  s.slip = float(r.number("slip", 1.0, 0.0, 1.0));
  s.energy_conserving = r.boolean("energy_conserving", false) ? 1 : 0;
}

Vec3 to_vec3(const Vec3d& v) { return Vec3{float(v[0]), float(v[1]), float(v[2])}; }

BoundarySpec read_boundary(ObjectReader& r) {
  BoundarySpec b;
  Shape& s = b.shape;
  s.type = r.choice<ShapeType>("type", ShapeType::Box,
                               {{"box", ShapeType::Box}, {"plane", ShapeType::Plane}, {"sphere", ShapeType::Sphere},
                                {"quadric", ShapeType::Quadric}});
  if (!r.has("type")) r.missing("type", "is required (\"box\", \"plane\", \"sphere\" or \"quadric\")");
  read_coefficients(r, s);
  switch (s.type) {
    case ShapeType::Box: {
      r.allow({"type", "bounce", "slip", "energy_conserving", "min", "max", "inside", "open_top"});
      const Vec3d lo = r.required_vec3("min"), hi = r.required_vec3("max");
      check_box(lo, hi, r.source(), r.key_path("max"));
      s.a = to_vec3(lo);
      s.b = to_vec3(hi);
      s.keep_inside = r.boolean("inside", true);
      s.open_top = r.boolean("open_top", false);
      break;
    }
    case ShapeType::Plane:
      r.allow({"type", "bounce", "slip", "energy_conserving", "point", "normal", "absorb"});
      s.absorb = r.boolean("absorb", false) ? 1 : 0;
      s.a = to_vec3(r.required_vec3("point"));
      if (!r.has("normal")) r.missing("normal", "is required");
      s.b = to_vec3(normalised(r.vec3("normal", {}), r.source(), r.key_path("normal")));
      break;
    case ShapeType::Sphere:
      r.allow({"type", "bounce", "slip", "energy_conserving", "center", "radius", "inside"});
      s.a = to_vec3(r.required_vec3("center"));
      if (!r.has("radius")) r.missing("radius", "is required");
      s.radius = float(r.number("radius", 0.0, 0.0, kHuge, true));
      s.keep_inside = r.boolean("inside", true);
      break;
    case ShapeType::Quadric: {
      r.allow({"type", "bounce", "slip", "energy_conserving", "matrix"});
      if (!r.has("matrix")) r.missing("matrix", "is required (4x4 symmetric, fluid where p^T Q p >= 0)");
      const json& m = r.raw("matrix");
      const std::string key = r.key_path("matrix");
      if (!m.is_array() || m.size() != 4) fail(r.source(), key, "expected 4 rows of 4 numbers");
      for (int i = 0; i < 4; ++i) {
        if (!m[i].is_array() || m[i].size() != 4) fail(r.source(), key, "expected 4 rows of 4 numbers");
        for (int j = 0; j < 4; ++j) {
          if (!m[i][j].is_number() || !std::isfinite(m[i][j].get<double>()))
            fail(r.source(), key, "expected 4 rows of 4 finite numbers");
          s.q[4 * i + j] = float(m[i][j].get<double>());
        }
      }
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < i; ++j)
          if (std::fabs(s.q[4 * i + j] - s.q[4 * j + i]) > 1e-6f * (1.0f + std::fabs(s.q[4 * i + j])))
            fail(r.source(), key, "the matrix must be symmetric");
      break;
    }
  }
  r.finish();
  return b;
}

}  // namespace

double EmitterSpec::min_extent() const {
  switch (type) {
    case EmitterType::Box:
      return std::min({max[0] - min[0], max[1] - min[1], max[2] - min[2]});
    case EmitterType::Sphere:
    case EmitterType::Jet:
      return 2.0 * radius;
  }
  return 0.0;
}

namespace {

// The scene in root (the file with the --set overrides applied); SceneError names source and the key.
Scene read_scene(const json& root, const std::string& source) {
  Scene s;
  s.source = source;
  ObjectReader r(root, source, "");
  r.allow({"name", "description", "fluids", "emitters", "boundaries", "resolution", "sph", "solver", "dfsph", "pbf",
           "integrator", "time_step", "gravity", "domain", "run", "limits", "relaxation", "initial_state", "on_overlap",
           "meshes", "bodies", "probes", "interface_tension"});
  s.name = r.string("name", s.name);
  s.description = r.string("description", "");

  if (!r.has("fluids")) r.missing("fluids", "is required: a list of fluids (at least one)");
  const json& fl = r.raw("fluids");
  if (!fl.is_array() || fl.empty()) fail(source, "fluids", "expected a non-empty list of fluid objects");
  if (fl.size() > std::size_t(kMaxFluids))
    fail(source, "fluids", "at most " + std::to_string(kMaxFluids) + " fluids are supported");
  for (std::size_t i = 0; i < fl.size(); ++i) {
    ObjectReader fr(fl[i], source, "fluids." + std::to_string(i));
    s.fluids.push_back(read_fluid(fr));
  }
  if (r.has("interface_tension")) read_interface_tensions(r.raw("interface_tension"), source, s);

  if (r.has("initial_state")) {  // a path relative to the scene file; frame_reader.h reads and checks it
    const fs::path p = r.string("initial_state", "");
    if (p.empty()) fail(source, "initial_state", "expected the path of a frame (.ply) written by sph_run");
    s.initial_state = (p.is_absolute() ? p : fs::path(source).parent_path() / p).string();
  }
  // With an initial state the emitters may be left out: the frame holds the fluid.
  if (!r.has("emitters") && s.initial_state.empty())
    r.missing("emitters", "is required: a list of emitters (box, sphere, jet), or an initial_state");
  const json& em = r.has("emitters") ? r.raw("emitters") : json::array();
  if (!em.is_array() || (em.empty() && s.initial_state.empty()))
    fail(source, "emitters", "expected a non-empty list of emitter objects");
  for (std::size_t i = 0; i < em.size(); ++i) {
    ObjectReader er(em[i], source, "emitters." + std::to_string(i));
    s.emitters.push_back(read_emitter(er, s.fluids));
  }

  if (r.has("boundaries")) {
    const json& bd = r.raw("boundaries");
    if (!bd.is_array()) fail(source, "boundaries", "expected a list of boundary objects");
    if (bd.size() > std::size_t(kMaxShapes))
      fail(source, "boundaries", "at most " + std::to_string(kMaxShapes) + " boundaries are supported");
    for (std::size_t i = 0; i < bd.size(); ++i) {
      ObjectReader br(bd[i], source, "boundaries." + std::to_string(i));
      s.boundaries.push_back(read_boundary(br));
    }
  }

  read_meshes(r, s);
  read_bodies(r, s);
  read_probes(r, s);

  if (!r.has("resolution")) r.missing("resolution", "is required: {\"particles_across\": N} or {\"spacing\": metres}");
  {
    ObjectReader rr(r.raw("resolution"), source, "resolution");
    rr.allow({"particles_across", "spacing", "neighbours", "mass"});
    const bool across = rr.has("particles_across"), spacing = rr.has("spacing");
    if (across == spacing) rr.missing("", "give exactly one of particles_across and spacing");
    if (across) {
      const json& v = rr.raw("particles_across");
      if (!v.is_number_integer()) fail(source, "resolution.particles_across", "expected a whole number");
      const long n = v.get<long>();
      if (n < 2 || n > 100000)
        fail(source, "resolution.particles_across", "value " + std::to_string(n) + " is out of range: allowed [2, 100000]");
      s.particles_across = int(n);
      if (s.emitters.empty())
        fail(source, "resolution.particles_across", "counts across the first emitter, and there is none; give resolution.spacing");
    } else {
      s.spacing = rr.number("spacing", 0.0, 0.0, kHuge, true);
    }
    s.neighbours = rr.number("neighbours", s.neighbours, 4.0, 500.0);
    s.mass_rule = rr.choice<MassRule>("mass", s.mass_rule,
                                      {{"rest_density", MassRule::RestDensity}, {"volume", MassRule::Volume}});
    rr.finish();
  }

  if (r.has("sph")) {
    ObjectReader sr(r.raw("sph"), source, "sph");
    sr.allow({"density", "equation_of_state", "pressure_force", "kernel", "viscosity", "negative_pressure", "walls",
              "multiphase", "surface_tension"});
    s.density = sr.choice<DensityMethod>("density", s.density,
                                         {{"summation", DensityMethod::Summation}, {"continuity", DensityMethod::Continuity}});
    s.eos = sr.choice<EquationOfState>("equation_of_state", s.eos,
                                       {{"tait", EquationOfState::Tait}, {"ideal", EquationOfState::Ideal}});
    s.pressure_form = sr.choice<PressureForm>(
        "pressure_force", s.pressure_form, {{"monaghan", PressureForm::MonaghanSymmetric}, {"mueller", PressureForm::Mueller}});
    s.kernel_set = sr.has("kernel");
    s.kernel = sr.choice<KernelPair>("kernel", s.kernel,
                                     {{"poly6_spiky", KernelPair::Poly6Spiky}, {"cubic_spline", KernelPair::CubicSpline}});
    s.viscosity = sr.choice<ViscosityModel>("viscosity", s.viscosity,
                                            {{"none", ViscosityModel::None},
                                             {"mueller", ViscosityModel::Mueller},
                                             {"morris", ViscosityModel::Morris},
                                             {"artificial", ViscosityModel::Artificial}});
    s.clamp_negative_pressure =
        sr.choice<bool>("negative_pressure", s.clamp_negative_pressure, {{"keep", false}, {"clamp", true}});
    // 0 penalty, 1 mirror, 2 particles.
    const int walls = sr.choice<int>("walls", s.boundary_particles ? 2 : s.mirror_walls ? 1 : 0,
                                     {{"penalty", 0}, {"mirror", 1}, {"particles", 2}});
    s.mirror_walls = walls == 1;
    s.boundary_particles = walls == 2;
    s.number_density = sr.choice<bool>("multiphase", s.number_density,
                                       {{"number_density", true}, {"mass_density", false}});
    s.surface_tension_model = sr.choice<SurfaceTensionModel>(
        "surface_tension", s.surface_tension_model, {{"cohesion", SurfaceTensionModel::Cohesion}, {"csf", SurfaceTensionModel::Csf}});
    sr.finish();
  }

  read_solver(r, s);
  // PBF has no wall force: its walls are the collision and, in its constraint, the walls' mirror images. With
  // the collision alone a front piles particles onto a wall's plane, where nothing pushes them off, and the
  // 16k dam break blew up at the impact (0.33 s, at 4 and at 2 ms steps; docs/results.md). So under PBF
  // penalty walls run as mirror walls, and the set-up says so.
  if (s.solver == Solver::Pbf && !s.mirror_walls && !s.boundary_particles) {
    s.mirror_walls = true;
    s.penalty_walls_as_mirror = true;
  }
  check_fluid_ratios(s);
  if (!s.bodies.empty() && !s.boundary_particles)
    fail(source, "bodies", "rigid bodies are made of boundary particles: set \"sph\": {\"walls\": \"particles\"} (--set sph.walls=particles)");
  if (!s.bodies.empty() && s.solver == Solver::Pbf)
    fail(source, "bodies", "rigid bodies are coupled to the wcsph and dfsph solvers only so far, not to \"pbf\" "
                           "(allowed: \"solver\": \"wcsph\" or \"dfsph\")");
  // Between fluids of different density the projection stirred the interface: two_layers (1000 and 100
  // kg/m^3) mixed within 0.5 s (docs/results.md, "PBF's coarse grid").
  if (s.solver == Solver::Pbf && s.pbf.coarse_grid != 0)
    for (const FluidSpec& f : s.fluids)
      if (f.rest_density != s.fluids.front().rest_density) {
        std::ostringstream os;
        os << "the coarse grid is for fluids of one rest density, and \"" << s.fluids.front().name << "\" has "
           << s.fluids.front().rest_density << " kg/m^3 where \"" << f.name << "\" has " << f.rest_density
           << " (between them it mixes the interface); set pbf.coarse_grid false";
        fail(source, "pbf.coarse_grid", os.str());
      }
  // The coarse grid's walls are the analytic shapes (pbf_coarse.h, shape_excludes): boundary particles would
  // count as air there, and the projection would push the fluid into them.
  if (s.solver == Solver::Pbf && s.pbf.coarse_grid != 0 && s.boundary_particles)
    fail(source, "pbf.coarse_grid", "the coarse grid knows the walls of \"boundaries\" (mirror or penalty walls), not walls "
                                    "of boundary particles: set \"sph\": {\"walls\": \"mirror\"} or pbf.coarse_grid false");
  if (!s.meshes.empty() && !s.boundary_particles)
    fail(source, "meshes", "triangle meshes are walls of boundary particles only: set \"sph\": {\"walls\": \"particles\"} "
                           "(--set sph.walls=particles); mirror and penalty walls know the analytic shapes of \"boundaries\"");

  s.integrator = r.choice<Integrator>("integrator", s.integrator,
                                      {{"explicit_euler", Integrator::ExplicitEuler},
                                       {"semi_implicit_euler", Integrator::SemiImplicitEuler},
                                       {"velocity_verlet", Integrator::VelocityVerlet},
                                       {"modified_velocity_verlet", Integrator::ModifiedVelocityVerlet},
                                       {"leapfrog", Integrator::Leapfrog}});

  if (r.has("time_step")) {
    ObjectReader tr(r.raw("time_step"), source, "time_step");
    tr.allow({"mode", "dt", "min", "max", "cfl_velocity", "cfl_acceleration", "cfl_sound", "cfl_viscosity"});
    TimeStepSpec& t = s.time_step;
    t.mode = tr.choice<TimeStepMode>("mode", t.mode, {{"fixed", TimeStepMode::Fixed}, {"adaptive", TimeStepMode::Adaptive}});
    t.dt = tr.number("dt", t.dt, 0.0, 10.0, true);
    t.min = tr.number("min", t.min, 0.0, 10.0, true);
    t.max = tr.number("max", t.max, 0.0, 10.0, true);
    if (t.min > t.max) fail(source, "time_step.min", "must not exceed time_step.max");
    t.cfl_velocity = tr.number("cfl_velocity", t.cfl_velocity, 0.0, 10.0, true);
    t.cfl_acceleration = tr.number("cfl_acceleration", t.cfl_acceleration, 0.0, 10.0, true);
    t.cfl_sound = tr.number("cfl_sound", t.cfl_sound, 0.0, 10.0, true);
    t.cfl_viscosity = tr.number("cfl_viscosity", t.cfl_viscosity, 0.0, 1.0, true);  // 1: the stability bound
    tr.finish();
  }

  s.gravity = r.vec3("gravity", s.gravity, 1e4);
  if (!s.probes.empty() && s.gravity == Vec3d{0.0, 0.0, 0.0})
    fail(source, "probes", "a probe measures depth along gravity, and \"gravity\" is zero");
  s.overlap_error = r.choice<bool>("on_overlap", false, {{"remove", false}, {"error", true}});

  if (r.has("domain")) {
    ObjectReader dr(r.raw("domain"), source, "domain");
    dr.allow({"min", "max"});
    s.domain_min = dr.required_vec3("min");
    s.domain_max = dr.required_vec3("max");
    check_box(s.domain_min, s.domain_max, source, "domain.max");
    s.has_domain = true;
    dr.finish();
  }

  if (r.has("run")) {
    ObjectReader rr(r.raw("run"), source, "run");
    rr.allow({"time", "frames_every"});
    s.run_time = rr.number("time", s.run_time, 0.0, 1e7, true);
    s.frames_every = rr.number("frames_every", s.frames_every, 0.0, 1e7);
    rr.finish();
  }

  if (r.has("relaxation")) {
    ObjectReader xr(r.raw("relaxation"), source, "relaxation");
    xr.allow({"enabled", "viscosity", "speed_threshold", "max_steps"});
    RelaxationSpec& x = s.relaxation;
    x.enabled = xr.boolean("enabled", true);
    x.viscosity = xr.number("viscosity", x.viscosity, 0.0, 1e6);
    x.speed_threshold = xr.number("speed_threshold", x.speed_threshold, 0.0, 1e4);
    x.max_steps = long(xr.number("max_steps", double(x.max_steps), 1.0, 1e7));
    xr.finish();
  }

  if (r.has("limits")) {
    ObjectReader lr(r.raw("limits"), source, "limits");
    lr.allow({"max_particles", "blowup_speed"});
    s.max_particles = lr.number("max_particles", s.max_particles, 1.0, 2e9);
    s.blowup_speed = lr.number("blowup_speed", s.blowup_speed, 0.0, 1e8);
    lr.finish();
  }
  r.finish();
  return s;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers out of a double's range
    throw SceneError(source + ": not valid JSON: " + e.what());
  }
  const json file = overrides.empty() ? json() : root;
  for (const auto& o : overrides) apply_override(root, o, source);
  try {
    return read_scene(root, source);
  } catch (const SceneError& e) {
    const std::string message = e.what();
    if (const std::string* o = override_of(message, source, overrides, file))
      throw SceneError("--set \"" + *o + "\": " + message.substr(source.size() + 2) + " (in the scene " + source +
                       " as changed by --set)");
    throw;
  }
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_scene(read_scene_file(path), path, overrides);
}

}  // namespace sph
