// DFSPH and PBF (issue 12) on the device back end against the serial reference: whole runs and every phase
// of a step bit for bit (bitwise() on host; within a step on cuda, device_compare.h), including the
// iterative solves' iteration counts and errors, which decide how many loops a step runs.
#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <vector>

#include "common/viscous_limit.h"
#include "device_compare.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

// steps side by side, then one step phase by phase from the reference's state; the solvers' statistics of
// the last step must agree too.
void check_solver_case(const sph::Scene& scene, int steps) {
  std::unique_ptr<sph::Simulation> ref;
  compare_runs(scene, steps, &ref);
  const sph::SimConstants& c = ref->setup().constants;
  const float dt = float(ref->last_dt());
  REQUIRE(dt > 0.0f);
  compare_phases(c, ref->particles(), dt, ref->setup().boundary);

  // The statistics of one more step from the same state on both back ends.
  sph::CpuBackend cpu(c);
  std::unique_ptr<sph::Backend> dev = sph::backend_factory(device_name())(c);
  cpu.set_boundary(ref->setup().boundary);
  dev->set_boundary(ref->setup().boundary);
  cpu.upload(ref->particles());
  dev->upload(ref->particles());
  cpu.step(dt);
  dev->step(dt);
  const sph::SolverStats a = cpu.solver_stats(), b = dev->solver_stats();
  CHECK(a.density_iterations > 0);
  CHECK(a.density_iterations == b.density_iterations);
  CHECK(a.divergence_iterations == b.divergence_iterations);
  if (bitwise()) {
    CHECK(a.density_error == b.density_error);
    CHECK(a.divergence_error == b.divergence_error);
  }
}

}  // namespace

TEST_CASE("device solvers: DFSPH on the dam break with penalty walls", "[device][solvers]") {
  const sph::Scene scene = scene_file("dam_break.json", {"resolution.particles_across=10", "solver=dfsph"});
  REQUIRE(scene.solver == sph::Solver::Dfsph);
  check_solver_case(scene, 60);
}

TEST_CASE("device solvers: DFSPH with mirror walls and Morris viscosity, no warm start", "[device][solvers]") {
  const sph::Scene scene = scene_file("hydrostatic_tank.json", {"resolution.particles_across=8", "solver=dfsph",
                                                                "sph.viscosity=morris", "dfsph.warm_start=false"});
  REQUIRE(scene.mirror_walls);
  check_solver_case(scene, 40);
}

TEST_CASE("device solvers: DFSPH at 2.6 ms steps, its artificial viscosity sub-cycled, a warm start's share of 0.75",
          "[device][solvers]") {
  const sph::Scene scene = scene_file("hydrostatic_tank.json", {"resolution.particles_across=8", "solver=dfsph",
                                                                "time_step.mode=fixed", "time_step.dt=0.0026",
                                                                "dfsph.warm_start_fraction=0.75"});
  REQUIRE(sph::viscous_substeps(double(sph::create_setup(scene, 1.0).constants.substep_rate), 0.0026) > 1);
  check_solver_case(scene, 30);
}

TEST_CASE("device solvers: DFSPH with the continuum surface force on a free drop", "[device][solvers][surface_tension]") {
  const sph::Scene scene = scene_file("drop_oscillation.json", {"resolution.particles_across=8", "solver=dfsph",
                                                                "sph.surface_tension=csf"});
  check_solver_case(scene, 40);
}

TEST_CASE("device solvers: PBF at 4 ms with XSPH and vorticity confinement", "[device][solvers]") {
  const sph::Scene scene =
      scene_file("dam_break.json", {"resolution.particles_across=10", "solver=pbf", "time_step.mode=fixed",
                                    "time_step.dt=0.004", "pbf.vorticity_epsilon=0.01", "pbf.density_tolerance=0.001"});
  REQUIRE(scene.solver == sph::Solver::Pbf);
  check_solver_case(scene, 30);
}

TEST_CASE("device solvers: PBF with mirror walls", "[device][solvers]") {
  const sph::Scene scene = scene_file("hydrostatic_tank.json", {"resolution.particles_across=8", "solver=pbf",
                                                                "time_step.mode=fixed", "time_step.dt=0.004"});
  REQUIRE(scene.mirror_walls);
  check_solver_case(scene, 30);
}

TEST_CASE("device solvers: PBF with the coarse grid", "[device][solvers][coarse]") {
  // Its cell sums are fixed-point integers added atomically: the same bits in any order.
  check_solver_case(scene_file("hydrostatic_tank.json", {"resolution.particles_across=8", "solver=pbf", "time_step.mode=fixed",
                                                         "time_step.dt=0.004", "pbf.coarse_grid=true"}),
                    30);
  check_solver_case(scene_file("dam_break.json", {"resolution.particles_across=10", "solver=pbf", "time_step.mode=fixed",
                                                  "time_step.dt=0.004", "pbf.coarse_grid=true"}),
                    30);
}

TEST_CASE("device solvers: every solver with boundary particles", "[device][solvers][boundary_particles]") {
  // Issue 13: the boundary particles' sums (density, pressure and friction for WCSPH, alpha, rate and kappa for
  // DFSPH, lambda and Delta p for PBF) bit for bit. slip 0.5 so that the friction term runs.
  for (const char* solver : {"wcsph", "dfsph", "pbf"}) {
    const sph::Scene scene = scene_file("hydrostatic_tank.json", {"resolution.particles_across=8", std::string("solver=") + solver,
                                                                  "sph.walls=particles", "boundaries.0.slip=0.5"});
    REQUIRE(scene.boundary_particles);
    INFO("solver " << solver);
    if (scene.solver == sph::Solver::Wcsph) {
      std::unique_ptr<sph::Simulation> ref;
      compare_runs(scene, 40, &ref);
      compare_phases(ref->setup().constants, ref->particles(), float(ref->last_dt()), ref->setup().boundary);
    } else {
      check_solver_case(scene, 30);
    }
  }
}

