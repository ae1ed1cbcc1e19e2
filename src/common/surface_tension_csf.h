// Surface tension as a continuum surface force (CSF: Brackbill, Kothe & Zemach 1992; in SPH Morris 2000), the
// scene's sph.surface_tension = "csf": a force per volume -sigma kappa N delta_s on the fluid's surface, with
// sigma in N/m, kappa = div N the mean curvature (2 / R on a sphere) and N the outward unit normal. Only the
// surface band feels it, so the bulk carries no more than the Laplace pressure 2 sigma / R (the cohesion
// model, forces.h, makes the bulk hold an internal pressure of 8.23 sigma / h, 20 to 40 times that, and a drop
// then settles like an elastic solid: docs/results.md).
//
// Per particle, over the neighbours of its own fluid, V_j = m_j / rho0_j:
// - colour gradient n_i = sum_j V_j grad W_ij (Poly6), pointing into the fluid, |n| ~ delta_s at the surface
//   and ~0 inside (csf_normal);
// - curvature kappa_i = -div(n / |n|) over the neighbours with a normal (|n| h above kCsfNormalFloor),
//   normalised for the neighbours there are: -2 sum_j V_j (u_j - u_i) . grad W_ij / sum_j V_j x_ji . grad W_ij,
//   u = n / |n| (csf_curvature). The 2, not the 3 of a divergence in the bulk: the neighbours with a normal
//   form a nearly flat band, whose sum x_ji . grad W holds the two directions along the surface, in which u
//   turns, and little of the third (with 3 a sphere read 1.6 times 2 / R; projecting on the tangent plane
//   instead divided by nearly zero for particles whose band lay along their normal, and threw them off),
//   then moved from the particles' outer layer out to the surface half a spacing beyond it
//   (csf_surface_curvature); and kept within half of its neighbours' mean estimate, so that one particle's
//   noisy reading cannot push it off the surface (csf_limited_curvature);
// - acceleration a_i = sigma kappa_i n_i / (chi rho0) where |n| h is above kCsfNormalFloor, else none
//   (csf_acceleration; rho0, not the summed rho_i, which is small for a particle with few neighbours). chi
//   is the integral of |n| across a flat lattice surface over those layers (csf_band_integral): the
//   particles stand for only part of the smoothed step of the colour, so without it the force per area
//   would be chi sigma kappa, not sigma kappa.
// Not a pair force: the total momentum is conserved only as far as sum_i V_i kappa_i n_i vanishes (to the
// discretisation's error on a closed surface).
//
// Walls under a contact angle theta (fluids.N.contact_angle): the surface must meet a wall at theta [BKZ92,
// "wall adhesion"]. Here the fluid is continued through the walls within h (mirror_walls.h: faces of box
// containers, planes and sphere containers, whatever sph.walls is; obstacles and bodies have none) by images
// that continue a surface meeting the wall at theta straight through it, and the colour gradient and the
// curvature read those images as neighbours. A surface meeting the wall at another angle then shows a kink
// at the wall, read as curvature, whose force moves the contact line towards theta; a wetted wall is no
// surface (a particle resting on the floor has |n| ~ 0 as in the bulk). The image of x, at height y =
// n.x - offset above a wall of normal n (into the fluid), is x - 2 y n + 2 y cot(theta) t, t the unit vector
// along the wall away from the fluid (from the particle's normal): the reflection sheared along t, which
// maps the half-space behind a plane meeting the wall at theta onto its own continuation (at 90 degrees the
// plain mirror image). Normals map by the transpose of that map: u -> u - 2 (u.n) n + 2 cot(theta) (u.t) n.
// theta is measured inside the liquid, between the wall and the surface:
//
//        gas      /  surface, outward normal m = n cos(theta) + t sin(theta)
//                /
//      liquid   / theta
//   ===========+=========== wall          n: the wall's normal, up into the fluid
//              contact line  --> t        t: along the wall, away from the liquid
//
// Two fluids with an interface tension sigma_ab (scene key interface_tension): the colour above counts a
// particle's own fluid, so it reads the other fluid as a free surface, and without more the two would meet
// with sigma_a + sigma_b. So each particle takes its share s of the surface it stands at that is the other
// fluid's rather than the gas's, from the colour values c = sum_j V_j W_ij over its own fluid (itself
// included) and over the other: s = c_other / (1 - c_own), within [0, 1] (csf_interface_share). W is the
// solver's density kernel (DFSPH's cubic spline, WCSPH's Poly6 or sph.kernel's), whose sum over both fluids the pressure
// holds at 1. The force takes the tension (1 - s) sigma + s sigma_ab (csf_interface_acceleration), the
// interface's part only where the interface is convex seen from the particle's fluid (curvature > 0), so it
// points into the particle's own fluid. Walls, which the colours do not count, read as gas.
// Measured (docs/results.md, "Interface tension under the continuum surface force"):
// - a force on the concave side pushes that side's particles into the other fluid, which, as a heavy layer
//   over a light one under gravity, mixes the two: with sigma_ab / 2 on each side, or all of it on the
//   concave side, a drop's jump fell to 0.3 to 0.6 of Laplace's and its fluid spread into the other. The
//   convex side alone holds it; at an inflexion the curvature, and with it the force, goes to zero on both
//   sides, so the switch is continuous;
// - the share is read from colour values with the density's kernel, not from gradients: under DFSPH two
//   fluids at an interface pack in shells about 1.4 spacings apart, where the other fluid's colour gradient
//   reads half a free surface's, and Poly6's colours sum to 0.95 while the cubic spline reads rho0 (s was
//   0.45 instead of 1).
//
// Where two or three walls are within h (an edge, a corner) the images are the plain mirror images (90
// degrees), and where a particle's normal lies within kCsfContactTangentFloor of the wall's normal (a
// surface along the wall, no contact line) there is no shear; the shear switches on at that floor in one
// step, not by a ramp (an angle of 6 degrees between the surface and the wall, where contact lines at 60 to
// 120 degrees never are). Only the neighbours within h are imaged, while the shear can bring a particle from
// up to about 1.7 h to within h: at 60 degrees that misses about 3% of the images' weight at the contact line
// (on a lattice wedge), none from 75 to 120 degrees. Validated with mirror walls and boundary particles
// (docs/results.md), refused with penalty walls.
#pragma once

