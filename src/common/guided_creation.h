// Guided creation (thesis 4.1.4 and 4.1.5): from the user's volumes, physical properties and resolution,
// derive the spacing, the smoothing length h from the mean neighbour count, the particle masses, the grid,
// and the initial particles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "boundary_particles.h"
#include "rigid_body.h"
#include "springs.h"
#include "emitters.h"
#include "particle_state.h"
#include "scene.h"
#include "calibration.h"

namespace sph {

struct Setup {
  SimConstants constants{};
  ParticleState particles;         // instant emitters plus the jets' prefilled inlets
  BoundaryParticles boundary;      // the walls' boundary particles (sph.walls = "particles"), else empty
  std::vector<MeshSolid> meshes;   // the scene's meshes, loaded, scaled and placed
  std::vector<RigidBody> bodies;   // the scene's rigid bodies at their start
  SpringNetwork springs;           // the elastic fluids' springs at the start (springs.h), else empty
  std::vector<JetEmitter> jets;
  double spacing = 0.0;            // d
  double h = 0.0;                  // support radius
  double lattice_density = 0.0;    // sum_b W over a cubic lattice of spacing d, times d^3 (lattice_density_factor)
  double max_speed_of_sound = 0.0;
  double viscous_rate = 0.0;       // lambda_max of the viscous operator [1/s] (viscous_limit.h)
  double spring_rate = 0.0;        // a bound on the springs' fastest angular frequency [1/s] (springs.h); 0: none
  double blowup_speed = 0.0;       // speeds above this stop the run
  double expected_particles = 0.0; // instant particles plus the jets' steady state
  int32_t next_id = 0;
  // What set-up found and did, one line each (fills, shared lattice points, particles removed from
  // solids): the runner prints them as "setup: ...".
  std::vector<std::string> report;
  bool adjusted = false;           // the checks changed what the scene asked for (refit, shared or removed points)
};

// The speed bound when the energy check cannot give one (a user force doing work) [m/s]:
// limits.blowup_speed, or ten times the fastest of the speeds of sound and the jets (weakly compressible
// SPH assumes flow speeds well below c0).
double fallback_blowup_speed(const Scene& scene, double max_speed_of_sound, const std::vector<JetEmitter>& jets);

// Throws SceneError when the scene cannot be set up: an emitter holds no lattice point, a jet's inlet
// crosses a boundary, fluid lies in a solid with "on_overlap": "error", a derived quantity leaves single
// precision's range, the particles (counted before anything is allocated) exceed limits.max_particles or
// this machine's memory, the grid would be too large; a std::bad_alloc becomes "out of memory" with the
// estimate.
Setup create_setup(const Scene& scene, double run_time);

}  // namespace sph
