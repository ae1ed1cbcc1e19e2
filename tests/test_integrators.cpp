// Integrators (src/common/integrate.h) on the thesis's oscillators (thesis 2.3.2 and 2.3.3), against the
// hand-derived update matrices, closed-form critical stiffnesses and energy behaviour of tests/integrator_theory.h
// (which says how each is derived and how it compares with the thesis's observations).
#include <catch2/catch.hpp>

#include "integrator_theory.h"

using namespace integrator_theory;

TEST_CASE("the hand-derived update matrices reproduce the library's integrators", "[integrators]") {
  for (Integrator m : kAllMethods) {
    for (bool damped : {false, true}) {
      for (double stiffness : {100.0, 1.0e4, 3.0e4}) {
        INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ", K = " << stiffness);
        const Oscillator o = oscillator(stiffness, damped);
        const Mat4 s4 = step_matrix4(m, o);
        for (int i = 0; i < 3; ++i) CHECK(s4[i][U] == 0.0);  // u is never carried from one step to the next
        const Mat3 s = step_matrix(m, o);
        // One step at a time along the library's own trajectory (comparing whole trajectories would also
        // measure how rounding differences grow, which for the defective critically damped Euler matrix is
        // ~ n sqrt(eps) / |lambda|).
        State lib = initial_state(o);
        for (int n = 0; n < 200; ++n) {
          const std::array<double, 3> prev = {lib.x, lib.v, lib.a};
          library_step(m, o, lib);
          std::array<double, 3> z{};
          for (int i = 0; i < 3; ++i) z[i] = s[i][0] * prev[0] + s[i][1] * prev[1] + s[i][2] * prev[2];
          // Relative to the state's size (velocity and acceleration scaled to lengths).
          const double scale = std::fabs(z[0]) + std::fabs(z[1]) * kDt + std::fabs(z[2]) * kDt * kDt;
          INFO("step " << n + 1 << ": library (x, v, a) = (" << lib.x << ", " << lib.v << ", " << lib.a
                        << "), matrix (" << z[0] << ", " << z[1] << ", " << z[2] << ")");
          REQUIRE(std::fabs(lib.x - z[0]) <= 1e-12 * scale);
          REQUIRE(std::fabs(lib.v - z[1]) * kDt <= 1e-12 * scale);
          REQUIRE(std::fabs(lib.a - z[2]) * kDt * kDt <= 1e-12 * scale);
        }
      }
    }
  }
}

TEST_CASE("critical stiffness of each method agrees with the closed forms", "[integrators]") {
  // Explicit Euler undamped: unstable at every stiffness, |lambda| = sqrt(1 + w^2).
  const Critical ee = critical_stiffness(Integrator::ExplicitEuler, false);
  CHECK(ee.unstable_everywhere);
  for (double stiffness : {1.0, 100.0, 1e4, 1e5, 1e6}) {
    const double w = omega_dt(stiffness);
    CHECK(theory_radius(Integrator::ExplicitEuler, stiffness, false) ==
          Approx(std::sqrt(1.0 + w * w)).epsilon(1e-7));
  }
  for (bool damped : {false, true}) {
    for (Integrator m : kAllMethods) {
      if (m == Integrator::ExplicitEuler && !damped) continue;
      const Critical c = critical_stiffness(m, damped);
      INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ": K_crit = " << c.stiffness << ", expected "
                      << expected_critical(m, damped));
      REQUIRE_FALSE(c.unstable_everywhere);
      CHECK_FALSE(c.restabilises);
      CHECK(std::fabs(c.stiffness - expected_critical(m, damped)) <= 1e-6 * expected_critical(m, damped));
    }
  }
  // Symplectic methods conserve phase-space area: det = 1 undamped, at any stable stiffness.
  for (Integrator m : kSymplectic) {
    for (double stiffness : {100.0, 1e4, 9e4}) {
      const Mat2 b = reduced_undamped(m, stiffness);
      CHECK(b[0][0] * b[1][1] - b[0][1] * b[1][0] == Approx(1.0).epsilon(1e-12));
    }
  }
}

TEST_CASE("library integrators are bounded at 0.8 K_crit and blow up at 1.25 K_crit", "[integrators]") {
  for (bool damped : {false, true}) {
    for (Integrator m : kAllMethods) {
      if (m == Integrator::ExplicitEuler && !damped) continue;  // no stable range (see the energy test)
      const double kc = critical_stiffness(m, damped).stiffness;
      {
        const double stiffness = 0.8 * kc;
        const RunResult r = run_library(m, stiffness, damped, 2000);
        INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ", K = 0.8 K_crit = " << stiffness
                        << ": max |x|/x0 = " << r.max_abs_x / kX0 << ", final |x|/x0 = " << r.final_abs_x / kX0);
        CHECK_FALSE(r.escaped);
        CHECK(r.max_abs_x < 5.0 * kX0);
        if (damped) {
          CHECK(r.final_abs_x < 1e-6 * kX0);  // spectral radius < 0.94: decays by many orders in 2000 steps
        } else {
          // Undamped: the trajectory stays on the conserved ellipse, so |x| is bounded by its half-axis.
          CHECK(r.max_abs_x <= energy_theory(m, stiffness).max_abs_x * (1.0 + 1e-9));
        }
      }
      {
        const double stiffness = 1.25 * kc;
        const double rho = theory_radius(m, stiffness, damped);
        const RunResult r = run_library(m, stiffness, damped, 2000);
        const double measured = measured_growth(r);
        INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ", K = 1.25 K_crit = " << stiffness
                        << ": escaped after " << r.steps << " steps, theory rho = " << rho
                        << ", measured growth per step = " << measured);
        CHECK(r.escaped);  // |x| > 1e12 x0
        REQUIRE(r.steps >= 20);  // enough steps for the two windows of measured_growth
        CHECK(std::fabs(measured - rho) < 0.02 * rho);
      }
    }
  }
}

