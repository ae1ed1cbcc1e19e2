// Hydrostatic tank: a resting column keeps its density near rho0 and its pressure follows
// p(y) = rho0 g (H - y), i.e. dp/dy = -rho0 g.
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "common/metrics.h"
#include "physics_helpers.h"

using namespace sph_test;

namespace {

// One look at the column: interior density error, least-squares pressure slope and mean vertical
// acceleration (interior: at least h from every wall and from the free surface, where the summation
// density has its full neighbourhood from particles alone), bottom-layer pressure and height.
struct ColumnSample {
  double err_mean = 0.0, err_max = 0.0, slope = 0.0, acc_y = 0.0, p_bottom = 0.0, H = 0.0, v_max = 0.0;
  long interior = 0;
};

ColumnSample sample_column(sph::Simulation& sim) {
  const sph::ParticleState& ps = sim.particles();
  const double rho0 = 1000.0, h = sim.setup().h, d = sim.setup().spacing, width = 0.05;
  const sph::Metrics m = sph::measure(sim.setup().constants, ps);
  ColumnSample out;
  out.H = m.top_y + 0.5 * d;  // free surface: the top layer's centres lie half a spacing below
  out.v_max = m.v_max;
  double sy = 0.0, sp = 0.0, syy = 0.0, syp = 0.0;
  long n_bottom = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const sph::Vec3 x = ps.pos[i];
    if (x.y < d) {
      out.p_bottom += ps.pressure[i];
      ++n_bottom;
    }
    if (x.x < h || x.x > width - h || x.z < h || x.z > width - h || x.y < h || x.y > out.H - h) continue;
    const double err = std::fabs(ps.density[i] - rho0) / rho0;
    out.err_mean += err;
    out.err_max = std::max(out.err_max, err);
    sy += x.y;
    sp += ps.pressure[i];
    syy += double(x.y) * x.y;
    syp += double(x.y) * ps.pressure[i];
    out.acc_y += ps.acc[i].y;  // total acceleration: pressure, viscosity and gravity
    ++out.interior;
  }
  const double n = double(out.interior);
  if (n > 0) {
    out.slope = (n * syp - sy * sp) / (n * syy - sy * sy);
    out.err_mean /= n;
    out.acc_y /= n;
  }
  if (n_bottom > 0) out.p_bottom /= double(n_bottom);
  return out;
}

}  // namespace

TEST_CASE("hydrostatic column: density error and pressure profile", "[hydrostatic]") {
  // The tank has mirror walls, which return the energy of the column's first acoustic mode (period
  // 4 H / c0 = 27 ms) instead of absorbing it at the floor as penalty walls do; artificial viscosity damps
  // it slowly, and after 1 s it still rings with about 50 micrometres of amplitude. One snapshot would
  // catch a random phase of it (the slope then reads up to 25% off), so the figures are averages over the
  // last 0.1 s, about four periods, sampled every millisecond.
  sph::Scene scene = scene_file("hydrostatic_tank.json");
  const double settle = 0.9, window = 0.1;
  sph::Simulation sim(scene, cpu_factory(), settle + window);
  while (sim.time() < settle) sim.advance();
  ColumnSample mean;
  int samples = 0;
  double next = sim.time();
  while (sim.time() < settle + window) {
    sim.advance();
    if (sim.time() < next) continue;
    next += 1e-3;
    const ColumnSample c = sample_column(sim);
    REQUIRE(c.interior > 100);
    mean.err_mean += c.err_mean;
    mean.err_max = std::max(mean.err_max, c.err_max);
    mean.slope += c.slope;
    mean.acc_y += c.acc_y;
    mean.p_bottom += c.p_bottom;
    mean.H += c.H;
    mean.v_max = std::max(mean.v_max, c.v_max);
    ++samples;
  }
  REQUIRE(samples > 50);
  mean.err_mean /= samples;
  mean.slope /= samples;
  mean.acc_y /= samples;
  mean.p_bottom /= samples;
  mean.H /= samples;

  const double rho0 = 1000.0, g = 9.81, d = sim.setup().spacing, H0 = 0.1, H = mean.H;
  INFO(samples << " samples over the last " << window << " s; H " << H << " m (initial " << H0 << "), largest v_max "
                << mean.v_max << " m/s");
  INFO("interior density error: mean " << mean.err_mean << ", max " << mean.err_max);
  INFO("interior dp/dy " << mean.slope << " Pa/m against -rho0 g = " << -rho0 * g);
  INFO("interior mean vertical acceleration " << mean.acc_y << " m/s^2");
  INFO("bottom-layer pressure " << mean.p_bottom << " Pa against rho0 g (H - d/2) = " << rho0 * g * (H - 0.5 * d));

  // At rest: what moves is the slow residual ringing only.
  CHECK(mean.v_max < 0.05 * std::sqrt(2.0 * g * H0));
  // Density within 1% of rho0 in the interior (the issue 5 target for Tait with c0 >= 10 v_max).
  CHECK(mean.err_mean < 0.01);
  CHECK(mean.err_max < 0.02);
  // Equilibrium: on average the SPH pressure force carries the weight of the interior particles.
  CHECK(std::fabs(mean.acc_y) < 0.02 * g);
  // The pressure that does so follows rho0 g (H - y) up to the SPH gradient's consistency error: on the
  // initial lattice (h = 1.97 d) the Spiky gradient sum recovers 95.3% of a linear field's gradient
  // (sum_b V_b y_ab dW/dy_ab = -0.953), so the pressure slope must be about 5% steeper than rho0 g;
  // particle disorder after settling adds more. Bound: 15%.
  CHECK(mean.slope < -rho0 * g);
  CHECK(mean.slope == Approx(-rho0 * g).epsilon(0.15));
  // Mirror walls (tests/test_mirror_walls.cpp): the column keeps its height within a spacing, and the
  // bottom layer carries the whole column, rho0 g (H - d/2). Its pressure is the slope integrated over
  // the column, so it carries the same consistency error and the same bound (measured: 10.4% high).
  CHECK(std::fabs(H - H0) < d);
  CHECK(mean.p_bottom > rho0 * g * (H - 0.5 * d));
  CHECK(mean.p_bottom == Approx(rho0 * g * (H - 0.5 * d)).epsilon(0.15));
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
