// How deep the fluid has got into the solids: the leak check of sph_run's metrics and of the tests that run
// every shipped scene (issue 13: no leak through any wall or obstacle). Host code, O(N) per call.
#pragma once

#include <vector>

#include "boundary_particles.h"
#include "particle_state.h"
#include "rigid_body.h"

namespace sph {

struct Penetration {
  double deepest = 0.0;  // [m] the largest depth of any fluid particle inside any solid (0 when none is)
  long count = 0;        // fluid particles deeper than the threshold asked
};

// Depth of each fluid particle (a jet's inlet particles left out) inside the solids: the scene's shapes
// except absorbing ones (depth = -boundary_clearance, setup_checks.h: outside a container counts as inside
// its solid), its meshes (-mesh_signed_distance for an obstacle, + for a container; only particles within
// the mesh's bounding box are asked) and its rigid bodies at their current pose (box or sphere). A particle
// that crosses a wall of thickness T at the CFL-limited speed (at most 0.8 d a step) is at some step deeper
// than T / 2 - 0.4 d: checked every step, a crossing of a wall 2 d thick shows as a depth of 0.6 d at least.
// threshold [m]: the depth counted in Penetration::count.
Penetration solid_penetration(const SimConstants& c, const std::vector<MeshSolid>& meshes,
                              const std::vector<RigidBody>& bodies, const ParticleState& ps, double threshold);

}  // namespace sph