#include "grid.h"
#include "kernels.h"
#include "mirror_walls.h"
#include "params.h"
#include "particle_view.h"

namespace sph {

// Particles whose |n| h is below this have no normal: no curvature, no force, and they take no part in the
// curvature sums. On a flat lattice surface |n| h is about 0.8 on the outer layer and 0.25 on the next; in a
// settled drop's disordered bulk it is noise of 0.07 to 0.12 (measured), whose random directions, counted in
// the sums with a floor of 0.05, made a drop's surface read 3.4 times its curvature.
constexpr float kCsfNormalFloor = 0.5f;
// A curvature needs this many neighbours with a normal (a particle flung off alone has none it can trust), and
// is kept within +-kCsfMaxCurvature / h (a drop of radius h / 2). Without these, a particle leaving a drop read
// a curvature of the wrong sign from its two or three neighbours and was thrown off at 5 m/s (measured).
constexpr int32_t kCsfMinNeighbours = 6;
// csf_curvature's value for a particle without an estimate of its own (no normal, or too few neighbours
// with one); csf_limited_curvature skips it.
constexpr float kCsfNoCurvature = 3.0e38f;
constexpr float kCsfMaxCurvature = 4.0f;

// The curvature of the fluid's surface from that of the particles' outer layer, kappa_p (2 / r_p on a sphere of
// particles): the surface lies half a spacing d beyond the particle centres (as the emitters lay a block out,
// and as a settled drop shows: its outer layer at r_p = 0.0577 m, the ball of its volume R = 0.0619 m, d =
// 0.0083 m), so 2 / R = 2 / (2 / kappa_p + d / 2) = kappa_p / (1 + kappa_p d / 4). Either sign (a concave
// surface lies closer to its centre of curvature than the particles). The shell picture holds only where the
// radius of curvature spans several spacings: the divisor's kappa_p is kept within +-kCsfOffsetMaxCurvature / d
// (a radius of 4 d), so at a corner it stays within 0.875 to 1.125. Measured (docs/results.md): a box's l = 2
// period from 12% short of Rayleigh's to 3% (12 across) and 8% (14 across); without the bound 6 of a cube's
// corner particles were thrown off at 12 across, with it none at 10, 12 and 14 across.
constexpr float kCsfOffsetMaxCurvature = 0.5f;
SPH_HD inline float csf_surface_curvature(float kappa_p, float spacing) {
  const float most = kCsfOffsetMaxCurvature / spacing;
  const float bounded = kappa_p > most ? most : (kappa_p < -most ? -most : kappa_p);
  return kappa_p / (1.0f + 0.25f * bounded * spacing);
}

// The contact angles the wall condition is measured to hold, in degrees (docs/results.md, "Contact angle"):
// below 60 the spreading film sheds a third of a drop at 45, above 120 a drop released as a cube leaves the
// floor (at 135 and 150). Others are refused at set-up (scene_fluids.cpp).
constexpr double kCsfContactAngleMin = 60.0;
constexpr double kCsfContactAngleMax = 120.0;

// Below this part along the wall of a particle's unit normal (the sine of its angle to the wall's normal: 6
// degrees) its surface runs along the wall, with no contact line: no shear (above).
constexpr float kCsfContactTangentFloor = 0.1f;

// The one wall within h of a particle, for its images (above): on = 0 where there is none or more than one.
struct CsfWallFrame {
  int32_t on;
  Vec3 normal;   // n, unit, into the fluid
  float offset;  // the wall is n.x = offset
  Vec3 shear;    // 2 cot(theta) t [-], 0 without a contact line
};

// The frame of a particle with inward unit normal u (or 0 without a normal) among `walls`.
SPH_HD inline CsfWallFrame csf_wall_frame(const FluidConstants& f, const NearWalls& walls, Vec3 u) {
  CsfWallFrame w{0, Vec3{0.0f, 0.0f, 0.0f}, 0.0f, Vec3{0.0f, 0.0f, 0.0f}};
  if (walls.count != 1) return w;
  w.on = 1;
  w.normal = walls.normal[0];
  w.offset = walls.offset[0];
  const Vec3 along = dot(u, w.normal) * w.normal - u;  // the outward normal's part along the wall
  const float length_along = sqrtf(dot(along, along));
  if (length_along > kCsfContactTangentFloor) w.shear = (2.0f * f.csf_contact_cot / length_along) * along;
  return w;
}

SPH_HD inline Vec3 csf_image_position(const CsfWallFrame& w, Vec3 x) {
  const float y = dot(x, w.normal) - w.offset;
  return x - (2.0f * y) * w.normal + y * w.shear;
}

// The image of a normal (any length), by the transpose of the map of positions.
SPH_HD inline Vec3 csf_image_normal(const CsfWallFrame& w, Vec3 u) {
  return u + (dot(u, w.shear) - 2.0f * dot(u, w.normal)) * w.normal;
}

// The colour gradient from the particle's neighbours of its own fluid, without images.
SPH_HD inline Vec3 csf_fluid_normal(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const uint8_t fluid = p.fluid[i];
  Vec3 n{0.0f, 0.0f, 0.0f};
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3 xij, float r2) {
    if (p.fluid[j] != fluid || r2 <= 0.0f) return;
    const float volume = p.pos_mass[j].w / c.fluids[fluid].rest_density;
    n += (volume * poly6_grad_fac(k, r2)) * xij;
  });
  return n;
}