TEST_CASE("undamped symplectic methods are stable exactly below omega dt = 2", "[integrators]") {
  for (Integrator m : kSymplectic) {
    INFO(name_of(m));
    for (double w : {0.5, 1.0, 1.9, 1.99}) {
      const double stiffness = stiffness_for(w);
      const RunResult r = run_library(m, stiffness, false, 5000);
      INFO("K = " << stiffness << ": max |x|/x0 = " << r.max_abs_x / kX0);
      CHECK_FALSE(r.escaped);
      CHECK(r.max_abs_x <= energy_theory(m, stiffness).max_abs_x * (1.0 + 1e-9));
    }
    for (double w : {2.01, 2.1, 3.0}) {
      const double stiffness = stiffness_for(w);
      const RunResult r = run_library(m, stiffness, false, 5000);
      INFO("K = " << stiffness << ": escaped after " << r.steps << " steps");
      CHECK(r.escaped);
    }
  }
}

TEST_CASE("damped oscillator: the thesis's observations at K = 15000 and 20000", "[integrators]") {
  const auto stable = [](Integrator m, double stiffness) {
    const RunResult r = run_library(m, stiffness, true, 2000);
    return !r.escaped && r.final_abs_x < 1e-6 * kX0;
  };
  const auto unstable = [](Integrator m, double stiffness) { return run_library(m, stiffness, true, 2000).escaped; };
  // Thesis: semi-implicit Euler and modified velocity Verlet stable at 15000, unstable at 20000.
  CHECK(stable(Integrator::SemiImplicitEuler, 15000.0));
  CHECK(unstable(Integrator::SemiImplicitEuler, 20000.0));
  CHECK(stable(Integrator::ModifiedVelocityVerlet, 15000.0));
  CHECK(unstable(Integrator::ModifiedVelocityVerlet, 20000.0));
  // Thesis: velocity Verlet unstable at 15000 (theory: K_crit 13397); stable at 10000 (all but Beeman).
  CHECK(unstable(Integrator::VelocityVerlet, 15000.0));
  CHECK(stable(Integrator::VelocityVerlet, 10000.0));
  // Thesis: explicit Euler the only one left stable at 20000.
  CHECK(stable(Integrator::ExplicitEuler, 20000.0));
  // Leapfrog (drift-kick-drift here) follows its own theory, K_crit 17157, not the thesis's observation.
  CHECK(stable(Integrator::Leapfrog, 15000.0));
  CHECK(unstable(Integrator::Leapfrog, 20000.0));
}

TEST_CASE("explicit Euler gains energy by a factor 1 + (omega dt)^2 every step at any stiffness", "[integrators]") {
  for (double stiffness : {1.0, 100.0, 1e4, 1e5}) {
    const double w = omega_dt(stiffness);
    const Oscillator o = oscillator(stiffness, false);
    State s = initial_state(o);
    double e = energy(s, stiffness);
    const double e0 = e;
    for (int n = 1; n <= 300; ++n) {
      library_step(Integrator::ExplicitEuler, o, s);
      const double e_new = energy(s, stiffness);
      INFO("K = " << stiffness << ", step " << n);
      REQUIRE(e_new / e == Approx(1.0 + w * w).epsilon(1e-9));
      e = e_new;
    }
    if (stiffness == 100.0) {
      // (1 + 0.004)^300 = 3.31: the energy grew by 231 % in 300 steps (thesis fig. 2.3: Euler diverges).
      const double expected = std::pow(1.0 + w * w, 300);
      INFO("K = 100: E_300 / E_0 = " << e / e0 << ", theory " << expected);
      CHECK(e / e0 == Approx(expected).epsilon(1e-9));
      CHECK(e / e0 > 3.3);
    }
  }
}

TEST_CASE("symplectic methods show no secular energy drift at K = 100", "[integrators]") {
  const double stiffness = 100.0;
  const double w = omega_dt(stiffness);  // 0.0632
  for (Integrator m : kSymplectic) {
    const Oscillator o = oscillator(stiffness, false);
    State s = initial_state(o);
    const double e0 = energy(s, stiffness);
    double first = 0.0, last = 0.0, all = 0.0;
    const int steps = 10000;
    for (int n = 0; n < steps; ++n) {
      library_step(m, o, s);
      const double dev = std::fabs(energy(s, stiffness) / e0 - 1.0);
      if (n < 1000) first = std::max(first, dev);
      if (n >= steps - 1000) last = std::max(last, dev);
      all = std::max(all, dev);
    }
    const EnergyTheory t = energy_theory(m, stiffness);
    INFO(name_of(m) << ": max relative energy deviation, first 1000 steps " << first << ", last 1000 " << last
                    << ", all " << all << "; theory " << t.max_relative_excursion << "; (omega dt)^2 = " << w * w);
    CHECK(last <= 1.5 * first);
    CHECK(all <= t.max_relative_excursion * (1.0 + 1e-6) + 1e-12);  // never leaves the conserved ellipse
    CHECK(first >= 0.9 * t.max_relative_excursion);                 // and the bound is a real one
    if (m == Integrator::SemiImplicitEuler) {
      // x and v are half a step apart, so E = M v^2/2 + K x^2/2 oscillates by O(omega dt), ~ w/2.
      CHECK(t.max_relative_excursion < w);
      CHECK(t.max_relative_excursion > 0.4 * w);
    } else {
      // Position and velocity at the same time: O((omega dt)^2), ~ w^2/4.
      CHECK(t.max_relative_excursion < 0.5 * w * w);
    }
  }
}
