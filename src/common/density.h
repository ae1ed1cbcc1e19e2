// Phase "density": density (summation or continuity) and near density of one particle.
// Shared by every back end; the back end decides how the loop over particles is scheduled.
#pragma once

#include "grid.h"
#include "kernels.h"
#include "params.h"
#include "mirror_walls.h"

namespace sph {

// Summation, thesis eq. 2.10: rho_a = sum_b m_b W_poly6(r_ab), the particle itself included.
// Continuity, thesis eq. 2.12: rho_a += dt * sum_b m_b (v_a - v_b) . grad W_ab (grad of Spiky).
// With sph.kernel = cubic_spline both take the cubic spline instead (kernels.h, density_kernel).
// Near density, thesis 3.1: rho_near_a = sum_b m_b W_near(r_ab).
// Several fluids (SimConstants::number_density, [SP08] eq. 5, thesis eq. 3.5): rho_a = m_a delta_a with the
// number density delta_a = sum_b W_ab, i.e. every neighbour counts with a's own mass m_a. Summed with the
// neighbours' masses, a light particle next to a heavy fluid counts the heavy particles' mass as its own and
// sees a density (and, through Tait's seventh power, a pressure) far above its rest value: a water-over-oil
// interface at ratio 10 threw particles at 50 m/s within two steps (issue 15). Boundary particles count as
// rho0_a V_b either way (V_b / V_a particles of a's mass).
// One neighbour's share, real or a wall's ghost (xab = x_a - x_b, vab = v_a - v_b, r2 < h^2).
SPH_HD_ALWAYS_INLINE void density_pair(const SimConstants& c, bool summation, float mb, Vec3 xab, float r2, Vec3 vab,
                                       float& rho, float& rho_near, float& drho) {
  const KernelCoeffs& k = c.kernel;
  const bool cubic = c.cubic_spline != 0;
  if (summation) rho += mb * density_kernel(k, cubic, r2);
  if (c.near_enabled || !summation) {
    const float r = sqrtf(r2);
    if (c.near_enabled) rho_near += mb * near_kernel(k, r);
    if (!summation && r > 0.0f) drho += mb * (gradient_dwdr(k, cubic, r) / r) * dot(vab, xab);
  }
}

// kSummation as a template parameter: each method's loops hold only what it needs (summation no
// velocities, continuity no summed density), which keeps the GPU kernel within 64 registers (issue 11).
template <bool kSummation>
SPH_HD inline void density_with(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t a,
                                float dt) {
  const KernelCoeffs& k = c.kernel;
  const Vec3 xa = xyz(p.pos_mass[a]);
  const float ma = p.pos_mass[a].w;
  const bool number_density = c.number_density != 0;
  float rho = 0.0f, rho_near = 0.0f, drho = 0.0f;
  // The neighbour's position and mass in one record (pos_mass); continuity reads vel_force, the pressure
  // phase's packed velocity being written after this phase.
  for_each_neighbour(grid, p.pos_mass, a, k.h2, [&](int32_t b, Vec3 xab, float r2) {
    const Vec3 vab = kSummation ? Vec3{0.0f, 0.0f, 0.0f} : p.vel_force[a] - p.vel_force[b];
    density_pair(c, kSummation, number_density ? ma : p.pos_mass[b].w, xab, r2, vab, rho, rho_near, drho);
  });
  // Mirror walls: the ghosts of the neighbours, the particle's own included (mirror_walls.h). A second
  // pass, so the loop above stays as lean as without walls.
  const NearWalls walls = c.mirror_walls ? near_walls(c, xa) : NearWalls{};
  for_each_ghost(c, grid, p, walls, a, [&](int32_t b, int32_t image, Vec3 xg, float r2) {
    const Vec3 vab = kSummation ? Vec3{0.0f, 0.0f, 0.0f} : p.vel_force[a] - mirror_velocity(walls, image, p.vel_force[b]);
    density_pair(c, kSummation, number_density ? ma : p.pos_mass[b].w, xa - xg, r2, vab, rho, rho_near, drho);
  });
  // Boundary particles [AIA12] eq. 5: Psi_b = rho0_a V_b in place of a neighbour's mass, static ones at rest.
  if (grid.boundary.n > 0 || grid.num_bodies > 0) {
    const float rho0 = c.fluids[p.fluid[a]].rest_density;
    const Vec3 va = kSummation ? Vec3{0.0f, 0.0f, 0.0f} : p.vel_force[a];
    for_each_boundary(grid.boundary, xa, k.h2, [&](int32_t, Vec3 xab, float r2, float volume) {
      density_pair(c, kSummation, rho0 * volume, xab, r2, va, rho, rho_near, drho);
    });
    // Rigid bodies' particles: the same, moving with their body (continuity: v_a - v_b).
    for_each_body_particle(grid.bodies, grid.num_bodies, xa, k.h2, [&](int32_t, int32_t, Vec3 xab, float r2, float volume, Vec3 vb) {
      density_pair(c, kSummation, rho0 * volume, xab, r2, va - vb, rho, rho_near, drho);
    });
  }
  p.density[a] = kSummation ? rho : p.density[a] + dt * drho;
  p.near_density[a] = rho_near;
}

SPH_HD inline void density_of(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t a,
                              float dt) {
  if (c.density == DensityMethod::Summation)
    density_with<true>(c, grid, p, a, dt);
  else
    density_with<false>(c, grid, p, a, dt);
}

}  // namespace sph
