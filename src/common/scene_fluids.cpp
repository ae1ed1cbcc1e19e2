#include "scene_fluids.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "guided_creation.h"
#include "host_neighbours.h"
#include "kernels.h"
#include "mirror_walls.h"
#include "surface_tension_csf.h"

namespace sph {

namespace {

std::string fluid_key(std::size_t i) { return "fluids." + std::to_string(i); }

double tait_b(const FluidSpec& f) { return f.rest_density * f.speed_of_sound * f.speed_of_sound / 7.0; }

}  // namespace

void check_fluid_ratios(const Scene& scene) {
  const std::vector<FluidSpec>& fluids = scene.fluids;
  for (std::size_t i = 0; i < fluids.size(); ++i)
    for (std::size_t j = 0; j < fluids.size(); ++j) {
      const FluidSpec& heavy = fluids[i];
      const FluidSpec& light = fluids[j];
      if (i == j || heavy.rest_density <= light.rest_density) continue;
      const double ratio = heavy.rest_density / light.rest_density;
      std::ostringstream os;
      os << scene.source << ": ";
      if (!scene.number_density && ratio > kMassDensityRatioLimit) {
        os << "sph.multiphase: \"mass_density\" holds fluids (all those of a scene) whose rest densities differ by at most a factor "
           << kMassDensityRatioLimit << ", but " << fluid_key(i) << " and " << fluid_key(j) << " differ by " << ratio
           << " (" << heavy.rest_density << " and " << light.rest_density
           << " kg/m^3): use \"multiphase\": \"number_density\" (allowed: number_density, mass_density)";
        throw SceneError(os.str());
      }
      const double b_ratio = tait_b(heavy) / tait_b(light);
      if (scene.solver == Solver::Wcsph && scene.number_density && b_ratio > kTaitRatioLimit) {
        const double c_min = std::sqrt(tait_b(heavy) / kTaitRatioLimit * 7.0 / light.rest_density);
        os << fluid_key(j) << ".speed_of_sound: " << light.speed_of_sound << " m/s makes Tait's B = rho0 c0^2 / 7 of "
           << fluid_key(j) << " " << b_ratio << " times smaller than that of " << fluid_key(i)
           << "; the fluids of a scene may differ by at most " << kTaitRatioLimit << " (at the interface each side's pressure "
           << "must follow about the same law), so give " << fluid_key(j) << " a speed of sound of at least " << c_min
           << " m/s (the time step shrinks in proportion)";
        throw SceneError(os.str());
      }
    }
}

void check_surface_tension(const Scene& scene, double h) {
  // The incompressible solvers hold any pressure; the continuum surface force has no internal pressure.
  if (scene.solver != Solver::Wcsph || scene.surface_tension_model != SurfaceTensionModel::Cohesion) return;
  for (std::size_t i = 0; i < scene.fluids.size(); ++i) {
    const FluidSpec& f = scene.fluids[i];
    if (!(f.surface_tension > 0.0)) continue;
    const double p = cohesion_pressure(f.surface_tension, h);
    const double compression = p / (f.rest_density * f.speed_of_sound * f.speed_of_sound);
    if (compression <= kCohesionCompressionLimit) continue;
    std::ostringstream os;
    os.precision(3);
    os << scene.source << ": " << fluid_key(i) << ".speed_of_sound: " << f.speed_of_sound << " m/s is too soft for "
       << fluid_key(i) << ".surface_tension = " << f.surface_tension << " N/m at this resolution (h = " << h
       << " m): the cohesion's internal pressure 8.23 sigma / h = " << p << " Pa would compress the fluid by "
       << 100.0 * compression << "%, more than " << 100.0 * kCohesionCompressionLimit
       << "%. Allowed: a speed of sound of at least "
       << std::sqrt(p / (kCohesionCompressionLimit * f.rest_density)) << " m/s (or a smaller sigma, or a coarser resolution)";
    throw SceneError(os.str());
  }
  // An interface tension's cohesion between two fluids is that of one fluid with sigma = |sigma_a + sigma_b -
  // sigma_ab| / 2 (calibration.h, cross_cohesion): the same limit on each side's equation of state.
  for (std::size_t k = 0; k < scene.interface_tensions.size(); ++k) {
    const InterfaceTensionSpec& t = scene.interface_tensions[k];
    const double sigma = 0.5 * std::fabs(scene.fluids[std::size_t(t.a)].surface_tension +
                                         scene.fluids[std::size_t(t.b)].surface_tension - t.sigma);
    const double p = cohesion_pressure(sigma, h);
    for (const int i : {t.a, t.b}) {
      const FluidSpec& f = scene.fluids[std::size_t(i)];
      const double compression = p / (f.rest_density * f.speed_of_sound * f.speed_of_sound);
      if (compression <= kCohesionCompressionLimit) continue;
      std::ostringstream os;
      os.precision(3);
      os << scene.source << ": interface_tension." << k << ".sigma = " << t.sigma << " N/m needs a cohesion between "
         << fluid_key(t.a) << " and " << fluid_key(t.b) << " that would compress " << fluid_key(i) << " by "
         << 100.0 * compression << "% at this resolution (h = " << h << " m; internal pressure 8.23 |sigma_a + sigma_b - "
         << "sigma_ab| / (2 h) = " << p << " Pa), more than " << 100.0 * kCohesionCompressionLimit << "%. Allowed: "
         << fluid_key(i) << ".speed_of_sound of at least " << std::sqrt(p / (kCohesionCompressionLimit * f.rest_density))
         << " m/s (or an interface tension closer to the sum of the two fluids' sigmas, or a coarser resolution)";
      throw SceneError(os.str());
    }
  }
}

void check_contact_angle(const Scene& scene) {
  for (std::size_t i = 0; i < scene.fluids.size(); ++i) {
    const FluidSpec& f = scene.fluids[i];
    if (!(f.contact_angle > 0.0)) continue;
    const std::string key = scene.source + ": " + fluid_key(i) + ".contact_angle";
    if (scene.solver == Solver::Pbf)
      throw SceneError(key + ": solver \"pbf\" holds no contact angle (it has neither the cohesion's adhesion nor the "
                             "continuum surface force's wall images); use \"wcsph\" or \"dfsph\"");
    if (!(f.surface_tension > 0.0))
      throw SceneError(key + ": a contact angle is a property of the fluid's surface tension; give " + fluid_key(i) +
                       ".surface_tension > 0 [N/m] or remove contact_angle");
    if (scene.surface_tension_model == SurfaceTensionModel::Csf) {
      // Measured with mirror walls and boundary particles; with penalty walls, whose particles pack against
      // the wall closer than the images assume, 32% of a 90-degree drop was thrown off within 0.6 s.
      if (!scene.mirror_walls && !scene.boundary_particles)
        throw SceneError(key + ": under the continuum surface force the contact angle needs sph.walls = \"mirror\" "
                               "or \"particles\" (with \"penalty\" walls the drops fly apart: docs/results.md, "
                               "\"Contact angle\")");
      // The continuum surface force sets the angle at the walls mirror_walls.h finds (surface_tension_csf.h).
      bool wall = false;
      for (const BoundarySpec& b : scene.boundaries) {
        const Shape& s = b.shape;
        wall = wall || (s.type == ShapeType::Box && s.keep_inside) || (s.type == ShapeType::Plane && !s.absorb) ||
               (s.type == ShapeType::Sphere && s.keep_inside);
      }
      if (!wall)
        throw SceneError(key + ": the continuum surface force sets the angle at walls (box or sphere containers, "
                               "planes that do not absorb), and this scene has none");
      if (f.contact_angle < kCsfContactAngleMin || f.contact_angle > kCsfContactAngleMax) {
        std::ostringstream os;
        os << key << " = " << std::setprecision(9) << f.contact_angle << ": under the continuum surface force the contact angle must lie in ["
           << kCsfContactAngleMin << ", " << kCsfContactAngleMax << "] degrees (below, the spreading film sheds "
           << "particles; above, a drop released as a cube leaves the wall and no angle was measured: docs/results.md, \"Contact angle\"); sph.surface_tension = "
           << "\"cohesion\" takes any angle in (0, 180]";
        throw SceneError(os.str());
      }
      continue;
    }
    if (!scene.boundary_particles && scene.bodies.empty())
      throw SceneError(key + ": the adhesion acts between the fluid and boundary particles; set sph.walls = "
                             "\"particles\" (or add bodies)");
  }
}

void check_interface_tension(const Scene& scene) {
  if (scene.interface_tensions.empty()) return;
  const std::string key = scene.source + ": interface_tension";
  if (scene.solver == Solver::Pbf)
    throw SceneError(key + ": solver \"pbf\" has no interface tension between two fluids (its continuum surface force "
                           "acts with each fluid's own surface_tension only); use \"wcsph\" or \"dfsph\"");
  if (scene.surface_tension_model != SurfaceTensionModel::Csf) return;
  // The share of the other fluid (surface_tension_csf.h) counts every fluid but a particle's own as one.
  if (scene.fluids.size() != 2)
    throw SceneError(key + ": under sph.surface_tension = \"csf\" an interface tension is between the scene's two "
                           "fluids, and this scene has " + std::to_string(scene.fluids.size()) +
                     "; use sph.surface_tension = \"cohesion\" for interface tensions among more fluids");
  for (std::size_t i = 0; i < scene.fluids.size(); ++i)
    if (scene.fluids[i].contact_angle > 0.0)
      throw SceneError(key + ": under sph.surface_tension = \"csf\" an interface tension and a contact angle are "
                             "not run together; remove " + fluid_key(i) + ".contact_angle (or the interface_tension)");
}

void check_interface_gas(const Scene& scene, const Setup& s) {
  if (scene.interface_tensions.empty() || scene.surface_tension_model != SurfaceTensionModel::Csf) return;
  const SimConstants& c = s.constants;
  const ParticleState& ps = s.particles;
  const double h = s.h;
  const HostNeighbours neighbours(ps, h, [&](std::size_t a) { return ps.age[a] < kRemovedAge; });
  const KernelCoeffs& k = c.kernel;
  const bool cubic = density_cubic_spline(c);  // the share's kernel (csf_interface_share)
  long meets[kMaxFluids] = {};
  long example[kMaxFluids];
  for (std::size_t a = 0; a < ps.size(); ++a) {
    if (near_walls(c, ps.pos[a]).count > 0) continue;
    double colour = double(c.fluids[ps.fluid[a]].mass) / c.fluids[ps.fluid[a]].rest_density * density_kernel(k, cubic, 0.0f);  // itself
    neighbours.for_each(a, [&](std::size_t b, Vec3 x) {
      const float r2 = dot(x, x);
      if (r2 < k.h2) colour += double(c.fluids[ps.fluid[b]].mass) / c.fluids[ps.fluid[b]].rest_density * density_kernel(k, cubic, r2);
    });
    if (1.0 - colour > kGasDeficit && meets[ps.fluid[a]]++ == 0) example[ps.fluid[a]] = long(a);
  }
  for (std::size_t t = 0; t < scene.interface_tensions.size(); ++t) {
    const InterfaceTensionSpec& it = scene.interface_tensions[t];
    if (meets[it.a] == 0 || meets[it.b] == 0) continue;
    std::ostringstream os;
    os.precision(4);
    const Vec3 xa = ps.pos[std::size_t(example[it.a])], xb = ps.pos[std::size_t(example[it.b])];
    os << scene.source << ": interface_tension." << t << ": under sph.surface_tension = \"csf\" an interface tension "
       << "holds only where at most one of its two fluids meets the gas (a drop of one inside the other, or both in a "
       << "container they fill), and here both do at the start (" << meets[it.a] << " particles of " << fluid_key(std::size_t(it.a))
       << ", e.g. at (" << xa.x << ", " << xa.y << ", " << xa.z << "), and " << meets[it.b] << " of " << fluid_key(std::size_t(it.b))
       << ", e.g. at (" << xb.x << ", " << xb.y << ", " << xb.z << ")): where both meet the gas along a line, two drops "
       << "side by side flew apart (docs/results.md, \"Interface tension under the continuum surface force\"). Use "
       << "sph.surface_tension = \"cohesion\" there, or start one fluid inside the other";
    throw SceneError(os.str());
  }
}

void check_springs(const Scene& scene) {
  for (std::size_t i = 0; i < scene.fluids.size(); ++i) {
    const FluidSpec& f = scene.fluids[i];
    if (!(f.spring_modulus > 0.0)) continue;
    const std::string key = fluid_key(i) + ".spring_modulus";
    std::ostringstream os;
    os << scene.source << ": " << key << ": ";
    if (!scene.initial_state.empty()) {
      os << "springs are made between the particles the emitters create at the start; an initial_state frame holds "
            "no springs (leave one of the two out)";
      throw SceneError(os.str());
    }
    for (std::size_t e = 0; e < scene.emitters.size(); ++e)
      if (scene.emitters[e].type == EmitterType::Jet && scene.emitters[e].fluid == int(i)) {
        os << "springs are made at the start, but emitters." << e << " (jet) creates " << fluid_key(i)
           << " during the run: give the jet a fluid without springs";
        throw SceneError(os.str());
      }
    // WCSPH's step follows the speed of sound; DFSPH's and PBF's have a limit of the springs' own (time_step.h).
    const double limit = kElasticWaveLimit * kElasticWaveLimit * f.rest_density * f.speed_of_sound * f.speed_of_sound;
    if (scene.solver == Solver::Wcsph && f.spring_modulus > limit) {
      os << f.spring_modulus << " Pa makes elastic waves (sqrt(G / rho0) = " << std::sqrt(f.spring_modulus / f.rest_density)
         << " m/s) faster than " << kElasticWaveLimit << " x " << fluid_key(i) << ".speed_of_sound; allowed: at most "
         << limit << " Pa at this speed of sound (or raise the speed of sound)";
      throw SceneError(os.str());
    }
  }
}

}  // namespace sph
