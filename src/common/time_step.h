// Time step choice (thesis 2.3.5 plus the usual WCSPH limits, and the viscous limit of viscous_limit.h),
// clamped to [min, max].
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene.h"
#include "viscous_limit.h"

namespace sph {

enum class StepLimit { Fixed, Velocity, Acceleration, Sound, Viscosity, Minimum, Maximum };

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

}  // namespace sph
