// Rigid bodies with two-way coupling (issue 13; thesis sections 3.5.5 and 4.2.4, [AIA12] section 4): a body
// carries boundary particles, sampled once in its own frame, that take part in the fluid's sums like the
// walls' (boundary_view.h, BodyView); the fluid's reaction on them is summed deterministically into a force
// and a torque (src/solvers/rigid_bodies.h), which move the body, whose motion moves its particles.
// Host code: the state is double precision and advanced on the host, once per step, the same on every back
// end.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "boundary_particles.h"
#include "mesh.h"
#include "params.h"

namespace sph {

using BodyVector = std::array<double, 3>;

enum class BodyMotion { Fixed, Free, Prescribed };

struct RigidBody {
  std::string label;          // "bodies.N (box)", for messages
  BoundaryParticles local;    // its particles relative to the centre of mass, in its own cell grid
  BodyMotion motion = BodyMotion::Free;
  double mass = 0.0;          // [kg]
  BodyVector inertia{};       // principal moments in the body frame (its axes) [kg m^2]
  double radius = 0.0;        // of its particles about the centre [m]
  double spacing = 0.0;       // d its particles were sampled at [m]
  BodyVector half_extent{};   // box: half sides; sphere: the radius three times; mesh: of its bounding box
                              // about the centre, in its axes [m] (contact between bodies)
  bool sphere = false;
  bool mesh = false;
  std::vector<BodyVector> hull;  // box: its corners; mesh: its vertices; in its frame [m] (contact with walls)
  TriangleMesh surface;          // mesh: its surface in its frame [m]
  // Prescribed motion, s = sin(2 pi t / period): a turn by angle s about `axis` through `pivot`, then a
  // shift by amplitude s: centre(t) = pivot + R(angle s) (start - pivot) + amplitude s, orientation R(angle s)
  // (a piston and/or a flap wave maker; scene.h, BodySpec).
  BodyVector start{}, amplitude{};
  double period = 0.0;  // [s]
  double angle = 0.0;   // [rad]
  BodyVector axis{0.0, 0.0, 1.0}, pivot{};
  double time = 0.0;    // its own clock [s], advanced with every step
  // State
  BodyVector centre{}, velocity{}, omega{};
  std::array<double, 4> orientation{1.0, 0.0, 0.0, 0.0};  // unit quaternion (w, x, y, z), body to world
  // The fluid's last force and torque on it [N], [N m], and whether contact with the walls acted.
  BodyVector force{}, torque{};
  bool contact = false;       // a wall's contact acted this step
  bool body_contact = false;  // another body's contact acted this step (body_contact.h)

  // The view the fluid's loops read, with `local` as given (the back end's copy of this body's particles).
  BodyView view(const BoundaryView& local_view, float h) const;
};

// One step of a free body: v += dt (F / M + g), the angular momentum L = I_world omega += dt tau, omega from
// L with the rotated inertia, the orientation by the quaternion rate 0.5 [0, omega] q (normalised), x += dt
// v (symplectic Euler, the fluid's forces of this step), g the scene's gravity. Then the walls of box
// containers: corners behind a wall are pushed out and given an inelastic impulse at the contact
// (rigid_body.cpp; a mesh body's vertices stand for its corners); bodies touching each other are handled after all have moved (body_contact.h).
// Fixed bodies do not move; prescribed ones follow their oscillation (prescribed_pose) (the fluid's force on them is
// recorded, not applied).
void advance_body(RigidBody& b, const SimConstants& c, double dt);

// Depth [m] of world point p inside body b at its current pose (negative outside): a box's or sphere's
// exact, a mesh's from its signed distance (mesh.h).
double depth_in_body(const RigidBody& b, const BodyVector& p);

// The pose and velocities of a prescribed body at time t [s] (its oscillation; see RigidBody): sets centre,
// orientation, velocity and omega.
void prescribed_pose(RigidBody& b, double t);

}  // namespace sph
