// Integrators (thesis 2.3), split around the force evaluation so every back end runs
//   predict -> (grid, density, pressure, forces) -> correct.
// predict moves the state to where the forces are evaluated and sets the velocity the forces see (vf);
// correct finishes the step with the new acceleration. Templates on the vector and scalar types so the
// oscillator tests (tests/test_integrators.cpp) run the very same update rules in double precision.
#pragma once

#include "params.h"
#include "particle_view.h"
#include "sph_hd.h"

namespace sph {

// a is the acceleration of the previous evaluation (the state's current acceleration).
template <class V, class S>
SPH_HD inline void integrate_predict(Integrator m, V& x, V& v, V& vf, const V& a, S dt) {
  switch (m) {
    case Integrator::ExplicitEuler:      // eq. 2.29: a = f(x_t, v_t), then x and v from the old values
    case Integrator::SemiImplicitEuler:  // eq. 2.30: a = f(x_t, v_t), kick then drift
      vf = v;
      break;
    case Integrator::VelocityVerlet:  // eq. 2.32: x' = x + v dt + a dt^2/2, a' = f(x', v_t)
      vf = v;
      x = x + v * dt + a * (S(0.5) * dt * dt);
      v = v + a * (S(0.5) * dt);  // first half of v' = v + (a + a') dt / 2
      break;
    case Integrator::ModifiedVelocityVerlet:  // Groot & Warren: v_half = v + a dt/2, x' = x + v_half dt,
      v = v + a * (S(0.5) * dt);              // a' = f(x', v_half): the forces see the half-step velocity
      x = x + v * dt;
      vf = v;
      break;
    case Integrator::Leapfrog:  // drift-kick-drift: x_half = x + v dt/2, a = f(x_half, v_t)
      vf = v;
      x = x + v * (S(0.5) * dt);
      break;
  }
}

// a is the acceleration just evaluated at the predicted state.
template <class V, class S>
SPH_HD inline void integrate_correct(Integrator m, V& x, V& v, const V& a, S dt) {
  switch (m) {
    case Integrator::ExplicitEuler:
      x = x + v * dt;
      v = v + a * dt;
      break;
    case Integrator::SemiImplicitEuler:
      v = v + a * dt;
      x = x + v * dt;
      break;
    case Integrator::VelocityVerlet:
    case Integrator::ModifiedVelocityVerlet:
      v = v + a * (S(0.5) * dt);
      break;
    case Integrator::Leapfrog:
      v = v + a * dt;
      x = x + v * (S(0.5) * dt);
      break;
  }
}

// Particle-level wrappers: inlet particles (age < 0) move kinematically with their emission velocity.
// predict records where the step starts: the boundaries test the whole segment moved (boundaries.h).
SPH_HD inline void predict_particle(const SimConstants& c, const ParticleView& p, int32_t i, float dt) {
  p.pos_start[i] = p.pos[i];
  if (p.age[i] < 0.0f) {
    p.vel_force[i] = p.vel[i];
    p.pos[i] = p.pos[i] + p.vel[i] * dt;
    return;
  }
  integrate_predict(c.integrator, p.pos[i], p.vel[i], p.vel_force[i], p.acc[i], dt);
}

SPH_HD inline void correct_particle(const SimConstants& c, const ParticleView& p, int32_t i, float dt) {
  const bool kinematic = p.age[i] < 0.0f;
  p.age[i] += dt;
  if (kinematic) return;
  integrate_correct(c.integrator, p.pos[i], p.vel[i], p.acc[i], dt);
  if (c.xsph_enabled) p.vel[i] += p.xsph_dv[i];
}

}  // namespace sph