// The colour gradient n: from the neighbours of the particle's own fluid, and under a contact angle also
// from their plain mirror images across the walls within h (the first of two passes: the second,
// csf_contact_normal, shears the images along the direction this one gives).
SPH_HD inline Vec3 csf_normal(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  Vec3 n = csf_fluid_normal(c, grid, p, i);
  const uint8_t fluid = p.fluid[i];
  if (!c.fluids[fluid].csf_contact) return n;
  const Vec3 xi = xyz(p.pos_mass[i]);
  const float rho0 = c.fluids[fluid].rest_density;
  for_each_ghost(c, grid, p, near_walls(c, xi), i, [&](int32_t j, int32_t, Vec3 xg, float r2) {
    if (p.fluid[j] != fluid || r2 <= 0.0f) return;
    n += (p.pos_mass[j].w / rho0 * poly6_grad_fac(c.kernel, r2)) * (xi - xg);
  });
  return n;
}

// The second pass under a contact angle, for a particle with a normal at one wall: the colour gradient with
// the images sheared along the wall (above), the direction t from the first pass's normal. Elsewhere the
// first pass's n. It reads no other particle's normal, so it may overwrite surface_normal in place.
SPH_HD inline Vec3 csf_contact_normal(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const Vec3 first = p.surface_normal[i];
  const uint8_t fluid = p.fluid[i];
  const FluidConstants& f = c.fluids[fluid];
  const float len = sqrtf(dot(first, first));
  if (!f.csf_contact || !(len * k.h > kCsfNormalFloor)) return first;
  const Vec3 xi = xyz(p.pos_mass[i]);
  const CsfWallFrame w = csf_wall_frame(f, near_walls(c, xi), (1.0f / len) * first);
  if (!w.on) return first;
  Vec3 n = csf_fluid_normal(c, grid, p, i);
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3, float) {
    if (p.fluid[j] != fluid) return;
    const Vec3 xij = xi - csf_image_position(w, xyz(p.pos_mass[j]));
    const float r2 = dot(xij, xij);
    if (!(r2 < k.h2) || r2 <= 0.0f) return;
    n += (p.pos_mass[j].w / f.rest_density * poly6_grad_fac(k, r2)) * xij;
  });
  return n;
}

