// A scene as the user describes it (JSON, scenes/*.json): physical properties, emitters, boundaries and
// method choices by name. Loading validates everything and fills defaults (scene_loader.cpp); guided
// creation (guided_creation.h) turns it into simulation constants and particles.
#pragma once

#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "params.h"

namespace sph {

using Vec3d = std::array<double, 3>;

// Every problem with a scene file or an override is reported as a SceneError naming the file and the key.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct FluidSpec {
  std::string name = "water";
  double rest_density = 1000.0;    // kg/m^3
  double speed_of_sound = 20.0;    // m/s (numerical, far below water's 1500: thesis 3.2)
  double viscosity = 1e-3;         // mu [Pa s], the laminar viscosity (Mueller or Morris, sph.viscosity)
  double artificial_viscosity = 0.05; // alpha of Monaghan's artificial viscosity, added to any laminar model; 0 = off
  double near_stiffness = 0.0;     // k_near, m^2/s^2; 0 = no double density relaxation
  double surface_tension = 0.0;    // sigma [N/m], cohesion calibrated to it (calibration.h); 0 = off
  double xsph = 0.0;               // XSPH epsilon; 0 = off
  // Equilibrium contact angle [degrees] on boundary particles, (0, 180]: Akinci's adhesion calibrated to it
  // (cohesion_energy.h, adhesion_constant); 0 (the key absent) = no adhesion term.
  double contact_angle = 0.0;
  // Viscoelastic springs between close particles at the start (springs.h): shear modulus G [Pa] of the
  // spring network (0 = none), yield ratio gamma and plasticity alpha [1/s] (Clavet et al. 2005).
  double spring_modulus = 0.0;
  double spring_yield = 0.1;
  double spring_plasticity = 0.0;
};

enum class EmitterType { Box, Sphere, Jet };
enum class JetSection { Circle, Square };

struct EmitterSpec {
  EmitterType type = EmitterType::Box;
  int fluid = 0;
  Vec3d min{}, max{};              // box
  Vec3d center{};                  // sphere
  double radius = 0.0;             // sphere radius, circular jet radius, square jet half side
  Vec3d velocity{};                // box, sphere: initial velocity
  // jet (thesis 4.1.4 "circle / square flow", 4.1.6 inlet flow)
  JetSection section = JetSection::Circle;
  Vec3d position{};                // centre of the outlet (the "real birth position")
  Vec3d direction{1.0, 0.0, 0.0};  // unit vector after loading
  double speed = 0.0;
  double lifetime = 0.0;           // recycle particles older than this [s]; 0 = never
  double inlet_length = -1.0;      // < 0: 4 h (thesis 4.1.6)
  double start = 0.0;
  double stop = std::numeric_limits<double>::infinity();

  // Smallest extent of the fluid this emitter creates, used by resolution.particles_across.
  double min_extent() const;
};

// An interface tension between two fluids (scene key "interface_tension", cohesion model): sigma_ab [N/m],
// set by a cohesion between their particles (calibration.h, cross_cohesion). Pairs not listed meet with
// sigma_a + sigma_b (no attraction between them).
struct InterfaceTensionSpec {
  int a = 0, b = 0;     // fluid indices, a != b
  double sigma = 0.0;   // [N/m], >= 0
};

struct BoundarySpec {
  Shape shape{};  // type, coefficients and geometry, ready for SimConstants
};

// A rigid body (scene key "bodies", issue 13; rigid_body.h): a box, a sphere or a closed triangle mesh of
// boundary particles that the fluid pushes and that pushes the fluid (WCSPH, sph.walls = "particles").
struct BodySpec {
  bool sphere = false;
  bool mesh = false;    // a closed triangle mesh (OBJ), placed as the scene's meshes are
  Vec3d min{}, max{};   // box [m]
  Vec3d center{};       // sphere [m]
  double radius = 0.0;  // sphere [m]
  std::string file;     // mesh: OBJ, resolved against the scene file's folder
  Vec3d scale{1.0, 1.0, 1.0}, translate{};  // mesh: per axis, then [m]
  double density = 0.0; // [kg/m^3]; or
  double mass = 0.0;    // [kg]: exactly one of the two is given
  bool free = true;     // "motion": "free" (moved by the fluid and gravity), "fixed" or "prescribed"
  bool prescribed = false;
  // prescribed: with s = sin(2 pi t / period), the body turns by angle s about the axis through pivot and
  // moves by amplitude s: centre(t) = pivot + R(angle s) (start - pivot) + amplitude s (a piston and/or a
  // flap wave maker)
  Vec3d amplitude{};    // [m]
  double period = 0.0;  // [s]
  double angle = 0.0;   // [rad] (the scene gives degrees)
  Vec3d axis{0.0, 0.0, 1.0};  // unit
  Vec3d pivot{};        // [m]
  double slip = 1.0;    // as a shape's: the friction factor of its particles is 1 - slip
};

