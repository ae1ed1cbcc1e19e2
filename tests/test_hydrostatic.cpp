// Hydrostatic tank: a resting column keeps its density near rho0 and its pressure follows
// p(y) = rho0 g (H - y), i.e. dp/dy = -rho0 g.
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "common/metrics.h"
#include "physics_helpers.h"

using namespace sph_test;

TEST_CASE("hydrostatic column: density error and pressure profile", "[hydrostatic]") {
  sph::Scene scene = scene_file("hydrostatic_tank.json");
  const double settle = 1.0;
  sph::Simulation sim(scene, cpu_factory(), settle);
  while (sim.time() < settle) sim.advance();

  const sph::ParticleState& ps = sim.particles();
  const sph::SimConstants& c = sim.setup().constants;
  const double rho0 = 1000.0, g = 9.81, h = sim.setup().h, d = sim.setup().spacing;
  const sph::Metrics m = sph::measure(c, ps);
  const double H = m.top_y + 0.5 * d;  // free surface: the top layer's centres lie half a spacing below
  const double width = 0.05, H0 = 0.1;

  // Interior: at least h from every wall and from the free surface, where the summation density has its
  // full neighbourhood from particles alone. Least-squares fit p = p0 + s y there.
  double err_sum = 0.0, err_max = 0.0, sy = 0.0, sp = 0.0, syy = 0.0, syp = 0.0, acc_y = 0.0;
  long n = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const sph::Vec3 x = ps.pos[i];
    if (x.x < h || x.x > width - h || x.z < h || x.z > width - h || x.y < h || x.y > H - h) continue;
    const double err = std::fabs(ps.density[i] - rho0) / rho0;
    err_sum += err;
    err_max = std::max(err_max, err);
    sy += x.y;
    sp += ps.pressure[i];
    syy += double(x.y) * x.y;
    syp += double(x.y) * ps.pressure[i];
    acc_y += ps.acc[i].y;  // total acceleration: pressure, viscosity and gravity
    ++n;
  }
  REQUIRE(n > 100);
  const double slope = (n * syp - sy * sp) / (n * syy - sy * sy);
  const double err_mean = err_sum / n;
  INFO("interior particles " << n << ", H " << H << " m (initial " << H0 << "), v_max " << m.v_max << " m/s");
  INFO("interior density error: mean " << err_mean << ", max " << err_max);
  INFO("interior dp/dy " << slope << " Pa/m against -rho0 g = " << -rho0 * g);
  INFO("interior mean vertical acceleration " << acc_y / n << " m/s^2");

  // At rest: what moves is slow residual sloshing only.
  CHECK(m.v_max < 0.05 * std::sqrt(2.0 * g * H0));
  // Density within 1% of rho0 in the interior (the issue 5 target for Tait with c0 >= 10 v_max).
  CHECK(err_mean < 0.01);
  CHECK(err_max < 0.02);
  // Equilibrium: the SPH pressure force carries the weight of the interior particles.
  CHECK(std::fabs(acc_y / n) < 0.02 * g);
  // The pressure that does so follows rho0 g (H - y) up to the SPH gradient's consistency error: on the
  // initial lattice (h = 1.97 d) the Spiky gradient sum recovers 95.3% of a linear field's gradient
  // (sum_b V_b y_ab dW/dy_ab = -0.953), so the pressure slope must be about 5% steeper than rho0 g;
  // particle disorder after settling adds more (measured: 10.6% steeper). Bound: 15%.
  CHECK(slope < -rho0 * g);
  CHECK(slope == Approx(-rho0 * g).epsilon(0.15));
  // The tank has mirror walls (tests/test_mirror_walls.cpp): the column keeps its height within a
  // spacing, and the bottom layer carries the whole column, rho0 g (H - d/2), within the gradient's
  // consistency error.
  double p_bottom = 0.0;
  long n_bottom = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.pos[i].y < d) {
      p_bottom += ps.pressure[i];
      ++n_bottom;
    }
  REQUIRE(n_bottom > 0);
  p_bottom /= double(n_bottom);
  INFO("bottom-layer pressure " << p_bottom << " Pa against rho0 g (H - d/2) = " << rho0 * g * (H - 0.5 * d));
  CHECK(std::fabs(H - H0) < d);
  CHECK(p_bottom == Approx(rho0 * g * (H - 0.5 * d)).epsilon(0.10));
}

TEST_CASE("hydrostatic column on penalty walls settles low", "[hydrostatic]") {
  // Penalty walls alone (thesis 3.5.1) leave wall particles with too few neighbours, so they pack closer
  // and the column settles lower: 29% at 10 particles across, 17% at 20 (measured), converging with
  // resolution. Guard the size of that known artefact at this resolution.
  sph::Scene scene = scene_file("hydrostatic_tank.json", {"sph.walls=penalty"});
  sph::Simulation sim(scene, cpu_factory(), 1.0);
  while (sim.time() < 1.0) sim.advance();
  const double d = sim.setup().spacing, H0 = 0.1;
  const double H = sph::measure(sim.setup().constants, sim.particles()).top_y + 0.5 * d;
  INFO("height " << H << " m (initial " << H0 << ")");
  CHECK(H > 0.65 * H0);
  CHECK(H < 0.9 * H0);
}