SPH_HD inline float csf_curvature(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const Vec3 ni = p.surface_normal[i];
  const float len_i = sqrtf(dot(ni, ni));
  if (!(len_i * k.h > kCsfNormalFloor)) return kCsfNoCurvature;
  const Vec3 ui = (1.0f / len_i) * ni;
  const uint8_t fluid = p.fluid[i];
  const FluidConstants& f = c.fluids[fluid];
  float divergence = 0.0f, norm = 0.0f;
  int32_t count = 0;
  // V_j (u_j - u_i) . grad W_ij and V_j x_ji . grad W_ij of one neighbour (or image) at x_ij with colour
  // gradient n_j, if it has a normal (|n_j| h above the floor). An image's colour gradient is its source's
  // mapped by the transpose of the map, length included (the gradient of the colour composed with the map),
  // so the floor is taken on the mapped vector: sheared at 60 degrees an n_j along t is 1.53 times longer.
  // (Taken on the source's n_j instead, the 60-degree drop of contact_angle shed 4.6% of its particles
  // instead of 2.8%.)
  auto add = [&](Vec3 nj, Vec3 xij, float r2, float volume) {
    const float len_j = sqrtf(dot(nj, nj));
    if (!(len_j * k.h > kCsfNormalFloor)) return;
    ++count;
    const float w = volume * poly6_grad_fac(k, r2);  // V_j grad W_ij / x_ij
    divergence += w * dot((1.0f / len_j) * nj - ui, xij);
    norm -= w * r2;
  };
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3 xij, float r2) {
    if (p.fluid[j] != fluid || r2 <= 0.0f) return;
    add(p.surface_normal[j], xij, r2, p.pos_mass[j].w / f.rest_density);
  });
  if (f.csf_contact) {  // the images across the walls (above)
    const Vec3 xi = xyz(p.pos_mass[i]);
    const NearWalls walls = near_walls(c, xi);
    const CsfWallFrame w = csf_wall_frame(f, walls, ui);
    if (w.on) {  // one wall: sheared images
      for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3, float) {
        if (p.fluid[j] != fluid) return;
        const Vec3 xij = xi - csf_image_position(w, xyz(p.pos_mass[j]));
        const float r2 = dot(xij, xij);
        if (r2 < k.h2 && r2 > 0.0f) add(csf_image_normal(w, p.surface_normal[j]), xij, r2, p.pos_mass[j].w / f.rest_density);
      });
    } else {  // an edge or a corner: mirror images
      for_each_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t image, Vec3 xg, float r2) {
        if (p.fluid[j] != fluid || r2 <= 0.0f) return;
        add(mirror_direction(walls, image, p.surface_normal[j]), xi - xg, r2, p.pos_mass[j].w / f.rest_density);
      });
    }
  }
  if (count < kCsfMinNeighbours || !(norm > 0.0f)) return kCsfNoCurvature;
  float kappa = -2.0f * divergence / norm;
  const float most = kCsfMaxCurvature / k.h;
  kappa = kappa > most ? most : (kappa < -most ? -most : kappa);
  return csf_surface_curvature(kappa, f.particle_side);
}

// The curvature the force uses (curvature): each particle's own estimate (csf_curvature, in curvature_own) kept
// within kCsfCurvatureSpread of its neighbours' mean, the mean of the estimates of the neighbours of its fluid
// that made one, itself left out, with Poly6 weights m_j W_ij; a particle with a normal but no estimate of its
// own takes that mean. 0 for a particle without a normal; its own estimate where no neighbour made one; with
// c.csf_curvature_spread < 0 (tests only) the own estimate alone, as before this limit.
// Why: curvature is a second derivative of the colour, and one particle's estimate is noisy where its surface
// is rough on the scale of a spacing. Tracked on a 20-across cube under DFSPH (docs/results.md, "The
// curvature's limit"): a face particle standing out of its bulging face by part of a spacing read -49 1/m
// from its neighbours with a normal, each of which read +44 to +91; the force of the wrong sign pushed it
// out, and once fewer than kCsfMinNeighbours of its neighbours had a normal it got no force at all and left
// the drop (54 to 69 of the 8,000 particles by 0.4 s). With the limit it reads at least half its neighbours'
// convex surface, and a particle with too few neighbours for an estimate of its own takes theirs and is
// pulled back: none left. A plain average in place of the limit (a Shepard filter, or half the own estimate
// and half the mean) also kept the drop whole but let the particle-scale roughness that it no longer
// answers grow, which the estimates read as curvature: the jump across the interface drop rose from 1.12
// to 1.16 to 1.18 of Laplace's. A wider bound above (up to 3 times the mean) held the tips a ringing cube
// draws out of its face centres, which this one lets go (13, 13 and 24 particles at 16, 18 and 22 across
// under DFSPH; none from 12 to 24 across with it), but WCSPH's Poly6 and Spiky box then rang 12% short of
// Rayleigh's period (17% with 2 times the mean; 5.6% with this bound, 2.9% before it; its test asks 10%).
constexpr float kCsfCurvatureSpread = 0.5f;

