// Relaxation phase (thesis 4.1.6): a lattice that is not at rest density is relaxed, without gravity and
// with a large viscosity, until it is slow and in balance; the run then starts from it at rest.
#include <catch2/catch.hpp>

#include "common/metrics.h"
#include "physics_helpers.h"

using namespace sph_test;

TEST_CASE("relaxation brings a lattice off rest density into balance before time starts", "[relaxation]") {
  // The thesis's mass rule (m = V rho0 / N) leaves the lattice off rest density, so it is not in balance.
  const std::vector<std::string> thesis_mass{"resolution.mass=volume", "resolution.particles_across=10"};
  std::vector<std::string> relaxed_overrides = thesis_mass;
  relaxed_overrides.push_back("relaxation.enabled=true");

  sph::Simulation plain(scene_file("drop_zero_g.json", thesis_mass), cpu_factory(), 1.0);
  sph::Simulation relaxed(scene_file("drop_zero_g.json", relaxed_overrides), cpu_factory(), 1.0);
  const sph::RelaxationReport& report = relaxed.relaxation();
  INFO("relaxation: " << report.steps << " steps, final speed measure " << report.final_speed << " m/s, threshold "
                      << report.threshold);
  REQUIRE(report.ran);
  CHECK(report.converged);
  CHECK(report.steps > 3);  // it had work to do
  CHECK(relaxed.time() == 0.0);

  // The run starts at rest, and the forces of the relaxed state are far smaller.
  const sph::Metrics m = sph::measure(relaxed.setup().constants, relaxed.particles());
  CHECK(m.kinetic_energy == 0.0);
  const float a_plain = plain.backend().diagnose().max_accel;
  const float a_relaxed = relaxed.backend().diagnose().max_accel;
  INFO("largest acceleration at t = 0: lattice " << a_plain << " m/s^2, relaxed " << a_relaxed << " m/s^2");
  CHECK(a_relaxed < 0.1f * a_plain);
}

TEST_CASE("relaxation that cannot converge in max_steps says so", "[relaxation]") {
  sph::Simulation sim(scene_file("drop_zero_g.json", {"resolution.mass=volume", "resolution.particles_across=8",
                                                      "relaxation.enabled=true", "relaxation.max_steps=5"}),
                      cpu_factory(), 1.0);
  CHECK(sim.relaxation().steps == 5);
  CHECK_FALSE(sim.relaxation().converged);
}