TEST_CASE("device solvers: adhesion to boundary particles under WCSPH and DFSPH", "[device][solvers][adhesion]") {
  // Issue 15: Akinci's adhesion (forces.h, boundary_pair) beside the cohesion, two fluids of different contact
  // angles on a floor of boundary particles (scenes/wetting.json, the drops on the floor from the start).
  for (const char* solver : {"wcsph", "dfsph"}) {
    const sph::Scene scene = scene_file("wetting.json", {"resolution.particles_across=5", std::string("solver=") + solver,
                                                         "emitters.0.min=[0.03,0,0.03]", "emitters.1.min=[0.13,0,0.03]"});
    INFO("solver " << solver);
    std::unique_ptr<sph::Simulation> ref;
    compare_runs(scene, 40, &ref);
    REQUIRE(ref->setup().constants.adhesion_enabled == 1);
    compare_phases(ref->setup().constants, ref->particles(), float(ref->last_dt()), ref->setup().boundary);
  }
}

TEST_CASE("device solvers: a floating box (rigid body, two-way coupling) under WCSPH", "[device][solvers][bodies]") {
  // The body's force and torque come from the back end's deterministic sums, and its pose from the host:
  // every step's particles bit for bit (which needs the same pose on both).
  const sph::Scene scene = scene_file("floating_box.json", {"resolution.spacing=0.02", "bodies.0.min=[0.16,0.12,0.06]",
                                                             "bodies.0.max=[0.24,0.18,0.14]"});  // in the water from the start
  REQUIRE(scene.bodies.size() == 1);
  std::unique_ptr<sph::Simulation> ref;
  compare_runs(scene, 40, &ref);
  CHECK(ref->backend().bodies().at(0).force[1] != 0.0);  // the fluid acted on the body
}

TEST_CASE("device solvers: a floating box under DFSPH", "[device][solvers][bodies]") {
  // As above under DFSPH: the body's reaction sums what both pressure solves applied (src/solvers/dfsph.h).
  const sph::Scene scene = scene_file("floating_box.json", {"resolution.spacing=0.02", "bodies.0.min=[0.16,0.12,0.06]",
                                                             "bodies.0.max=[0.24,0.18,0.14]", "solver=dfsph"});
  std::unique_ptr<sph::Simulation> ref;
  compare_runs(scene, 20, &ref);
  CHECK(ref->backend().bodies().at(0).force[1] != 0.0);
}

TEST_CASE("device solvers: DFSPH with two fluids of density ratio 10 in the number-density form", "[device][solvers][multiphase]") {
  const sph::Scene scene = scene_file("two_layers.json", {"resolution.particles_across=5", "solver=dfsph"});
  REQUIRE(scene.number_density);
  check_solver_case(scene, 30);
}

TEST_CASE("device solvers: DFSPH with Poly6 and Spiky (sph.kernel given), mirror walls and boundary particles",
          "[device][solvers][multiphase]") {
  // The kernel choice of src/common/dfsph.h (dfsph_w, dfsph_grad_fac) in every DFSPH sum: two fluids between
  // mirror walls, then one fluid on boundary particles (their density, alpha, rate and hydrostatic part).
  const sph::Scene layers = scene_file("two_layers.json", {"resolution.particles_across=5", "solver=dfsph", "sph.kernel=poly6_spiky"});
  const sph::Scene tank = scene_file("hydrostatic_tank.json", {"resolution.particles_across=8", "solver=dfsph",
                                                               "sph.kernel=poly6_spiky", "sph.walls=particles"});
  for (const sph::Scene* scene : {&layers, &tank}) {
    INFO(scene->name);
    // The flag is set (the cpu reference depends on it: tests/test_multiphase.cpp, test_dfsph_formulas.cpp),
    // so host matching cpu bit for bit means host honours it too.
    REQUIRE(sph::create_setup(*scene, 0.1).constants.dfsph_poly6_spiky == 1);
    check_solver_case(*scene, 30);
  }
}

TEST_CASE("device solvers: PBF with two fluids of density ratio 10 in the number-density form", "[device][solvers][multiphase]") {
  // Mirror walls, the light fluid's corrections weighted by inverse mass (src/common/pbf.h); then with the
  // fluids' artificial viscosity (src/solvers/pbf.h, apply_viscosity: sub-cycled, 2 updates a step here).
  for (const char* artificial : {"false", "true"}) {
    const sph::Scene scene = scene_file("two_layers.json", {"resolution.particles_across=5", "solver=pbf",
                                                            std::string("pbf.artificial_viscosity=") + artificial});
    REQUIRE(scene.number_density);
    check_solver_case(scene, 30);
  }
}

TEST_CASE("device solvers: PBF with the continuum surface force on a free drop", "[device][solvers][surface_tension]") {
  // The force at the positions the solve ended at (src/solvers/pbf.h, SyncGridPositionsFn), XSPH at 0.1, and
  // the scene's laminar viscosity (Morris, 0.5 Pa s).
  const sph::Scene scene = scene_file("drop_oscillation.json", {"resolution.particles_across=6", "solver=pbf", "pbf.xsph=0.1"});
  REQUIRE(scene.surface_tension_model == sph::SurfaceTensionModel::Csf);
  check_solver_case(scene, 30);
}
