// Every model of the solver on the device back end against the serial reference (issue 11, items 5 and
// 10): both density methods (continuity with dt > 0), both equations of state, both pressure forms, all
// four viscosity models, XSPH, surface tension, near pressure, all five integrators, mirror walls and both
// kernel pairs.
// Each case runs 200 steps side by side (every field compared after every step), then one step phase by
// phase from where the run ended; and each model it names must change that step on the reference when it
// is switched off, so a case cannot pass without exercising its model.
#include <catch2/catch.hpp>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "device_compare.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

// A model of the case, and how to switch it off (or to another choice) in the constants.
struct Model {
  std::string name;
  std::function<void(sph::SimConstants&)> switch_off;
};

void no_artificial_viscosity(sph::SimConstants& c) {
  c.artificial_enabled = 0;
  for (auto& f : c.fluids) f.artificial_alpha = 0.0f;
}

// 200 steps side by side, one step phase by phase, then each model switched off in turn must change the
// reference's step. Returns the reference's state after each phase of that step.
std::vector<sph::ParticleState> check_case(const sph::Scene& scene, const std::vector<Model>& models, int steps = 200) {
  std::unique_ptr<sph::Simulation> ref;
  compare_runs(scene, steps, &ref);
  const sph::SimConstants& c = ref->setup().constants;
  const sph::ParticleState start = ref->particles();
  const float dt = float(ref->last_dt());
  REQUIRE(dt > 0.0f);
  const sph::SpringNetwork springs = ref->backend().download_springs();  // as the run left them
  const std::vector<sph::ParticleState> phases = compare_phases(c, start, dt, sph::BoundaryParticles{}, springs);
  const sph::ParticleState& stepped = phases.back();
  for (const Model& m : models) {
    sph::SimConstants off = c;
    m.switch_off(off);
    INFO("switching off " << m.name << " must change the step");
    CHECK(compare_states(stepped, reference_step(off, start, dt, springs), true) != "");
  }
  return phases;
}

std::size_t phase_slot(sph::Phase p) { return std::size_t(p); }  // kStepPhases lists the phases in enum order

}  // namespace

TEST_CASE("device models: summation, Tait, Monaghan's form, artificial viscosity, modified Verlet", "[device][models]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=10"});
  REQUIRE(scene.density == sph::DensityMethod::Summation);
  REQUIRE(scene.eos == sph::EquationOfState::Tait);
  REQUIRE(scene.pressure_form == sph::PressureForm::MonaghanSymmetric);
  REQUIRE(scene.viscosity == sph::ViscosityModel::Artificial);
  REQUIRE(scene.integrator == sph::Integrator::ModifiedVelocityVerlet);
  check_case(scene, {{"artificial viscosity", no_artificial_viscosity},
                     {"Tait (to ideal)", [](sph::SimConstants& c) { c.eos = sph::EquationOfState::Ideal; }},
                     {"Monaghan's form (to Mueller's)", [](sph::SimConstants& c) { c.pressure_form = sph::PressureForm::Mueller; }},
                     {"modified Verlet (to velocity Verlet)", [](sph::SimConstants& c) { c.integrator = sph::Integrator::VelocityVerlet; }}});
}

TEST_CASE("device models: continuity density, ideal gas, Mueller's form, Morris viscosity, explicit Euler", "[device][models]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=10", "sph.density=continuity",
                                                         "sph.equation_of_state=ideal", "sph.pressure_force=mueller",
                                                         "sph.viscosity=morris", "integrator=explicit_euler"});
  const auto phases = check_case(scene, {{"continuity (to summation)", [](sph::SimConstants& c) { c.density = sph::DensityMethod::Summation; }},
                                         {"ideal gas (to Tait)", [](sph::SimConstants& c) { c.eos = sph::EquationOfState::Tait; }},
                                         {"Mueller's form (to Monaghan's)", [](sph::SimConstants& c) { c.pressure_form = sph::PressureForm::MonaghanSymmetric; }},
                                         {"Morris viscosity", [](sph::SimConstants& c) { c.viscosity = sph::ViscosityModel::None; }},
                                         {"explicit Euler (to semi-implicit)", [](sph::SimConstants& c) { c.integrator = sph::Integrator::SemiImplicitEuler; }}});
  // Continuity integrates the density with dt > 0: the density phase must change every density it sees
  // move (the divergence is non-zero somewhere in a collapsing column).
  const sph::ParticleState& before = phases[phase_slot(sph::Phase::BuildGrid)];
  const sph::ParticleState& after = phases[phase_slot(sph::Phase::Density)];
  std::size_t changed = 0;
  for (std::size_t i = 0; i < after.size(); ++i) changed += before.density[i] != after.density[i] ? 1 : 0;
  CHECK(changed > after.size() / 2);
}

