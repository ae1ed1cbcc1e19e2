// Rigid bodies' two-way coupling in a step (issue 13; the body's state and integration: src/common/rigid_body.h):
// the fluid's reaction on each free body summed over the particles in the back end's fixed order (the same
// bits on every back end), then the body advanced on the host and its new pose handed to the loops.
// WCSPH: the forces phase calls update_bodies after the fluid's forces, so the body feels exactly the
// reaction to what the fluid felt. DFSPH (src/solvers/dfsph.h): after the density solve, the reaction to the
// non-pressure forces and to everything both pressure solves applied. Scenes with bodies under PBF are
// refused at load.
#pragma once

#include <cstdint>

#include "../common/forces.h"
#include "../common/body_contact.h"
#include "../common/rigid_body.h"
#include "../common/sph_hd.h"

namespace sph {

// The bodies' forces on fluid particle i (forces.h, body_forces), added to the acceleration the forces loop
// wrote (inlet particles have none).
template <class C, class Model>
struct BodyForcesFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] < 0.0f) return;
    p.acc[i] += body_forces<Model>(*c, g, particle_side(*c, p, i), xyz(p.pos_mass[i]));
  }
};

// Component `component` of a force and torque: 0-2 force x, y, z [N]; 3-5 torque x, y, z [N m] (the six sums
// update_bodies_with asks for).
SPH_HD inline double wrench_component(Vec3 force, Vec3 torque, int32_t component) {
  const Vec3 v = component < 3 ? force : torque;
  const int32_t k = component % 3;
  return double(k == 0 ? v.x : k == 1 ? v.y : v.z);
}

// Component `component` (0-2: force x, y, z [N]; 3-5: torque [N m]) of particle i's reaction on body `body`
// (forces.h, body_reaction), for the back end's deterministic sum (Exec::sum).
template <class C, class Model>
struct BodyReactionFn {
  C c;
  GridView g;
  ParticleView p;
  int32_t body;
  int32_t component;
  SPH_KERNEL_FN double operator()(int32_t i) const {
    Vec3 force, torque;
    body_reaction<Model>(*c, g, p, i, body, force, torque);
    return wrench_component(force, torque, component);
  }
};

// The fluid's force and torque on every moving body (into RigidBody::force, torque), each component the
// back end's deterministic sum over the particles of make(body, component) (a functor returning the
// particle's share as a double), then one step dt of each (advance_body: a free body by them, a prescribed one
// by its clock; dt = 0 at the initial forces: the force is recorded, nothing moves), the contacts between
// bodies, then the new poses to the loops.
template <class Exec, class MakeReaction>
void update_bodies_with(Exec& x, float dt, MakeReaction make) {
  std::vector<RigidBody>& bodies = x.bodies();
  if (bodies.empty()) return;
  const SimConstants& c = x.host_constants();
  const int32_t n = x.particles().n;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    RigidBody& b = bodies[k];
    if (b.motion == BodyMotion::Fixed) continue;
    double value[6];
    for (int32_t component = 0; component < 6; ++component) value[component] = x.sum(n, make(int32_t(k), component));
    b.force = {value[0], value[1], value[2]};
    b.torque = {value[3], value[4], value[5]};
    advance_body(b, c, double(dt));
  }
  if (dt > 0.0f) contact_between_bodies(bodies);
  x.upload_bodies();
}

// WCSPH: the reaction to the forces phase (body_reaction under the scene's force model).
template <class Exec>
void update_bodies(Exec& x, float dt) {
  using C = typename Exec::Constants;
  with_force_model(x.host_constants(), [&](auto model) {
    update_bodies_with(x, dt, [&](int32_t body, int32_t component) {
      return BodyReactionFn<C, decltype(model)>{x.constants(), x.grid(), x.particles(), body, component};
    });
  });
}

}  // namespace sph
