// Time step choice (thesis 2.3.5 plus the usual WCSPH limits, and the viscous limit of viscous_limit.h),
// clamped to [min, max].
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene.h"
#include "viscous_limit.h"

namespace sph {

enum class StepLimit { Fixed, Velocity, Acceleration, Sound, Viscosity, Springs, Minimum, Maximum };

// The incompressible solvers' step with springs: omega_max dt <= this fraction of the explicit bound 2
// (springs.h, spring_rate, the lattice's fastest frequency). Half, as the viscous limit's default
// cfl_viscosity: a strained network's bonds turn from the lattice's directions, and a particle's largest
// stiffness can grow up to 3 times the lattice's (all its bonds in one direction).
constexpr double kSpringStepFraction = 0.5;

// That limit [s] for springs of fastest angular frequency spring_rate [1/s] (> 0).
inline double spring_step_bound(double spring_rate) { return kSpringStepFraction * 2.0 / spring_rate; }

struct StepChoice {
  double dt;
  StepLimit limit;
};

// h: support radius [m]; c0: largest speed of sound [m/s]; viscous_rate: the fastest viscous rate lambda_max
// [1/s] (viscous_rate() in viscous_limit.h, 0 without viscosity); v_max [m/s] and a_max [m/s^2]: the
// largest speed and acceleration of the current state.
inline StepChoice choose_time_step(const TimeStepSpec& t, double h, double c0, double viscous_rate, double v_max,
                                   double a_max) {
  if (t.mode == TimeStepMode::Fixed) return {t.dt, StepLimit::Fixed};
  double dt = std::numeric_limits<double>::infinity();
  StepLimit limit = StepLimit::Maximum;
  auto take = [&](double candidate, StepLimit why) {
    if (candidate < dt) {
      dt = candidate;
      limit = why;
    }
  };
  if (v_max > 0.0) take(t.cfl_velocity * h / v_max, StepLimit::Velocity);          // dt <= C_v h / v_max
  if (a_max > 0.0) take(t.cfl_acceleration * std::sqrt(h / a_max), StepLimit::Acceleration);  // C_a sqrt(h/a)
  take(t.cfl_sound * h / (c0 + v_max), StepLimit::Sound);                           // C h / (c0 + v_max)
  // lambda_max dt <= C_nu * 2: a fraction C_nu of the explicit stability bound (viscous_limit.h).
  if (viscous_rate > 0.0) take(t.cfl_viscosity * kViscousStabilityBound / viscous_rate, StepLimit::Viscosity);
  if (dt > t.max) return {t.max, StepLimit::Maximum};
  if (dt < t.min) return {t.min, StepLimit::Minimum};
  return {dt, limit};
}

// The incompressible solvers' step (DFSPH, PBF): no sound-speed limit, since no equation of state carries
// pressure waves. Adaptive: the CFL condition dt <= C_v d / v_max of [BK15] (seed 000 eq. 3, C_v =
// cfl_velocity, 0.4 by default), d the particle spacing [m], the explicit viscous limit as for WCSPH (the
// viscosity is integrated explicitly) and, where a_max > 0 is given (DFSPH: the largest non-pressure
// acceleration), WCSPH's dt <= C_a sqrt(h / a_max), h the support [m]: without it the cohesion of a 4 cm drop
// (about 600 m/s^2 at its surface) compressed it by 47% in a 1.5 ms step, which the density solve could not
// undo (scenes/wetting.json; the 16k dam break's steps are unchanged by it), and with springs of fastest
// angular frequency at most spring_rate [1/s] (springs.h) dt <= kSpringStepFraction 2 / spring_rate; clamped
// to [min, max]. Fixed: time_step.dt.
inline StepChoice choose_incompressible_step(const TimeStepSpec& t, double spacing, double viscous_rate, double v_max,
                                            double h = 0.0, double a_max = 0.0, double spring_rate = 0.0) {
  if (t.mode == TimeStepMode::Fixed) return {t.dt, StepLimit::Fixed};
  double dt = t.max;
  StepLimit limit = StepLimit::Maximum;
  if (v_max > 0.0 && t.cfl_velocity * spacing / v_max < dt) {
    dt = t.cfl_velocity * spacing / v_max;
    limit = StepLimit::Velocity;
  }
  if (a_max > 0.0 && t.cfl_acceleration * std::sqrt(h / a_max) < dt) {
    dt = t.cfl_acceleration * std::sqrt(h / a_max);
    limit = StepLimit::Acceleration;
  }
  if (viscous_rate > 0.0 && t.cfl_viscosity * kViscousStabilityBound / viscous_rate < dt) {
    dt = t.cfl_viscosity * kViscousStabilityBound / viscous_rate;
    limit = StepLimit::Viscosity;
  }
  if (spring_rate > 0.0 && spring_step_bound(spring_rate) < dt) {
    dt = spring_step_bound(spring_rate);
    limit = StepLimit::Springs;
  }
  if (dt < t.min) return {t.min, StepLimit::Minimum};
  return {dt, limit};
}

// The longest step an incompressible solver is allowed [s]: one in which gravity alone moves a particle at
// rest by at most half a spacing, g dt^2 / 2 <= d / 2. Beyond it each step starts from a compression of more
// than half a spacing that the solve must undo, which a few iterations cannot. Infinite without gravity.
inline double incompressible_step_bound(double spacing, double gravity) {
  return gravity > 0.0 ? std::sqrt(spacing / gravity) : std::numeric_limits<double>::infinity();
}

}  // namespace sph