TEST_CASE("device models: Mueller viscosity, semi-implicit Euler, mirror walls with no slip", "[device][models]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=10", "sph.viscosity=mueller",
                                                         "integrator=semi_implicit_euler", "sph.walls=mirror", "boundaries.0.slip=0"});
  REQUIRE(scene.mirror_walls);
  check_case(scene, {{"Mueller viscosity", [](sph::SimConstants& c) { c.viscosity = sph::ViscosityModel::None; }},
                     {"mirror walls", [](sph::SimConstants& c) { c.mirror_walls = 0; }},
                     {"semi-implicit Euler (to leapfrog)", [](sph::SimConstants& c) { c.integrator = sph::Integrator::Leapfrog; }}});
}

TEST_CASE("device models: no laminar viscosity, velocity Verlet", "[device][models]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=10", "sph.viscosity=none", "integrator=velocity_verlet"});
  REQUIRE(scene.viscosity == sph::ViscosityModel::None);
  check_case(scene, {{"velocity Verlet (to modified Verlet)", [](sph::SimConstants& c) { c.integrator = sph::Integrator::ModifiedVelocityVerlet; }},
                     {"artificial viscosity (the only viscosity here)", no_artificial_viscosity}});
}

TEST_CASE("device models: leapfrog with continuity density and Tait", "[device][models]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=10", "integrator=leapfrog", "sph.density=continuity"});
  check_case(scene, {{"leapfrog (to modified Verlet)", [](sph::SimConstants& c) { c.integrator = sph::Integrator::ModifiedVelocityVerlet; }},
                     {"continuity (to summation)", [](sph::SimConstants& c) { c.density = sph::DensityMethod::Summation; }}});
}

TEST_CASE("device models: near pressure, surface tension, XSPH and negative pressure on a free drop", "[device][models]") {
  const sph::Scene scene = scene_file("drop_zero_g.json", {"resolution.particles_across=9", "fluids.0.surface_tension=0.07",
                                                           "fluids.0.xsph=0.1"});
  REQUIRE(!scene.clamp_negative_pressure);
  const auto phases = check_case(scene, {{"kept negative pressure (to clamped)", [](sph::SimConstants& c) { c.clamp_negative_pressure = 1; }},
                                         {"near pressure", [](sph::SimConstants& c) {
                                            c.near_enabled = 0;
                                            for (auto& f : c.fluids) f.near_stiffness = 0.0f;
                                          }},
                                         {"surface tension", [](sph::SimConstants& c) {
                                            c.surface_tension_enabled = 0;
                                            for (auto& f : c.fluids) f.cohesion = 0.0f;
                                          }},
                                         {"XSPH", [](sph::SimConstants& c) {
                                            c.xsph_enabled = 0;
                                            for (auto& f : c.fluids) f.xsph = 0.0f;
                                          }}});
  // The fields these models write are non-zero: near density and near pressure after the pressure phase,
  // the XSPH correction after the forces phase.
  const sph::ParticleState& pressured = phases[phase_slot(sph::Phase::Pressure)];
  const sph::ParticleState& forced = phases[phase_slot(sph::Phase::Forces)];
  float near_rho = 0.0f, near_p = 0.0f, xsph = 0.0f;
  for (std::size_t i = 0; i < pressured.size(); ++i) {
    near_rho = std::max(near_rho, pressured.near_density[i]);
    near_p = std::max(near_p, std::fabs(pressured.near_pressure[i]));
  }
  for (const sph::Vec3& dv : forced.xsph_dv) xsph = std::max(xsph, sph::length(dv));
  INFO("largest near density " << near_rho << ", near pressure " << near_p << ", XSPH correction " << xsph);
  CHECK(near_rho > 0.0f);
  CHECK(near_p > 0.0f);
  CHECK(xsph > 0.0f);
}

TEST_CASE("device models: two fluids of density ratio 10 in the number-density form, with surface tension", "[device][models][multiphase]") {
  // Water under a fluid ten times lighter (issue 15), both with cohesion; coarse, so 200 steps stay short.
  const sph::Scene scene = scene_file("two_layers.json", {"resolution.particles_across=5", "fluids.0.surface_tension=0.5",
                                                          "fluids.1.surface_tension=0.05"});
  check_case(scene, {{"number density (to mass density)", [](sph::SimConstants& c) { c.number_density = 0; }},
                     {"surface tension", [](sph::SimConstants& c) {
                        c.surface_tension_enabled = 0;
                        for (auto& f : c.fluids) f.cohesion = 0.0f;
                      }}});
}

TEST_CASE("device models: viscoelastic springs beside plain water", "[device][models][viscoelastic]") {
  // The jelly and the water cubes of scenes/viscoelastic.json, coarse; the springs carry stretch by then.
  const sph::Scene scene = scene_file("viscoelastic.json", {"resolution.particles_across=6", "fluids.0.spring_plasticity=2",
                                                            "fluids.0.spring_yield=0.02"});
  check_case(scene, {{"springs", [](sph::SimConstants& c) {
                        for (auto& f : c.fluids) f.spring_stiffness = 0.0f;
                      }}});
}