// A triangle mesh as a solid (scene key "meshes", issue 13; mesh.h): sampled with boundary particles only,
// so it needs sph.walls = "particles".
struct MeshSpec {
  std::string file;              // OBJ, resolved against the scene file's folder
  bool inside = false;           // true: a container (fluid inside); false: an obstacle
  Vec3d scale{1.0, 1.0, 1.0};    // per axis, applied first
  Vec3d translate{0.0, 0.0, 0.0};  // [m], then
  double slip = 1.0;             // 1 - the boundary particles' friction factor, as a shape's slip
};

// A water-height probe (scene key "probes"): the depth of fluid above `position` along -gravity, written to
// metrics.csv as the column depth_<name> (metrics.h, probe_depth). Like a wave gauge of an experiment.
struct ProbeSpec {
  std::string name;   // letters, digits and '_'
  Vec3d position{};   // [m], normally on the floor
};

enum class TimeStepMode { Fixed, Adaptive };
enum class MassRule { RestDensity, Volume };

struct TimeStepSpec {
  TimeStepMode mode = TimeStepMode::Adaptive;
  double dt = 1e-3;               // fixed step, and the first step of an adaptive run
  double min = 1e-7;
  double max = 1e-2;
  double cfl_velocity = 0.4;      // dt <= C_v h / v_max (thesis 2.3.5)
  double cfl_acceleration = 0.25; // dt <= C_a sqrt(h / a_max)
  double cfl_sound = 0.4;         // dt <= C_c h / (c0 + v_max)
  // dt <= C_nu 2 / lambda_max, lambda_max the fastest rate of the discrete viscous operator (viscous_limit.h).
  // 0.5 keeps lambda dt <= 1: the fastest mode decays without changing sign, and the margin of 2 covers the
  // lower densities at a free surface (up to 1.34 lambda_max on a small cube, tests/test_timestep.cpp).
  double cfl_viscosity = 0.5;
};

// Relaxation phase (thesis 4.1.6): before time starts the fluid moves without gravity and with a large
// viscosity until the largest speed, and the speed one step of the largest acceleration adds, stay below a
// threshold for three steps; then the run starts from
// the relaxed positions at rest.
struct RelaxationSpec {
  bool enabled = false;
  double viscosity = 0.0;        // Pa s, Mueller viscosity during relaxation; 0 = rho0 * 0.03 h c0, about a
                                 // fifth of what would make the viscous step limit equal the sound step limit
  double speed_threshold = 0.0;  // m/s; 0 = 1e-3 c0
  long max_steps = 5000;
};

struct Scene {
  std::string name = "unnamed";
  std::string description;
  std::string source;  // file it came from, for messages

  std::vector<FluidSpec> fluids;
  std::vector<InterfaceTensionSpec> interface_tensions;
  std::vector<EmitterSpec> emitters;
  std::vector<BoundarySpec> boundaries;
  std::vector<MeshSpec> meshes;
  std::vector<BodySpec> bodies;
  std::vector<ProbeSpec> probes;

  // Resolution (thesis 4.1.4): either particles across the first emitter's smallest extent, or a spacing.
  int particles_across = 0;
  double spacing = 0.0;
  double neighbours = 32.0;            // n_avg, thesis 4.1.5
  MassRule mass_rule = MassRule::RestDensity;