// Whether particle i has a normal (|n| h above kCsfNormalFloor): the particles the force acts on.
SPH_HD inline bool csf_has_normal(const SimConstants& c, const ParticleView& p, int32_t i) {
  const Vec3 ni = p.surface_normal[i];
  return sqrtf(dot(ni, ni)) * c.kernel.h > kCsfNormalFloor;
}

SPH_HD inline float csf_limited_curvature(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                          int32_t i) {
  const KernelCoeffs& k = c.kernel;
  if (!csf_has_normal(c, p, i)) return 0.0f;  // no normal, as csf_curvature reads it
  const float own = p.curvature_own[i];
  const float own_or_none = own == kCsfNoCurvature ? 0.0f : own;
  if (c.csf_curvature_spread < 0.0f) return own_or_none;
  const uint8_t fluid = p.fluid[i];
  float sum = 0.0f, weight = 0.0f;
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3, float r2) {
    const float kappa = p.curvature_own[j];
    if (j == i || p.fluid[j] != fluid || kappa == kCsfNoCurvature) return;
    const float w = p.pos_mass[j].w * poly6(k, r2);
    sum += w * kappa;
    weight += w;
  });
  if (!(weight > 0.0f)) return own_or_none;
  const float mean = sum / weight;
  if (own == kCsfNoCurvature) return mean;
  const float spread = c.csf_curvature_spread * fabsf(mean);
  return own > mean + spread ? mean + spread : (own < mean - spread ? mean - spread : own);
}

SPH_HD inline Vec3 csf_acceleration(const SimConstants& c, const ParticleView& p, int32_t i) {
  const FluidConstants& f = c.fluids[p.fluid[i]];
  return (f.csf_sigma * p.curvature[i] / f.rest_density) * p.surface_normal[i];
}

// s of the interface tension (above): the share of particle i's missing colour that the other fluid fills.
SPH_HD inline float csf_interface_share(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const uint8_t fluid = p.fluid[i];
  const float rho0 = c.fluids[fluid].rest_density;
  // The solver's density kernel, with which its pressure holds the sum of both colours at 1 across the interface.
  const bool cubic = density_cubic_spline(c);
  float own = 0.0f, other = 0.0f;
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3, float r2) {
    const float w = density_kernel(k, cubic, r2);
    if (p.fluid[j] == fluid) own += p.pos_mass[j].w / rho0 * w;
    else other += p.pos_mass[j].w / c.fluids[p.fluid[j]].rest_density * w;
  });
  const float missing = 1.0f - own;
  if (!(other > 0.0f)) return 0.0f;
  return other >= missing ? 1.0f : other / missing;
}

// The acceleration [m/s^2] of a particle of a fluid with an interface tension (above).
SPH_HD inline Vec3 csf_interface_acceleration(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                              int32_t i) {
  const FluidConstants& f = c.fluids[p.fluid[i]];
  const float kappa = p.curvature[i];
  if (kappa == 0.0f) return Vec3{0.0f, 0.0f, 0.0f};
  const float s = csf_interface_share(c, grid, p, i);
  const float sigma = (1.0f - s) * f.csf_sigma + (kappa > 0.0f ? s * f.csf_interface_sigma : 0.0f);
  return (sigma * kappa / f.rest_density) * p.surface_normal[i];
}

// chi of the calibration above, for support h and spacing d [m] and lattice volume d^3 / lattice_density:
// the sum over the layers of a half-infinite cubic lattice of d |n|, n on each layer as csf_normal gives it,
// over the layers whose |n| h is above kCsfNormalFloor (those the force acts on). Dimensionless.
double csf_band_integral(double spacing, double h, double lattice_density);

}  // namespace sph
