// Simulation constants: plain, trivially copyable structs with fixed-size arrays, so one copy can live in
// CUDA __constant__ memory and the same bytes drive the serial reference. Built from a Scene by
// make_sim_constants() (guided_creation.h); never edited by the back ends.
#pragma once

#include <cstdint>

#include "kernels.h"
#include "sph_hd.h"
#include "vec3.h"

namespace sph {

constexpr int kMaxFluids = 8;
constexpr int kMaxShapes = 16;
// Age given to a particle that an absorbing boundary took out; the recycle phase removes it.
constexpr float kRemovedAge = 3.0e38f;

enum class DensityMethod : int32_t { Summation, Continuity };        // thesis eq. 2.10 / 2.12
enum class EquationOfState : int32_t { Tait, Ideal };                // thesis eq. 2.15 / 2.14
enum class PressureForm : int32_t { MonaghanSymmetric, Mueller };    // thesis eq. 2.18 / 2.19
// The laminar (physical) viscosity, from the fluids' mu: thesis eq. 2.24 (Mueller) or Morris 1997. Artificial
// names no laminar term (older scenes); Monaghan's artificial viscosity (thesis eq. 2.21) is added to any of
// them wherever a fluid's alpha > 0 (SimConstants::artificial_enabled).
enum class ViscosityModel : int32_t { None, Mueller, Morris, Artificial };
// Whether the model has a laminar term (Mueller's or Morris's).
constexpr bool has_laminar_term(ViscosityModel m) { return m == ViscosityModel::Mueller || m == ViscosityModel::Morris; }
// The pressure solver of a step (src/solvers/): weakly compressible SPH with an equation of state (thesis
// chapter 2), divergence-free SPH [BK15] (src/common/dfsph.h) or position-based fluids [MM13] (pbf.h).
enum class Solver : int32_t { Wcsph, Dfsph, Pbf };
// Surface tension (sph.surface_tension): cohesion between a fluid's particles ([AKT13] kernel calibrated from
// sigma, forces.h) or the continuum surface force on its surface band (surface_tension_csf.h).
enum class SurfaceTensionModel : int32_t { Cohesion, Csf };
// WCSPH's kernels (sph.kernel; kernels.h, density_kernel): Poly6 for the density with Spiky's gradient
// [Mueller 2003] (thesis eqs. 2.44, 2.45), or the cubic spline for both [Monaghan 1992; BT07].
enum class KernelPair : int32_t { Poly6Spiky, CubicSpline };

// DFSPH's solver settings (scene block "dfsph"). Tolerances are fractions of the rest density: the density
// solver stops when the mean compression (rho* - rho0) / rho0 is at most density_tolerance ([BK15] eta, 0.01%),
// the divergence solver when the mean dt (D rho / Dt) / rho0 is at most divergence_tolerance (0.1% per step).
// Each solver runs at least min_iterations and at most max_iterations (a step that reaches the cap is
// counted and reported); the error is checked every check_every iterations (one reduction each, a read on
// a GPU), the same on every back end so that they stay bit-identical.
struct DfsphConstants {
  float density_tolerance;     // eta / rho0, > 0
  float divergence_tolerance;  // eta_v dt / rho0, > 0
  int32_t min_iterations;      // density solver; the divergence solver runs at least one
  int32_t max_iterations;      // both solvers
  int32_t check_every;
  int32_t divergence_solver;   // 1: run it (0 for the comparisons of [BK15] section 5)
  int32_t warm_start;          // 1: start from the last step's pressures ([BK15] section 4.3)
  // The share of the last step's pressures a warm start carries, in (0, 1]; 1 (the paper's) by default. Below 1
  // the carried pressure is a leaky memory. With all of it a resting column rings: the density solve stops at
  // a mean residual of 1e-4, and a bulk compression of that size left by one step is corrected by the next with
  // a pressure of order rho0 H^2 e / dt^2, as large as the hydrostatic one for H = 0.1 m at 1 ms steps, which
  // the warm start carries on. Measured (2026-12-02, hydrostatic_tank.json, docs/results.md, "DFSPH's warm
  // start"): at 1 ms steps, 10 across, the floor's pressure swung between 0.4 and 1.7 times hydrostatic over
  // about six steps with 1 (rms speed 3.6 to 9 mm/s), as much with 0.9, and held within 3% with 0.75 (0.03 to
  // 0.06 mm/s, 17 iterations a step against 27) or 0.5; at 2.6 ms steps 0.75 calmed the median of the fastest particle (0.010 against
  // 0.021 m/s) but took 67 iterations against 24 and let single particles reach 0.08 m/s (1: 0.028), so it
  // is not the default. SPlisHSPlasH carries half.
  float warm_start_fraction;
  // Chebyshev semi-iterative acceleration of both solves' Jacobi iteration ([Wan15]: H. Wang 2015, "A
  // Chebyshev semi-iterative approach for accelerating projective and position-based dynamics", ACM TOG
  // 34(6)): the estimate rho of the iteration's spectral radius, in [0, 0.99]; 0: plain Jacobi. 0.9 measured
  // fastest of 0.8, 0.9, 0.95 (docs/results.md).
  float chebyshev;
};

// Position-based fluids' solver settings (scene block "pbf"), [MM13] with the paper's defaults.
struct PbfConstants {
  // Constraint force mixing epsilon of lambda, in units of 1 / h^2: epsilon = relaxation / h^2. In the bulk of
  // a lattice with h = 1.95 d, sum |grad C|^2 is 1.5 / h^2 (tests/test_pbf_formulas.cpp), so 0.1 softens the
  // bulk's lambda by 6% and bounds a particle with almost no neighbours to |lambda| <= 10 |C| h^2.
  float relaxation;
  // Artificial pressure s_corr = -k (W(r) / W(dq))^n, [MM13] section 4: k = 0.1 (default 0 here: see
  // pbf_defaults), n = 4, dq = 0.1 h to 0.3 h.
  // dq = 0.2 h, the middle of the paper's range: a pair at dq gets -k, a neighbour at the rest spacing
  // (about h / 2) about 5% of it, so s_corr acts on pairs that come too close, not on the bulk at rest.
  float scorr_k;
  int32_t scorr_n;
  float scorr_dq;  // dq / h
  // 1: lambda sees max(C_i, 0), a one-sided constraint (as Bender et al.'s PositionBasedDynamics library):
  // particles at a free surface, whose C < 0 only because neighbours are missing, are then not pulled
  // together. 0: the paper's C_i. The free surface's pull makes a plain Jacobi iteration compress a resting
  // blob (tests/test_pbf_formulas.cpp).
  int32_t clamp_expansion;
  float xsph_c;             // XSPH viscosity c, [MM13] section 5
  float vorticity_epsilon;  // vorticity confinement strength [m/s] (a = eps N x omega), 0: off
  int32_t iterations;       // constraint iterations per step (the most, with a tolerance)
  float density_tolerance;  // stop early once the mean compression max(C, 0) is at most this; 0: always iterations
  // Weighted Jacobi: each iteration applies this share of Delta p, in (0, 1]. Poly6's density read against
  // Spiky's correction overshoots the short density waves (G(q) up to 2.8, docs/results.md "Why PBF rattles
  // at rest"); 0.7 brings those inside the stable band that the Chebyshev weights below can then widen.
  float jacobi_weight;
  // Chebyshev acceleration of the iterations ([Wan15], solvers/chebyshev.h): the estimate rho of the weighted
  // iteration's spectral radius, in [0, 0.99]; 0: plain (weighted) Jacobi.
  float chebyshev;
  // 1: Monaghan's artificial viscosity of the fluids (fluids.N.artificial_viscosity) acts under PBF as well,
  // beside XSPH: the damping WCSPH and DFSPH give the same scene (src/solvers/pbf.h, apply_viscosity). 0 (the
  // default): XSPH alone, as [MM13]; the laminar viscosity (sph.viscosity) acts either way.
  int32_t artificial_viscosity;
  // 1: once a step, after the first density, a coarse-grid projection of the compression (pbf_coarse.h), which
  // carries a correction across the whole fluid at once: a resting column at 4 ms and 4 iterations 0.04%
  // compressed instead of 2.5% (docs/results.md, "PBF's coarse grid"). 0 (the default): [MM13]'s iteration.
  int32_t coarse_grid;
  int32_t coarse_iterations;  // the most conjugate-gradient iterations of its solve (it stops at 1e-2 of |b|)
};

// [BK15]'s defaults: eta = 0.01% and eta_v = 0.1% (section 5), at least 2 density iterations (SPlisHSPlasH's
// minimum: one iteration cannot both apply and re-measure the warm start), at most 100.
constexpr DfsphConstants dfsph_defaults() { return DfsphConstants{1e-4f, 1e-3f, 2, 100, 1, 1, 1, 1.0f, 0.9f}; }

// The paper's defaults ([MM13] sections 3 to 5) with the one-sided constraint, 4 iterations without a
// tolerance (the dam-break target of issue 12), and s_corr off: the paper's k = 0.1 belongs to its two-sided
// constraint, whose free surface pulls particles into clumps that s_corr pushes apart. With the one-sided
// constraint nothing pulls, and s_corr only pushes the free surface outward a little every step; as
// v = Delta x / dt that is a speed growing as the step shrinks, and a resting column with k = 0.1 blew up
// within 0.015 s at dt = 0.25 ms (measured; tests/test_solvers.cpp keeps the default stable there).
constexpr PbfConstants pbf_defaults() { return PbfConstants{0.1f, 0.0f, 4, 0.2f, 1, 0.01f, 0.0f, 4, 0.0f, 0.7f, 0.85f, 0, 0, 50}; }

enum class Integrator : int32_t {
  ExplicitEuler,            // thesis eq. 2.29, kept to show where it fails
  SemiImplicitEuler,        // thesis eq. 2.30
  VelocityVerlet,           // thesis eq. 2.32
  ModifiedVelocityVerlet,   // Groot & Warren form (design.md section 3), the default
  Leapfrog,                 // drift-kick-drift (position Verlet) form
};

// Per-fluid constants (thesis 4.1.4 physical parameters plus derived ones).
struct FluidConstants {
  float rest_density;      // rho0 [kg/m^3]
  float mass;              // particle mass [kg], from guided creation
  float speed_of_sound;    // c0 [m/s]
  float tait_b;            // rho0 c0^2 / gamma, gamma = 7 (thesis eq. 2.15)
  float viscosity;         // mu [Pa s] for Mueller and Morris
  float artificial_alpha;  // alpha for Monaghan artificial viscosity
  float near_stiffness;    // k_near [m^2/s^2], P_near = k_near rho_near (thesis 3.1); 0 disables
  float cohesion;          // 8 sigma / (pi rho0^2 h^5 J4) [m/(kg s^2)], cohesion from sigma (calibration.h); 0 disables
  float csf_sigma;         // sigma / chi [N/m] of the continuum surface force (surface_tension_csf.h)
  // sigma_ab / chi [N/m] at the fluid's interface with the other fluid of an interface tension under the
  // continuum surface force (surface_tension_csf.h); 0: none
  float csf_interface_sigma;
  // cbrt(m / rho0) [m], a particle's side, which the continuum surface force's curvature offset reads
  // (surface_tension_csf.h); computed on the host, since cbrtf differs in its last bit between glibc and CUDA
  float particle_side;
  float adhesion;          // k_a [m/(kg s^2)], adhesion to boundary particles from the contact angle (cohesion_energy.h); 0: none
  // The contact angle theta under the continuum surface force (surface_tension_csf.h): csf_contact 1 where
  // the fluid has one, and cot theta, the shear of its images along the walls.
  int32_t csf_contact;
  float csf_contact_cot;
  float xsph;              // XSPH epsilon; 0 disables
  float lifetime;          // particles older than this are recycled [s]; 0 = never
  // Viscoelastic springs (springs.h, Clavet et al. 2005, thesis eq. 2.26); spring_stiffness 0: none.
  float spring_stiffness;  // k / m [1/s^2] of a spring of rest length d, from the shear modulus (springs.h, spring_law)
  float spring_exponent;   // p: a spring of rest length L has k (d / L)^p (springs.h, spring_law)
  float spring_yield;      // gamma: a spring deforms by up to gamma L before its rest length L yields
  float spring_plasticity; // alpha [1/s]: how fast a yielded rest length follows the deformation
};

// Whether the recycle phase removes particle of this age and fluid: lifetime exceeded or absorbed.
SPH_HD inline bool expired(const FluidConstants& f, float age) {
  return age >= kRemovedAge || (f.lifetime > 0.0f && age > f.lifetime);
}

enum class ShapeType : int32_t { Box, Plane, Sphere, Quadric };

// A boundary shape with its penalty response (thesis 3.5.1). Every shape defines a region particles must
// stay in: a box or sphere container keeps them inside, an obstacle keeps them outside, a plane keeps them
// on the side its normal points to, a quadric keeps them where p^T Q p >= 0 (seed 000, section 3.8).
struct Shape {
  ShapeType type;
  int32_t keep_inside;   // Box, Sphere: 1 = container (stay inside), 0 = obstacle (stay outside)
  int32_t open_top;      // Box container: no collision with the ceiling (thesis "direction control")
  int32_t energy_conserving;  // scale the reflected normal velocity by d / (|v| dt) (thesis 3.5.1)
  int32_t absorb;        // particles crossing the shape leave the simulation (an outflow, e.g. the jet's ground)
  float bounce;          // C_bounce in [0, 1]
  float slip;            // C_slip in [0, 1]
  Vec3 a;                // Box: min corner; Plane: a point; Sphere: centre
  Vec3 b;                // Box: max corner; Plane: unit normal (towards the fluid)
  float radius;          // Sphere
  float q[16];           // Quadric: row-major 4x4 symmetric matrix
  Vec3 reach_lo;         // Box obstacle: how far its solid reaches below a and above b through faces that lie
  Vec3 reach_hi;         // on a wall or another obstacle (obstacle_contacts.h); 0 = the box itself
};

// Neighbour-grid geometry (grid.h). The grid is over the particles: cells of h / 2 (reach 2) counted from
// `origin`, with no memory for empty space. The domain, origin + cell_size * (nx, ny, nz), only says where
// the fluid is expected: particles outside it are still found as neighbours, and are counted in the
// metrics and the run's summary (particles_outside_domain).
struct GridGeometry {
  Vec3 origin;
  float cell_size;     // h / reach [m]
  int32_t reach;       // kGridReach
  int32_t nx, ny, nz;  // the domain's extent in cells
};

// A user force field (thesis eq. 2.25, f_other): an acceleration towards (strength > 0) or away from
// (strength < 0) a point, fading linearly to zero at the radius. The demo drives it with the mouse.
struct UserForce {
  Vec3 point;
  float radius;
  float strength;  // m/s^2 at the point; 0 = off
};

struct SimConstants {
  KernelCoeffs kernel;
  DensityMethod density;
  EquationOfState eos;
  PressureForm pressure_form;
  ViscosityModel viscosity;
  Integrator integrator;
  int32_t clamp_negative_pressure;  // 1: P = max(P, 0) (no tensile pull at a free surface)
  int32_t mirror_walls;             // 1: neighbours near walls act also as their mirror images (mirror_walls.h)
  // Half the particle spacing [m]: under PBF the nearest a particle's centre comes to a mirror wall
  // (mirror_walls.h, keep_off_mirror_walls), where its image is one spacing away as in the lattice.
  float mirror_wall_distance;
  // 1: WCSPH with sph.kernel = cubic_spline: its density (summation and continuity), pressure, viscosity and
  // XSPH terms use the cubic spline in place of Poly6 and Spiky (kernels.h, density_kernel, gradient_dwdr).
  // 0 under DFSPH and PBF, whose own sums have their own kernels (dfsph.h, pbf.h).
  int32_t cubic_spline;
  // 1: DFSPH with sph.kernel = "poly6_spiky" given in the scene: its density, rate, alpha and pressure
  // accelerations take Poly6 for W and Spiky's grad W in place of the cubic spline (dfsph.h, dfsph_w). 0 else.
  int32_t dfsph_poly6_spiky;
  // The continuum surface force's limit on a particle's curvature, relative to its neighbours' mean
  // (surface_tension_csf.h, csf_limited_curvature): kCsfCurvatureSpread, or -1 for none (Scene's
  // csf_curvature_limit, which only tests turn off).
  float csf_curvature_spread;
  // 1: several fluids of different particle mass, density and pressure force in the number-density form of
  // Solenthaler & Pajarola 2008 (thesis 3.4.3, eqs. 3.5-3.6; density.h, forces.h). Set only where the
  // scene asks for it (sph.multiphase) and the fluids' masses differ: with equal masses the two forms are
  // the same, and single-fluid scenes keep their arithmetic bit for bit.
  int32_t number_density;
  int32_t near_enabled;             // any fluid with near_stiffness > 0
  int32_t surface_tension_enabled;  // any fluid with surface_tension > 0 under the cohesion model
  int32_t adhesion_enabled;         // any fluid with an adhesion to boundary particles (contact_angle)
  int32_t csf_contact_enabled;      // any fluid with a contact angle under the continuum surface force
  int32_t interface_cohesion_enabled;  // any cross_cohesion != 0 (an interface tension between two fluids)
  int32_t csf_enabled;              // any fluid with surface_tension > 0 or an interface tension under the continuum surface force
  // An interface tension between two fluids under the continuum surface force (surface_tension_csf.h): each
  // particle's force takes its share of the interface's tension.
  int32_t csf_interface_enabled;
  // 1: each fluid's net continuum surface force is removed at every step (surface_forces.h): a free drop (no
  // wall, obstacle, mesh or body, no interface tension; calibration.h, csf_free_drop) under WCSPH or DFSPH,
  // where the force on a closed surface sums to zero, but on the particles did not (its centre drifted).
  int32_t csf_momentum;
  int32_t xsph_enabled;             // any fluid with xsph > 0
  int32_t artificial_enabled;       // any fluid with artificial_alpha > 0: Monaghan's term on every pair
  float artificial_rate;            // lambda_max of that term [1/s] (viscous_limit.h)
  // DFSPH's sub-steps of its non-pressure forces and PBF's of its viscosity (viscous_limit.h, viscous_substeps;
  // under PBF the artificial term counts only with pbf.artificial_viscosity): the artificial and the
  // laminar viscosity's lambda_max summed [1/s]. No further margin: the artificial term's bound is already
  // above its real rate (0.73 of it measured), and with a margin of 0.5 (time_step.cfl_viscosity) the 16k dam
  // break at cfl_velocity 0.6 blew up at 0.064 s where with the bound alone it ran (docs/results.md).
  float substep_rate;
  Vec3 gravity;
  UserForce user_force;
  Solver solver;
  DfsphConstants dfsph;
  PbfConstants pbf;
  int32_t num_fluids;
  int32_t num_shapes;
  FluidConstants fluids[kMaxFluids];
  // The cohesion constant between particles of two different fluids a != b [m/(kg s^2)] (as
  // FluidConstants::cohesion; calibration.h, cross_cohesion), symmetric, from the scene's
  // interface_tension; 0: no cohesion between them. Negative: they repel (an interface tension above
  // sigma_a + sigma_b).
  float cross_cohesion[kMaxFluids][kMaxFluids];
  Shape shapes[kMaxShapes];
  GridGeometry grid;
};

// Whether the run's summed density uses the cubic spline: DFSPH unless the scene asks for Poly6 with Spiky
// ([BK15], dfsph.h), WCSPH where sph.kernel = cubic_spline; else Poly6. The interface tension's colours take the same kernel, and the mass and
// the boundary particles' volumes are calibrated with it (lattice_density_factor), so that the start's lattice
// reads rho0. (Until 2026-12-02 DFSPH's masses took Poly6's lattice sum: its lattice started 0.78% below rho0
// and every resting DFSPH column first fell by that, at up to 0.15 m/s; docs/results.md, "DFSPH's mass from
// the cubic spline".)
SPH_HD inline bool density_cubic_spline(const SimConstants& c) {
  return (c.solver == Solver::Dfsph && c.dfsph_poly6_spiky == 0) || c.cubic_spline != 0;
}

}  // namespace sph