  // Default method set: safe, i.e. a scene that names no method is stable and never gains energy
  // (measured in docs/defaults.md: the dam break, a pour into a tank and the water jet; tests/test_energy.cpp).
  // - summation density, Tait, Monaghan's symmetric pressure force (conserves momentum exactly);
  // - negative pressure clamped: kept, it pulls free-surface particles into clumps (tensile instability);
  //   the dam break then exceeds 1.2 times its energy budget within 50 steps, even with the two below;
  // - Monaghan artificial viscosity, alpha = 0.05 (FluidSpec), added to every pair whatever the laminar
  //   model: with only water's laminar viscosity nothing damps the noise of the kernel pair (below) and even
  //   clamped, mirror-walled runs reach 13 times the energy available;
  // - the fluids' own viscosity mu through Morris's laminar term (Morris 1997), so a scene's mu always acts
  //   (with the artificial term alone, honey would flow like water);
  // - mirror walls: penalty walls let a resting column sink 30% in 1 s (mirror_walls.h); mirror walls keep
  //   it within 1% (hydrostatic_tank's alpha 0.2; 1.3% with alpha 0.05, none of it from the walls), and
  //   their ghosts never pull (mirror_walls.h, push_only).
  // Kernels (sph.kernel): Poly6 density with Spiky's pressure gradient, the thesis's pair and the default;
  // it is not conservative (the pressure force is no energy's gradient), which is why some dissipation is
  // part of the default. "cubic_spline" takes the cubic spline for both [BT07], DFSPH's default: it
  // holds a drop's pressure at Laplace's value, and the 16k dam break's surge front halves its error against
  // the experiment, where the column's height moves farther from it (docs/results.md). Without the key a
  // WCSPH scene with the continuum surface force takes it too (calibration.h, wcsph_cubic_spline).
  DensityMethod density = DensityMethod::Summation;
  EquationOfState eos = EquationOfState::Tait;
  PressureForm pressure_form = PressureForm::MonaghanSymmetric;
  KernelPair kernel = KernelPair::Poly6Spiky;
  bool kernel_set = false;  // sph.kernel given: DFSPH and WCSPH's continuum surface force then take it; PBF says it ignores "cubic_spline"
  ViscosityModel viscosity = ViscosityModel::Morris;
  bool clamp_negative_pressure = true;
  bool mirror_walls = true;            // sph.walls: "mirror" (mirror_walls.h) or "penalty" (thesis 3.5.1)
  bool boundary_particles = false;     // sph.walls: "particles" (boundary_particles.h, [AIA12])
  // sph.walls = "penalty" under solver "pbf", run as mirror walls (mirror_walls is then true): PBF has no wall
  // force to make penalty walls of (scene_loader.cpp says why; a set-up note tells the user).
  bool penalty_walls_as_mirror = false;
  // sph.multiphase: "number_density" (Solenthaler & Pajarola 2008; density.h, forces.h), the default, or
  // "mass_density" (the plain sums of the neighbours' masses, which fail beyond a density ratio of about
  // 1.25 between touching fluids: issue 15). Only fluids of different particle mass tell them apart.
  bool number_density = true;
  // sph.surface_tension: "cohesion" (forces.h, the default) or "csf" (surface_tension_csf.h): how the fluids'
  // surface_tension acts.
  SurfaceTensionModel surface_tension_model = SurfaceTensionModel::Cohesion;
  // Not a scene key: false turns the continuum surface force's curvature limit off (surface_tension_csf.h,
  // csf_limited_curvature), so that a test shows what it prevents.
  bool csf_curvature_limit = true;
  Integrator integrator = Integrator::ModifiedVelocityVerlet;  // WCSPH's; DFSPH and PBF integrate their own way
  // The pressure solver ("solver") and the settings of the incompressible ones (blocks "dfsph", "pbf";
  // params.h says what each is). DFSPH reads sph.viscosity and sph.walls and the fluids' viscosity and
  // surface tension; PBF has XSPH for viscosity and collides with the boundaries (no mirror walls).
  Solver solver = Solver::Wcsph;
  DfsphConstants dfsph = dfsph_defaults();
  PbfConstants pbf = pbf_defaults();
  TimeStepSpec time_step;
  Vec3d gravity{0.0, -9.81, 0.0};

  bool has_domain = false;
  Vec3d domain_min{}, domain_max{};

  double run_time = 1.0;         // default simulated time for sph_run
  double frames_every = 0.0;     // 0 = no frames unless asked
  double max_particles = 2e7;
  double blowup_speed = 0.0;     // m/s; 0 = max(c0, 2 sqrt(e_max)) from the energy put in (Simulation::speed_bound)
  bool overlap_error = false;    // "on_overlap": fluid placed in a solid is "remove"d (default) or an "error"
  RelaxationSpec relaxation;
  // "initial_state": a frame (frame_writer.h) whose particles replace the instant emitters' fill; jets
  // still run. Stored resolved against the scene file's folder; empty = none.
  std::string initial_state;
};

// Reads, validates and fills defaults. overrides are "dotted.path=value" strings applied to the JSON
// before validation (sph_run --set). Throws SceneError with a message naming the file and the key.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});
Scene parse_scene(const std::string& json_text, const std::string& source,
                  const std::vector<std::string>& overrides = {});

// Names accepted for each choice, for messages and --help.
const char* integrator_name(Integrator m);
const char* solver_name(Solver m);  // "wcsph", "dfsph", "pbf": the scene's names

}  // namespace sph
