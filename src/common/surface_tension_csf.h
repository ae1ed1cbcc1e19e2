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
//   (csf_surface_curvature);
// - acceleration a_i = sigma kappa_i n_i / (chi rho0) where |n| h is above kCsfNormalFloor, else none
//   (csf_acceleration; rho0, not the summed rho_i, which is small for a particle with few neighbours). chi
//   is the integral of |n| across a flat lattice surface over those layers (csf_band_integral): the
//   particles stand for only part of the smoothed step of the colour, so without it the force per area
//   would be chi sigma kappa, not sigma kappa.
// Not a pair force: the total momentum is conserved only as far as sum_i V_i kappa_i n_i vanishes (to the
// discretisation's error on a closed surface).
#pragma once

#include "grid.h"
#include "kernels.h"
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

SPH_HD inline Vec3 csf_normal(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
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

SPH_HD inline float csf_curvature(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const Vec3 ni = p.surface_normal[i];
  const float len_i = sqrtf(dot(ni, ni));
  if (!(len_i * k.h > kCsfNormalFloor)) return 0.0f;
  const Vec3 ui = (1.0f / len_i) * ni;
  const uint8_t fluid = p.fluid[i];
  float divergence = 0.0f, norm = 0.0f;
  int32_t count = 0;
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3 xij, float r2) {
    if (p.fluid[j] != fluid || r2 <= 0.0f) return;
    const Vec3 nj = p.surface_normal[j];
    const float len_j = sqrtf(dot(nj, nj));
    if (!(len_j * k.h > kCsfNormalFloor)) return;
    ++count;
    const float w = (p.pos_mass[j].w / c.fluids[fluid].rest_density) * poly6_grad_fac(k, r2);  // V_j grad W_ij / x_ij
    divergence += w * dot((1.0f / len_j) * nj - ui, xij);  // V_j (u_j - u_i) . grad W_ij
    norm -= w * r2;                                          // V_j x_ji . grad W_ij
  });
  if (count < kCsfMinNeighbours || !(norm > 0.0f)) return 0.0f;
  float kappa = -2.0f * divergence / norm;
  const float most = kCsfMaxCurvature / k.h;
  kappa = kappa > most ? most : (kappa < -most ? -most : kappa);
  return csf_surface_curvature(kappa, c.fluids[fluid].particle_side);
}

SPH_HD inline Vec3 csf_acceleration(const SimConstants& c, const ParticleView& p, int32_t i) {
  const FluidConstants& f = c.fluids[p.fluid[i]];
  return (f.csf_sigma * p.curvature[i] / f.rest_density) * p.surface_normal[i];
}

// chi of the calibration above, for support h and spacing d [m] and lattice volume d^3 / lattice_density:
// the sum over the layers of a half-infinite cubic lattice of d |n|, n on each layer as csf_normal gives it,
// over the layers whose |n| h is above kCsfNormalFloor (those the force acts on). Dimensionless.
double csf_band_integral(double spacing, double h, double lattice_density);

}  // namespace sph
