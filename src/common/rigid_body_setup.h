// The scene's rigid bodies (key "bodies") made at set-up: sampled, weighed and placed (rigid_body.h).
#pragma once

#include <string>
#include <vector>

#include "rigid_body.h"
#include "scene.h"

namespace sph {

// Each body of the scene as a RigidBody at rest at its place: its particles sampled as an obstacle of its
// shape alone (boundary_particles.h; the volumes its own, since it moves), then taken into its frame
// (relative to the centre of mass, along its principal axes); its mass from the density (or as given) and
// its principal moments from the shape (box: M (b^2 + c^2) / 12 about x, ...; sphere: 2 M r^2 / 5; mesh:
// mesh_mass_properties, diagonalised). c: the constants with the kernel and the walls. Throws SceneError
// naming bodies.N: a body that crosses a wall of a box container or overlaps another body (their bounding
// boxes), a mesh that cannot be read or bounds no solid, thinner than two spacings, a stroke through a
// wall, or too many particles for the budget. report gets a line each.
std::vector<RigidBody> make_rigid_bodies(const Scene& scene, const SimConstants& c, double spacing, double max_particles,
                                         std::vector<std::string>& report);

// make_rigid_bodies in its two halves, for the set-up, which removes the fluid where the bodies are before
// it knows the domain the spheres' sampling needs: the bodies placed, weighed and checked, without
// particles; then their particles (c with its grid), one report line each.
std::vector<RigidBody> place_rigid_bodies(const Scene& scene, const SimConstants& c, double spacing);
void sample_rigid_bodies(const Scene& scene, const SimConstants& c, double spacing, double max_particles,
                         std::vector<RigidBody>& bodies, std::vector<std::string>& report);

}  // namespace sph
