// Budgets checked at load time, before anything that grows with the scene is allocated: particle counts
// against limits.max_particles and this machine's memory, and the derived quantities of the resolution
// against single precision's range (the back ends compute in float).
#pragma once

#include <string>

#include "params.h"
#include "scene.h"

namespace sph {

// Memory [bytes] a run may fill: half of this machine's memory, or less where the process has an
// address-space limit (ulimit -v; 80% of it, the rest holds the program, its libraries and thread stacks).
// Also the bound of sph_surface's meshes and sph_demo --replay's recordings.
double usable_memory_bytes();

// A count for a message: "16000", "1.25e+11", or "more than 1e18" (never an overflowed integer).
std::string count_text(double n);

// Throws SceneError naming the file when `count` particles exceed limits.max_particles or, at
// kBytesPerParticle each, half of this machine's memory (less under an address-space limit, ulimit -v). what: where they come from ("<what> needs about N
// particles"); advice: what to change ("lower the resolution").
void check_particle_budget(const Scene& scene, double count, const std::string& what,
                           const std::string& advice = "lower the resolution");

// "out of memory: N particles need about X GB (estimate)", for a std::bad_alloc during set-up.
std::string out_of_memory_text(const Scene& scene, double count);

// Most particles one set-up step may create: limits.max_particles, or fewer where memory holds fewer.
double particle_budget(const Scene& scene);

// Checks every quantity the back ends keep in float (kernel coefficients, h, h^2, particle masses,
// Tait's B, cohesion, viscosities, rest densities) against single precision's normal range with a 1e3
// headroom for the products and sums built from them. Each is computed from logarithms, so no value
// overflows in double either. Throws SceneError naming the key, the quantity, its value and the
// spacings this scene allows. lattice_density: lattice_density_factor at this h / d (scale-free).
void check_float_range(const Scene& scene, double spacing, double h, double lattice_density);

}  // namespace sph
