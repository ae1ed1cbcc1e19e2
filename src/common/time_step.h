// Time step choice (thesis 2.3.5 plus the usual WCSPH limits), clamped to [min, max].
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene.h"

namespace sph {

enum class StepLimit { Fixed, Velocity, Acceleration, Sound, Viscosity, Minimum, Maximum };

struct StepChoice {
  double dt;
  StepLimit limit;
};

inline StepChoice choose_time_step(const TimeStepSpec& t, double h, double c0, double nu, double v_max, double a_max) {
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
  if (nu > 0.0) take(t.cfl_viscosity * h * h / nu, StepLimit::Viscosity);           // 0.125 h^2 / nu
  if (dt > t.max) return {t.max, StepLimit::Maximum};
  if (dt < t.min) return {t.min, StepLimit::Minimum};
  return {dt, limit};
}

}  // namespace sph
