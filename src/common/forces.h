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

// Pressure (and near pressure) pair term, returned as the scalar s with a_a += s * grad W; takes the
// inverse densities so the pair loop divides once per pair.
// Monaghan symmetric, thesis eq. 2.18 divided by rho_a: -m_b (P_a / rho_a^2 + P_b / rho_b^2).
// Mueller, thesis eq. 2.19 divided by rho_a: -m_b (P_a + P_b) / (2 rho_a rho_b).
SPH_HD inline float pressure_pair(PressureForm form, float mb, float pa, float inv_rhoa, float pb, float inv_rhob) {
  if (form == PressureForm::MonaghanSymmetric) return -mb * (pa * inv_rhoa * inv_rhoa + pb * inv_rhob * inv_rhob);
  return -0.5f * mb * (pa + pb) * inv_rhoa * inv_rhob;
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
  const float pa = p.pressure[a];
  const float pna = p.near_pressure[a];
  const float eps2 = 0.01f * k.h2;  // keeps Morris and artificial viscosity finite as r -> 0
  Vec3 acc{0.0f, 0.0f, 0.0f};
  Vec3 dv{0.0f, 0.0f, 0.0f};
  // One neighbour, real or a wall's ghost: pressure, near pressure and viscosity; for real neighbours
  // also surface tension and XSPH.
  auto pair = [&](const FluidConstants& fb, Vec3 xab, float r2, Vec3 vb, float rhob, float pb, float pnb, bool real) {
    const float r = sqrtf(r2);
    const float inv_r = 1.0f / r;
    const float mb = fb.mass;
    const float inv_rhob = 1.0f / rhob;
    const Vec3 vab = va - vb;
    const float grad = spiky_dwdr(k, r) * inv_r;  // grad W_ab = grad * xab

    float s = pressure_pair(c.pressure_form, mb, pa, inv_rhoa, pb, inv_rhob) * grad;
    if (c.near_enabled)  // double density relaxation, thesis 3.1: near pressures on the sharper kernel
      s += pressure_pair(c.pressure_form, mb, pna, inv_rhoa, pnb, inv_rhob) * near_dwdr(k, r) * inv_r;

    switch (c.viscosity) {
      case ViscosityModel::Mueller:  // thesis eq. 2.24 / rho_a: mu sum m_b (v_b - v_a)/rho_b lap W / rho_a
        acc -= (fa.viscosity * mb * viscosity_laplacian(k, r) * inv_rhoa * inv_rhob) * vab;
        break;
      case ViscosityModel::Morris:  // Morris 1997: sum m_b (mu_a + mu_b)/(rho_a rho_b) (x_ab.gradW)/(r^2+eps^2) v_ab
        acc += (mb * (fa.viscosity + fb.viscosity) * grad * r2 * inv_rhoa * inv_rhob / (r2 + eps2)) * vab;
        break;
      case ViscosityModel::Artificial: {  // thesis eq. 2.20-2.22 (beta = 0), approaching pairs only
        const float vx = dot(vab, xab);
        if (vx < 0.0f) {
          const float mu_ab = k.h * vx / (r2 + eps2);
          const float alpha = 0.5f * (fa.artificial_alpha + fb.artificial_alpha);
          const float cbar = 0.5f * (fa.speed_of_sound + fb.speed_of_sound);
          const float pi_ab = -alpha * cbar * mu_ab / (0.5f * (rhoa + rhob));
          s -= mb * pi_ab * grad;
        }
        break;
      }
      case ViscosityModel::None:
        break;
    }
    acc += s * xab;
    if (!real) return;

    if (c.surface_tension_enabled) {  // Becker & Teschner 2007 cohesion, thesis eq. 3.12
      const float kappa = 0.5f * (fa.cohesion + fb.cohesion);
      acc -= (kappa * mb / fa.mass * poly6(k, r2)) * xab;
    }
    if (c.xsph_enabled) {  // XSPH [Monaghan 1989]: v_a += eps sum m_b / rho_ab (v_b - v_a) W_ab
      dv -= (fa.xsph * mb * poly6(k, r2) / (0.5f * (rhoa + rhob))) * vab;
    }
  };
  const NearWalls walls = c.mirror_walls ? near_walls(c, xa) : NearWalls{};
  for_each_candidate(grid, xa, [&](int32_t b) {
    const Vec3 xb = p.pos[b];
    const float r2 = length2(xa - xb);
    if (r2 >= k.h2) return;  // then no ghost of b is within h either
    const FluidConstants& fb = c.fluids[p.fluid[b]];
    const Vec3 vb = p.vel_force[b];
    const float rhob = p.density[b];
    const float pb = p.pressure[b];
    const float pnb = p.near_pressure[b];
    // r2 = 0: the particle itself, or a coincident one, which has no direction to push along.
    if (r2 > 0.0f) pair(fb, xa - xb, r2, vb, rhob, pb, pnb, true);
    if (walls.count > 0)
      for_each_mirror(walls, xb, vb, [&](Vec3 xg, Vec3 vg) {
        const float rg2 = length2(xa - xg);
        if (rg2 < k.h2 && rg2 > 0.0f) pair(fb, xa - xg, rg2, vg, rhob, ghost_pressure(c, pb, rhob, xb, xg), pnb, false);
      });
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
