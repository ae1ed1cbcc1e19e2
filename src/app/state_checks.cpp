#include "state_checks.h"

#include <cmath>
#include <sstream>

namespace sph {

namespace {
bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

std::string describe_non_finite(const ParticleState& ps) {
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const char* what = !finite(ps.pos[i]) ? "position" : !finite(ps.vel[i]) ? "velocity"
                     : !std::isfinite(ps.density[i]) ? "density" : nullptr;
    if (!what) continue;
    std::ostringstream os;
    const Vec3 x = ps.pos[i], v = ps.vel[i];
    os << "particle id " << ps.id[i] << " at (" << x.x << ", " << x.y << ", " << x.z << ") has a non-finite " << what
       << " (velocity (" << v.x << ", " << v.y << ", " << v.z << "), density " << ps.density[i] << ")";
    return os.str();
  }
  return {};
}

}  // namespace sph
