// Finiteness of a particle state: the runner checks the state after set-up and before it reports success,
// so a NaN never leaves with exit status 0.
#pragma once

#include <string>

#include "../common/particle_state.h"

namespace sph {

// The first particle whose position, velocity or density is NaN or infinite, described as
// "particle id 12 at (x, y, z): density nan", or an empty string when every particle is finite.
std::string describe_non_finite(const ParticleState& ps);

}  // namespace sph
