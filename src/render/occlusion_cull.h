// Hidden-particle culling for drawing very large particle sets (issue 14: a 1M-particle replay). When the
// spheres are at most a couple of pixels across, most particles of a deep fluid are hidden behind nearer
// ones in the same pixel; drawing only the nearest particle of each pixel gives nearly the same picture for a
// fraction of the points (at the 1M dam break's start, about one in ten). It is an approximation only where a
// sprite reaches past its own pixel: a particle whose centre pixel is taken by a nearer one may still show
// at its sprite's rim; tests/demo_cull_test.sh bounds the differing pixels. CPU only, no OpenGL.
#pragma once

#include <cstdint>
#include <vector>

#include "../common/vec3.h"
#include "math3d.h"

namespace sph::render {

// Pixels per sphere diameter at view depth `depth` [m] (> 0): projection[5] * height * radius / depth, the
// point size shaders/particles.vert gives a sphere of radius `radius` [m] at that depth.
inline float projected_diameter(const Mat4& projection, int height, float radius, float depth) {
  return projection[5] * float(height) * radius / depth;
}

// The scratch buffers of front_particles, kept between calls (two per pixel of the view).
struct CullBuffers {
  std::vector<float> depth;
  std::vector<int32_t> nearest;
};

// Fills `out` with the indices, ascending, of the particles that are the nearest to the camera in their
// pixel of a width x height view (view and projection: column-major OpenGL matrices), one per pixel that a
// particle centre falls in; particles outside the view (beside it, before its near plane or beyond its far
// one: where OpenGL clips them) are left out. The projection must be a perspective one (clip w = -z_view,
// math3d.h). positions: world coordinates [m]. width, height >= 1.
void front_particles(const std::vector<Vec3>& positions, const Mat4& view, const Mat4& projection, int width, int height,
                     CullBuffers& scratch, std::vector<uint32_t>& out);

}  // namespace sph::render
