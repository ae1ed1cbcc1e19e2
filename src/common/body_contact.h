// Contact between rigid bodies (issue 13: "contact ... between bodies, simple and robust"). Host code, run
// once per step after every body has moved (src/solvers/rigid_bodies.h, update_bodies), in the scene's
// order, so every back end gets the same bits.
#pragma once

#include <vector>

#include "rigid_body.h"

namespace sph {

// For each pair of bodies whose shapes overlap (boxes by the separating-axis test over their 15 axes,
// spheres by their centres): the pair is pushed apart along the axis of least overlap by that overlap,
// shared by inverse mass, and the points where they touch (each body's outer layer of particles moved out to
// its surface, found inside the other) get inelastic, frictionless impulses along that axis, solved together
// (projected Gauss-Seidel with accumulated, non-negative impulses) so a resting body neither sinks nor spins.
// The impulses are equal and opposite: momentum is conserved; the push moves the bodies without changing
// their velocities. Fixed and prescribed bodies do not yield (infinite mass).
void contact_between_bodies(std::vector<RigidBody>& bodies);

}  // namespace sph
