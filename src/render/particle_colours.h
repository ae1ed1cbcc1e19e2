// The host path of particle colouring: the range of the mapped quantity and one colour per particle, as
// the demo uploads them when the back end cannot write the OpenGL buffers itself. Plain C++ (no GL), so the
// device test checks the interop kernel against exactly this (issue 11, Build item 5).
#pragma once

#include <algorithm>
#include <vector>

#include "../common/grid.h"
#include "../common/params.h"
#include "../common/particle_state.h"
#include "colour_map.h"

namespace sph::render {

// [lo, hi] of the mapped quantity and its unit, for the colour map and the legend.
struct ColourRange {
  float lo = 0.0f, hi = 1.0f;
  const char* unit = "";
};

// The range over the particles: speed 0 .. the largest speed (m/s), pressure from min(0, lowest) to the
// highest (Pa); the density error a fixed -5 .. +5 % of rest density; fluid and cell have none.
inline ColourRange colour_range(const ParticleState& ps, ColourMode mode) {
  if (mode == ColourMode::Speed) {
    float vmax = 1e-6f;
    for (const Vec3& v : ps.vel) vmax = std::max(vmax, length(v));
    return {0.0f, vmax, "m/s"};
  }
  if (mode == ColourMode::Pressure) {
    float lo = 0.0f, hi = 1e-6f;
    for (float p : ps.pressure) {
      lo = std::min(lo, p);
      hi = std::max(hi, p);
    }
    return {lo, hi, "Pa"};
  }
  if (mode == ColourMode::DensityError) return {-5.0f, 5.0f, "% of rho0"};
  return {};
}

// Particle i's colour by particle_colour, the definition the interop kernel uses. c: the constants ps was
// simulated with (rest densities, grid).
inline Vec3 colour_of(const ParticleState& ps, const SimConstants& c, ColourMode mode, const ColourRange& range,
                      std::size_t i) {
  return particle_colour(mode, range.lo, range.hi, length(ps.vel[i]), ps.density[i], c.fluids[ps.fluid[i]].rest_density,
                         ps.pressure[i], ps.fluid[i], cell_index(c.grid, ps.pos[i]));
}

// One colour per particle of ps (same order); out is resized to ps.size().
inline void colour_particles(const ParticleState& ps, const SimConstants& c, ColourMode mode, const ColourRange& range,
                             std::vector<Vec3>& out) {
  out.resize(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) out[i] = colour_of(ps, c, mode, range, i);
}

}  // namespace sph::render
