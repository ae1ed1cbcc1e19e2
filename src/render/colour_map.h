// What the particles are coloured by, and the colour maps. SPH_HD so a CUDA kernel writing interop
// buffers can use the same mapping as the host path.
#pragma once

#include <cstdint>

#include "../common/sph_hd.h"
#include "../common/vec3.h"

namespace sph::render {

enum class ColourMode : int { Fluid, Speed, DensityError, Pressure, Cell, Count };

inline const char* colour_mode_name(ColourMode m) {
  switch (m) {
    case ColourMode::Fluid: return "fluid";
    case ColourMode::Speed: return "speed";
    case ColourMode::DensityError: return "density error";
    case ColourMode::Pressure: return "pressure";
    case ColourMode::Cell: return "grid cell";
    case ColourMode::Count: break;
  }
  return "?";
}

// The tables below are switches, not local arrays: a local array indexed at run time takes a stack frame
// in every thread of the CUDA interop kernel (issue 11, item 1).

// The stops of a perceptually ordered dark-blue -> teal -> yellow ramp (after viridis), i in [0, 4].
SPH_HD inline Vec3 ramp_stop(int i) {
  switch (i) {
    case 0: return {0.27f, 0.00f, 0.33f};
    case 1: return {0.23f, 0.32f, 0.55f};
    case 2: return {0.13f, 0.57f, 0.55f};
    case 3: return {0.37f, 0.79f, 0.38f};
  }
  return {0.99f, 0.91f, 0.14f};
}

// The ramp at t in [0, 1] (clamped), linear between its stops.
SPH_HD inline Vec3 ramp(float t) {
  t = t < 0.0f ? 0.0f : (t > 1.0f ? 1.0f : t);
  const float x = t * 4.0f;
  int i = int(x);
  if (i > 3) i = 3;
  const float f = x - float(i);
  return (1.0f - f) * ramp_stop(i) + f * ramp_stop(i + 1);
}

// Distinct colours for fluids (water blue first).
SPH_HD inline Vec3 fluid_colour(int fluid) {
  switch (fluid & 7) {
    case 0: return {0.16f, 0.45f, 0.85f};
    case 1: return {0.90f, 0.45f, 0.15f};
    case 2: return {0.30f, 0.75f, 0.35f};
    case 3: return {0.80f, 0.25f, 0.55f};
    case 4: return {0.95f, 0.80f, 0.20f};
    case 5: return {0.45f, 0.35f, 0.85f};
    case 6: return {0.20f, 0.75f, 0.80f};
  }
  return {0.60f, 0.60f, 0.60f};
}

// A hash colour per grid cell, to see the binning.
SPH_HD inline Vec3 cell_colour(int32_t cell) {
  uint32_t h = uint32_t(cell) * 2654435761u;
  return {0.3f + 0.7f * float((h >> 8) & 255u) / 255.0f, 0.3f + 0.7f * float((h >> 16) & 255u) / 255.0f,
          0.3f + 0.7f * float((h >> 24) & 255u) / 255.0f};
}

// The colour of one particle: one definition for the host upload path and the CUDA interop kernel.
// [lo, hi] is the range of the mapped quantity (speed in m/s, pressure in Pa); the density error uses a
// fixed -5% .. +5% of rest density.
SPH_HD inline Vec3 particle_colour(ColourMode mode, float lo, float hi, float speed, float density,
                                   float rest_density, float pressure, int fluid, int32_t cell) {
  const float span = hi > lo ? hi - lo : 1.0f;
  switch (mode) {
    case ColourMode::Speed: return ramp((speed - lo) / span);
    case ColourMode::DensityError: return ramp(0.5f + 10.0f * (density - rest_density) / rest_density);
    case ColourMode::Pressure: return ramp((pressure - lo) / span);
    case ColourMode::Cell: return cell_colour(cell);
    case ColourMode::Fluid:
    case ColourMode::Count: break;
  }
  return fluid_colour(fluid);
}

}  // namespace sph::render
