// Tensile instability (thesis 3.1, 5.3.1): the zero-gravity drop keeps negative pressures, so particles
// are pulled together. Without near pressure they collapse into clusters (the method's failure, tested
// where it fails); with near pressure (double density relaxation) they keep their distance.
#include <catch2/catch.hpp>

#include "physics_helpers.h"

using namespace sph_test;

namespace {
struct DropResult {
  double min_distance_over_spacing;
  double clustered;  // fraction of particles with a neighbour closer than 0.5 spacing
};

DropResult run_drop(double near_stiffness, double seconds) {
  sph::Scene scene = scene_file("drop_zero_g.json", {"fluids.0.near_stiffness=" + std::to_string(near_stiffness)});
  sph::Simulation sim(scene, cpu_factory(), seconds);
  while (sim.time() < seconds) sim.advance();
  const double d = sim.setup().spacing;
  return {min_pair_distance(sim.particles()) / d, clustered_fraction(sim.particles(), 0.5 * d)};
}
}  // namespace

TEST_CASE("zero-g drop: near pressure prevents clustering, its absence shows it", "[tensile]") {
  const double seconds = 0.5;
  const DropResult with_near = run_drop(0.5, seconds);
  const DropResult without = run_drop(0.0, seconds);
  WARN("with near pressure: min distance " << with_near.min_distance_over_spacing << " d, clustered "
       << with_near.clustered);
  WARN("without near pressure: min distance " << without.min_distance_over_spacing << " d, clustered "
       << without.clustered);
  CHECK(with_near.min_distance_over_spacing > 0.5);
  CHECK(with_near.clustered == 0.0);
  CHECK(without.min_distance_over_spacing < 0.3);
  CHECK(without.clustered > 0.1);
}
