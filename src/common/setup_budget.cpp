#include "setup_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "guided_creation.h"
#include "particle_state.h"

namespace sph {

double usable_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  double bytes = 0.5 * (pages > 0 && page > 0 ? double(pages) * double(page) : 8.0 * double(1L << 30));
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    bytes = std::min(bytes, 0.8 * double(limit.rlim_cur));
  return bytes;
}

namespace {

std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// A value known by its natural logarithm: printed directly where a double holds it, else as 10^n.
std::string log_value_text(double log_value) {
  const double l10 = log_value / std::log(10.0);
  if (std::fabs(l10) < 300.0) return number_text(std::exp(log_value));
  char buf[32];
  std::snprintf(buf, sizeof buf, "about 10^%.0f", l10);
  return buf;
}

// Single precision's normal range, narrowed by 1e3 on each side: the phases multiply coefficients by
// small factors (-6 x Poly6 in its gradient) and sum a few dozen neighbour terms before any division.
const double kFloatLow = 1e3 * double(FLT_MIN);
const double kFloatHigh = double(FLT_MAX) / 1e3;

// One quantity kept in float: log of its value at this spacing, and its power of the spacing.
struct Derived {
  std::string name;  // for the message, with its formula
  std::string key;   // the scene key it comes from when it does not depend on the spacing
  double log_value;
  double power;
};

}  // namespace

std::string count_text(double n) {
  if (!(n <= 1e18)) return "more than 1e18";
  if (n < 1e15 && n == std::floor(n)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f", n);
    return buf;
  }
  return number_text(n);
}

double particle_budget(const Scene& scene) {
  return std::min(scene.max_particles, usable_memory_bytes() / double(kBytesPerParticle));
}

void check_particle_budget(const Scene& scene, double count, const std::string& what, const std::string& advice) {
  std::ostringstream os;
  if (!(count <= scene.max_particles)) {
    os << scene.source << ": " << what << " needs about " << count_text(count)
       << " particles, more than limits.max_particles = " << count_text(scene.max_particles) << "; " << advice
       << ", or raise the limit (--set limits.max_particles=N)";
    throw SceneError(os.str());
  }
  const double bytes = count * double(kBytesPerParticle);
  const double avail = usable_memory_bytes();
  if (bytes > avail) {
    os << scene.source << ": " << what << " needs about " << count_text(count) << " particles, about "
       << number_text(bytes / 1e9) << " GB (estimate, " << kBytesPerParticle
       << " bytes each), more than the " << number_text(avail / 1e9)
       << " GB this run may use (half of this machine's memory, or 80% of the process's address-space limit); "
       << advice;
    throw SceneError(os.str());
  }
}

std::string out_of_memory_text(const Scene& scene, double count) {
  return scene.source + ": out of memory: " + count_text(count) + " particles need about " +
         number_text(count * double(kBytesPerParticle) / 1e9) + " GB (estimate); lower the resolution";
}

void check_float_range(const Scene& scene, double spacing, double h, double lattice_density) {
  const double pi = 3.14159265358979323846;
  const double lh = std::log(h), ld = std::log(spacing);
  std::vector<Derived> q = {
      {"the support radius h", "", lh, 1.0},
      {"h^2", "", 2.0 * lh, 2.0},
      {"the Poly6 gradient coefficient 6 x 315/(64 pi h^9)", "", std::log(6.0 * 315.0 / (64.0 * pi)) - 9.0 * lh, -9.0},
      {"the Spiky gradient coefficient 45/(pi h^6)", "", std::log(45.0 / pi) - 6.0 * lh, -6.0},
      {"the near kernel gradient coefficient 105/(pi h^7)", "", std::log(105.0 / pi) - 7.0 * lh, -7.0},
      {"the viscosity kernel coefficient 15/(2 pi h^3)", "", std::log(15.0 / (2.0 * pi)) - 3.0 * lh, -3.0},
      {"the cubic spline coefficient 8/(pi h^3)", "", std::log(8.0 / pi) - 3.0 * lh, -3.0},
  };
  for (std::size_t i = 0; i < scene.fluids.size(); ++i) {
    const FluidSpec& f = scene.fluids[i];
    const std::string key = "fluids." + std::to_string(i);
    // Mass m = rho0 d^3 / (lattice kernel sum) (thesis 4.1.5), or rho0 d^3 with "mass": "volume".
    const double lm = std::log(f.rest_density) + 3.0 * ld -
                      (scene.mass_rule == MassRule::Volume ? 0.0 : std::log(lattice_density));
    q.push_back({"the particle mass of " + key, "", lm, 3.0});
    q.push_back({"the rest density", key + ".rest_density", std::log(f.rest_density), 0.0});
    q.push_back({"Tait's B = rho0 c0^2 / 7", key + ".speed_of_sound",
                 std::log(f.rest_density) + 2.0 * std::log(f.speed_of_sound) - std::log(7.0), 0.0});
    if (f.viscosity > 0.0) q.push_back({"the viscosity", key + ".viscosity", std::log(f.viscosity), 0.0});
    // The cohesion constant 8 sigma / (pi rho0^2 h^5 J4) (calibration.h) and what it multiplies, the mass.
    if (f.surface_tension > 0.0)
      q.push_back({"the cohesion constant 8 sigma / (pi rho0^2 h^5 J4)", key + ".surface_tension",
                   std::log(cohesion_from_surface_tension(f.surface_tension, f.rest_density, 1.0)) - 5.0 * lh, -5.0});
  }
  // Spacings for which every quantity that scales with d stays in range.
  const double llo = std::log(kFloatLow), lhi = std::log(kFloatHigh);
  double dmin = -INFINITY, dmax = INFINITY;  // as logarithms
  for (const Derived& x : q) {
    if (x.power == 0.0) continue;
    const double a = ld + (llo - x.log_value) / x.power, b = ld + (lhi - x.log_value) / x.power;
    dmin = std::max(dmin, std::min(a, b));
    dmax = std::min(dmax, std::max(a, b));
  }
  for (const Derived& x : q) {
    if (x.log_value >= llo && x.log_value <= lhi) continue;
    std::ostringstream os;
    os << scene.source << ": ";
    if (x.power == 0.0) {
      os << x.key << ": " << x.name << " = " << log_value_text(x.log_value);
    } else {
      os << (scene.spacing > 0.0 ? "resolution.spacing " : "resolution.particles_across " +
                                                              std::to_string(scene.particles_across) + " gives spacing ")
         << number_text(spacing) << " m: " << x.name << " = " << log_value_text(x.log_value);
    }
    os << (x.log_value > lhi ? " exceeds" : " falls below") << " single precision's range [" << number_text(kFloatLow)
       << ", " << number_text(kFloatHigh) << "] (its normal range with 1e3 headroom for products and sums)";
    if (x.power != 0.0) {
      if (dmin <= dmax)
        os << "; spacings allowed for this scene: [" << log_value_text(dmin) << ", " << log_value_text(dmax) << "] m";
      else
        os << "; no spacing fits this scene's fluids";
    }
    throw SceneError(os.str());
  }
}

}  // namespace sph
