// What a solver does not read or was not tested with, said at set-up, and the time steps the incompressible
// solvers cannot take (issue 12): part of guided creation (guided_creation.cpp calls these while it builds
// a Setup), kept apart so that the solvers' notes are found in one place.
#pragma once

#include <string>
#include <vector>

#include "scene.h"

namespace sph {

// Appends to report a "note: ..." line for each setting the scene's solver ignores (DFSPH and PBF integrate
// their own way; PBF has no cohesion or near pressure, and no artificial viscosity without
// pbf.artificial_viscosity) and for each
// combination measured to fail under PBF (the solver's keys and values named, with what held in the tests).
void report_ignored_settings(const Scene& scene, std::vector<std::string>& report);

// Throws SceneError naming time_step.dt (fixed) or time_step.max (adaptive) when DFSPH's or PBF's step exceeds
// sqrt(d / |g|) (time_step.h, incompressible_step_bound). spacing: d [m].
void check_incompressible_step(const Scene& scene, double spacing);

// Throws SceneError naming time_step.dt (fixed) or time_step.min (adaptive) when DFSPH's or PBF's step
// exceeds the springs' explicit limit (time_step.h, spring_step_bound). spring_rate: the springs' fastest
// angular frequency [1/s] (springs.h); 0: no springs.
void check_spring_step(const Scene& scene, double spring_rate);

}  // namespace sph