TEST_CASE("device models: viscoelastic springs under DFSPH", "[device][models][viscoelastic][dfsph]") {
  // The springs in DFSPH's non-pressure forces (solvers/dfsph.h), plasticity once per step.
  const sph::Scene scene = scene_file("viscoelastic.json", {"resolution.particles_across=6", "fluids.0.spring_plasticity=2",
                                                            "fluids.0.spring_yield=0.02", "solver=dfsph"});
  check_case(scene, {{"springs", [](sph::SimConstants& c) {
                        for (auto& f : c.fluids) f.spring_stiffness = 0.0f;
                      }}});
}

TEST_CASE("device models: viscoelastic springs under PBF", "[device][models][viscoelastic][pbf]") {
  // The springs as PBF's external force at the step's start (solvers/pbf.h, SpringAccelerationFn).
  const sph::Scene scene = scene_file("viscoelastic.json", {"resolution.particles_across=6", "fluids.0.spring_plasticity=2",
                                                            "fluids.0.spring_yield=0.02", "solver=pbf"});
  check_case(scene, {{"springs", [](sph::SimConstants& c) {
                        for (auto& f : c.fluids) f.spring_stiffness = 0.0f;
                      }}});
}

TEST_CASE("device models: WCSPH with the cubic spline kernel, summed and continuity density", "[device][models]") {
  // sph.kernel = cubic_spline (kernels.h, density_kernel, gradient_dwdr): density, pressure, both viscosities,
  // XSPH, against mirror walls' ghosts and against boundary particles.
  for (const auto& [density, walls] : std::vector<std::pair<std::string, std::string>>{{"summation", "mirror"}, {"continuity", "particles"}}) {
    INFO("sph.density = " << density << ", sph.walls = " << walls);
    const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=10", "sph.kernel=cubic_spline",
                                                           "sph.density=" + density, "sph.walls=" + walls, "sph.viscosity=morris",
                                                           "fluids.0.xsph=0.1"});
    check_case(scene, {{"the cubic spline (to Poly6 and Spiky)", [](sph::SimConstants& c) { c.cubic_spline = 0; }},
                       {"XSPH", [](sph::SimConstants& c) {
                          c.xsph_enabled = 0;
                          for (auto& f : c.fluids) f.xsph = 0.0f;
                        }}});
  }
}

TEST_CASE("device models: the continuum surface force on a free drop", "[device][models][surface_tension]") {
  const sph::Scene scene = scene_file("drop_oscillation.json", {"resolution.particles_across=8", "solver=wcsph", "sph.surface_tension=csf"});
  const auto phases = check_case(scene, {{"continuum surface force", [](sph::SimConstants& c) { c.csf_enabled = 0; }}});
  float kappa = 0.0f;
  for (float k : phases[phase_slot(sph::Phase::Forces)].curvature) kappa = std::max(kappa, k);
  CHECK(kappa > 0.0f);
}

TEST_CASE("device models: contact angles under the continuum surface force (DFSPH)", "[device][models][surface_tension]") {
  // Issue 15: the images sheared along the walls (surface_tension_csf.h), a colour pass of their own.
  const sph::Scene scene = scene_file("contact_angle.json", {"resolution.particles_across=5"});
  check_case(scene,
             {{"contact angle", [](sph::SimConstants& c) {
                 c.csf_contact_enabled = 0;
                 for (auto& f : c.fluids) f.csf_contact = 0;
               }}},
             100);
}

TEST_CASE("device models: interface tension under the continuum surface force (DFSPH)", "[device][models][interface]") {
  // Issue 15: each particle's share of the interface's tension (surface_tension_csf.h, csf_interface_share), a
  // neighbour loop in the force pass; a drop within a drop, so a free surface and an interface both act.
  const sph::Scene scene = scene_file("compound_drop.json", {"resolution.spacing=0.01"});
  check_case(scene, {{"interface share", [](sph::SimConstants& c) { c.csf_interface_enabled = 0; }}}, 60);
}

TEST_CASE("device models: interface tension between two fluids", "[device][models][interface]") {
  // Issue 15: the cohesion between two fluids (forces.h, interface_cohesion), a loop of its own.
  const sph::Scene scene = scene_file("interface_drop.json", {"resolution.spacing=0.01", "sph.surface_tension=cohesion",
                                                              "solver=wcsph"});
  REQUIRE(!scene.interface_tensions.empty());
  check_case(scene, {{"interface tension", [](sph::SimConstants& c) { c.interface_cohesion_enabled = 0; }}}, 60);
}
