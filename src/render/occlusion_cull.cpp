#include "occlusion_cull.h"

#include <algorithm>
#include <limits>

namespace sph::render {

void front_particles(const std::vector<Vec3>& positions, const Mat4& v, const Mat4& p, int width, int height,
                     CullBuffers& scratch, std::vector<uint32_t>& out) {
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  scratch.depth.assign(pixels, std::numeric_limits<float>::infinity());
  scratch.nearest.assign(pixels, -1);
  const float half_w = 0.5f * float(width), half_h = 0.5f * float(height);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3 x = positions[i];
    // View space, then clip space (the perspective of math3d.h: w = -z_view).
    const float ex = v[0] * x.x + v[4] * x.y + v[8] * x.z + v[12];
    const float ey = v[1] * x.x + v[5] * x.y + v[9] * x.z + v[13];
    const float ez = v[2] * x.x + v[6] * x.y + v[10] * x.z + v[14];
    const float depth = -ez;
    if (!(depth > 0.0f)) continue;
    const float cx = p[0] * ex + p[4] * ey + p[8] * ez + p[12];
    const float cy = p[1] * ex + p[5] * ey + p[9] * ez + p[13];
    const float cz = p[2] * ex + p[6] * ey + p[10] * ez + p[14];
    if (!(cz >= -depth && cz <= depth)) continue;  // before the near plane or beyond the far one: OpenGL clips it
    const float sx = (cx / depth + 1.0f) * half_w, sy = (cy / depth + 1.0f) * half_h;
    if (!(sx >= 0.0f && sx < float(width) && sy >= 0.0f && sy < float(height))) continue;
    const std::size_t pixel = std::size_t(int(sy)) * std::size_t(width) + std::size_t(int(sx));
    if (depth < scratch.depth[pixel]) {
      scratch.depth[pixel] = depth;
      scratch.nearest[pixel] = int32_t(i);
    }
  }
  out.clear();
  for (int32_t i : scratch.nearest)
    if (i >= 0) out.push_back(uint32_t(i));
  std::sort(out.begin(), out.end());
}

}  // namespace sph::render
