#include "solid_penetration.h"

#include <algorithm>
#include <cmath>

#include "mesh.h"
#include "setup_checks.h"

namespace sph {

Penetration solid_penetration(const SimConstants& c, const std::vector<MeshSolid>& meshes,
                              const std::vector<RigidBody>& bodies, const ParticleState& ps, double threshold) {
  Penetration out;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.age[i] < 0.0f) continue;
    const Vec3d p{ps.pos[i].x, ps.pos[i].y, ps.pos[i].z};
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;  // outside_domain counts them
    double depth = 0.0;
    for (int32_t s = 0; s < c.num_shapes; ++s)
      if (!c.shapes[s].absorb) depth = std::max(depth, -boundary_clearance(c.shapes[s], p));
    for (const MeshSolid& m : meshes) {
      const bool in_box = p[0] >= m.mesh.lo[0] && p[1] >= m.mesh.lo[1] && p[2] >= m.mesh.lo[2] &&
                          p[0] <= m.mesh.hi[0] && p[1] <= m.mesh.hi[1] && p[2] <= m.mesh.hi[2];
      if (in_box) {
        const double sd = mesh_signed_distance(m.mesh, {p[0], p[1], p[2]});
        depth = std::max(depth, m.inside ? sd : -sd);
      } else if (m.inside) {  // outside a container's bounding box: in its solid, at least this deep
        const double dx = std::max({m.mesh.lo[0] - p[0], p[0] - m.mesh.hi[0], 0.0});
        const double dy = std::max({m.mesh.lo[1] - p[1], p[1] - m.mesh.hi[1], 0.0});
        const double dz = std::max({m.mesh.lo[2] - p[2], p[2] - m.mesh.hi[2], 0.0});
        depth = std::max(depth, std::sqrt(dx * dx + dy * dy + dz * dz));
      }
    }
    for (const RigidBody& b : bodies) depth = std::max(depth, depth_in_body(b, p));
    out.deepest = std::max(out.deepest, depth);
    if (depth > threshold) ++out.count;
  }
  return out;
}

}  // namespace sph
