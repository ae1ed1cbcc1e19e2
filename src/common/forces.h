// Phase "forces": acceleration of one particle from pressure and near pressure, viscosity, surface
// tension and external forces; also the XSPH velocity correction when enabled. Every pair term is written
// so that the pair (a, b) and the pair (b, a) give equal and opposite momentum changes for equal masses
// and viscosities (tests/test_conservation.cpp). With mirror walls the ghosts of the neighbours add
// pressure, near pressure and viscosity (mirror_walls.h); the walls then take up momentum.
#pragma once

#include "grid.h"
#include "kernels.h"
#include "mirror_walls.h"
#include "params.h"

namespace sph {

// eps^2 / h^2 of the pair terms that divide by r^2 + eps^2 (Morris and artificial viscosity): keeps them finite
// as r -> 0.
constexpr float kPairEps2 = 0.01f;

// Pressure (and near pressure) pair term, returned as the scalar s with a_a += s * grad W; takes the
// inverse densities so the pair loop divides once per pair.
// Monaghan symmetric, thesis eq. 2.18 divided by rho_a: -m_b (P_a / rho_a^2 + P_b / rho_b^2).
// Mueller, thesis eq. 2.19 divided by rho_a: -m_b (P_a + P_b) / (2 rho_a rho_b).
SPH_HD inline float pressure_pair(PressureForm form, float mb, float pa, float inv_rhoa, float pb, float inv_rhob) {
  if (form == PressureForm::MonaghanSymmetric) return -mb * (pa * inv_rhoa * inv_rhoa + pb * inv_rhob * inv_rhob);
  return -0.5f * mb * (pa + pb) * inv_rhoa * inv_rhob;
}

// The pair terms a particle a gets from a neighbour b or from a wall's ghost of b: pressure, near pressure
// and viscosity, added to acc. xab = x_a - x_b, vab = v_a - v_b, 0 < r2 < h^2.
struct PairSide {  // what the pair needs of one side
  const FluidConstants* fluid;
  float rho, inv_rho, pressure, near_pressure;
};

SPH_HD_ALWAYS_INLINE void pressure_viscosity_pair(const SimConstants& c, const PairSide& a, const PairSide& b, Vec3 xab,
                                                  float r2, Vec3 vab, Vec3& acc) {
  const KernelCoeffs& k = c.kernel;
  const float eps2 = kPairEps2 * k.h2;
  const float r = sqrtf(r2);
  const float inv_r = 1.0f / r;
  const FluidConstants& fa = *a.fluid;
  const FluidConstants& fb = *b.fluid;
  const float mb = fb.mass;
  const float grad = spiky_dwdr(k, r) * inv_r;  // grad W_ab = grad * xab

  float s = pressure_pair(c.pressure_form, mb, a.pressure, a.inv_rho, b.pressure, b.inv_rho) * grad;
  if (c.near_enabled)  // double density relaxation, thesis 3.1: near pressures on the sharper kernel
    s += pressure_pair(c.pressure_form, mb, a.near_pressure, a.inv_rho, b.near_pressure, b.inv_rho) * near_dwdr(k, r) * inv_r;

  switch (c.viscosity) {  // the laminar viscosity of the fluids' mu
    case ViscosityModel::Mueller:  // thesis eq. 2.24 / rho_a: mu sum m_b (v_b - v_a)/rho_b lap W / rho_a
      acc -= (fa.viscosity * mb * viscosity_laplacian(k, r) * a.inv_rho * b.inv_rho) * vab;
      break;
    case ViscosityModel::Morris:  // Morris 1997: sum m_b (mu_a + mu_b)/(rho_a rho_b) (x_ab.gradW)/(r^2+eps^2) v_ab
      acc += (mb * (fa.viscosity + fb.viscosity) * grad * r2 * a.inv_rho * b.inv_rho / (r2 + eps2)) * vab;
      break;
    case ViscosityModel::Artificial:
    case ViscosityModel::None:
      break;
  }
  if (c.artificial_enabled) {  // thesis eq. 2.20-2.22 (beta = 0), approaching pairs only
    const float vx = dot(vab, xab);
    if (vx < 0.0f) {
      const float mu_ab = k.h * vx / (r2 + eps2);
      const float alpha = 0.5f * (fa.artificial_alpha + fb.artificial_alpha);
      const float cbar = 0.5f * (fa.speed_of_sound + fb.speed_of_sound);
      const float pi_ab = -alpha * cbar * mu_ab / (0.5f * (a.rho + b.rho));
      s -= mb * pi_ab * grad;
    }
  }
  acc += s * xab;
}

SPH_HD inline void forces_of(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t a) {
  if (p.age[a] < 0.0f) {  // inlet particle: kinematic until it leaves the inlet (thesis 4.1.6)
    p.acc[a] = Vec3{0.0f, 0.0f, 0.0f};
    if (c.xsph_enabled) p.xsph_dv[a] = Vec3{0.0f, 0.0f, 0.0f};
    return;
  }
  const KernelCoeffs& k = c.kernel;
  const FluidConstants& fa = c.fluids[p.fluid[a]];
  const Vec3 xa = p.pos[a];
  const Vec3 va = p.vel_force[a];
  const float rhoa = p.density[a];
  const float inv_rhoa = 1.0f / rhoa;
  const PairSide side_a{&fa, rhoa, inv_rhoa, p.pressure[a], p.near_pressure[a]};
  Vec3 acc{0.0f, 0.0f, 0.0f};
  Vec3 dv{0.0f, 0.0f, 0.0f};
  for_each_neighbour(grid, p.pos, a, k.h2, [&](int32_t b, Vec3 xab, float r2) {
    // r2 = 0: the particle itself, or a coincident one, which has no direction to push along.
    if (r2 <= 0.0f) return;
    const FluidConstants& fb = c.fluids[p.fluid[b]];
    const float rhob = p.density[b];
    const Vec3 vab = va - p.vel_force[b];
    pressure_viscosity_pair(c, side_a, PairSide{&fb, rhob, 1.0f / rhob, p.pressure[b], p.near_pressure[b]}, xab, r2, vab, acc);
    const float mb = fb.mass;
    if (c.surface_tension_enabled) {  // Becker & Teschner 2007 cohesion, thesis eq. 3.12
      const float kappa = 0.5f * (fa.cohesion + fb.cohesion);
      acc -= (kappa * mb / fa.mass * poly6(k, r2)) * xab;
    }
    if (c.xsph_enabled) {  // XSPH [Monaghan 1989]: v_a += eps sum m_b / rho_ab (v_b - v_a) W_ab
      dv -= (fa.xsph * mb * poly6(k, r2) / (0.5f * (rhoa + rhob))) * vab;
    }
  });
  // Mirror walls: the ghosts of the neighbours, the particle's own included, add pressure, near pressure and
  // viscosity (mirror_walls.h). A second pass, so the loop above stays as lean as without walls.
  const NearWalls walls = c.mirror_walls ? near_walls(c, xa) : NearWalls{};
  for_each_ghost(c, grid, p, walls, a, [&](int32_t b, int32_t image, Vec3 xg, float r2) {
    if (r2 <= 0.0f) return;  // a ghost on the particle itself: no direction to push along
    const Vec3 vg = mirror_velocity(walls, image, p.vel_force[b]);
    const float rhob = p.density[b];
    const PairSide ghost{&c.fluids[p.fluid[b]], rhob, 1.0f / rhob, ghost_pressure(c, p.pressure[b], rhob, p.pos[b], xg),
                         p.near_pressure[b]};
    const Vec3 xag = xa - xg;
    Vec3 pair{0.0f, 0.0f, 0.0f};
    pressure_viscosity_pair(c, side_a, ghost, xag, r2, va - vg, pair);
    acc += push_only(walls, xg, pair);
  });
  acc += c.gravity;  // external forces, thesis eq. 2.25
  if (c.user_force.strength != 0.0f) {
    const Vec3 to_point = c.user_force.point - xa;
    const float dist = length(to_point);
    if (dist < c.user_force.radius && dist > 0.0f)
      acc += (c.user_force.strength * (1.0f - dist / c.user_force.radius) / dist) * to_point;
  }
  p.acc[a] = acc;
  if (c.xsph_enabled) p.xsph_dv[a] = dv;
}

}  // namespace sph
