// Per-particle formulas of Divergence-Free SPH [BK15] (Bender & Koschier 2015, reproduced in seed 000, whose
// equation numbers are cited: "seed eq. N"). The solver phases (issue 12) call them in their loops over
// particles (src/solvers/dfsph.h); they read the particle and grid views, and the arrays of velocities and
// stiffnesses they are given. Each returns its value: the phase stores it.
//
// Kernel: the cubic spline (kernels.h, support h) for W and grad W alike by default, as [BK15] (seed 3.4: the
// density and its rate must use one kernel for the predictions and corrections to agree); or, where the scene
// asks for it (sph.kernel = "poly6_spiky", SimConstants::dfsph_poly6_spiky), Poly6 for W with Spiky's grad W,
// WCSPH's pair [Mueller 2003]. Why the option: a particle lattice held by one kernel resists a small shear as
// a crystal does (to shear it, particles must pass through compressed places), so a weak flow stalls as if the
// fluid had a yield stress; the pair, whose density and gradient disagree a little, melts it. Measured
// (2026-12-03, the rayleigh_taylor slab, 0.01 m deep; docs/results.md, "DFSPH's kernel"): the interface over
// its start at 0.2 s 1.63 with the cubic spline, 3.14 with the pair, linear theory 3.86 (WCSPH 3.08); the
// oil_drop rose at 0.189 m/s with the cubic spline, 0.238 with the pair (WCSPH 0.240). The
// pair's cost: a resting column rings more (rms 4.4 against 0.04 mm/s with warm_start_fraction 0.75) and the
// prediction and the next step's density disagree by the kernels' difference, so it is not the default.
// Neighbours: every particle
// within h (for_each_neighbour, the particle itself included); the particle itself, and any particle at the
// same position, adds W but no gradient (there is no direction). Positions and masses come from the grid
// phase's packed records (pos_mass).
//
// Walls: with mirror walls (sph.walls = "mirror") the neighbours' wall ghosts (mirror_walls.h) stand for the
// fluid beyond the wall, each the image of its particle: it adds its mass to the density and pushes with its
// particle's stiffness as the particle would (a_i -= m_b (kappa_i / rho_i + kappa_b / rho_b) grad W_ib, so
// the wall holds a hydrostatic column). In the density rate every ghost moves with its particle's velocity
// mirrored (mirror_velocity), as the fluid beyond the wall would. alpha, the inverse of d(D rho_i / Dt) /
// d kappa_i, holds what that adds: i's own images push with kappa_i twice and move with i, so their
// gradient counts twice in |sum m grad W|^2; a neighbour j that kappa_i pushes (by m grad W_ij) carries its
// images along, so each image g of j adds (m grad W_ij mirrored) . (m grad W_ig) to the second sum. (What
// kappa_i's own images push on j is left out, as [BK15] leaves out j's other neighbours.) Measured
// (2026-12-02, the rayleigh_taylor slab with one fluid, 80 particles tall between walls 4 particles apart):
// with only i's own images moving in the rate, the column rang after the start at up to 0.6 m/s for 40 ms
// (the other particles' images, at rest in the rate, hid the compression they bring); with every image
// moving and alpha as above, at most 0.14 m/s, 0.08 after the first 20 ms. Before that: with every ghost at
// rest a particle in a corner of the floor, whose seven images move when it does, rattled along the diagonal
// at up to 0.67 m/s (hydrostatic_tank.json, 2026-11-30); every ghost moving in the rate with alpha counting
// only i's own blew the dam break with mirror walls up at 0.29 s, as its front reached the far wall's floor
// edge (with the terms above it runs); ghosts that pushed with kappa_i alone gave the wall no pressure
// gradient, so the column's edges, with a quarter of their neighbours real, were squeezed up at 1 m/s.

// Several fluids (SimConstants::number_density, [SP08]; density.h and forces.h for WCSPH): every neighbour
// counts with particle i's mass m_i in the density, its rate and alpha, and the pressure acceleration takes
// the number-density form's weights m_i and m_j^2 / m_i (forces.h, pressure_pair); alpha is then the Jacobi
// diagonal of that system, rho_i / (|sum_j m_i grad W_ij|^2 + sum_j (m_i^3 / m_j) |grad W_ij|^2). With one
// particle mass nothing changes. dfsph_mass gives the neighbour's weight.

// Units (SI): m [kg], rho [kg/m^3], grad W [1/m^4], alpha [m^5/kg], kappa [m^2/s^2], acceleration [m/s^2].
#pragma once

#include "grid.h"
#include "kernels.h"
#include "mirror_walls.h"
#include "params.h"

namespace sph {

// Below this fraction of (m_i sigma / h)^2, sigma = 8 / (pi h^3), the denominator of alpha counts as zero: a
// particle with no neighbour in reach (or only neighbours at the rim of the support) gets alpha = 0 and so no
// pressure, instead of a division by zero. (m_i sigma / h is the size of one m grad W term of the cubic
// spline, and the same scale serves under Poly6 with Spiky, whose gradient is of that order; in the bulk of a lattice with h = 1.95 d the denominator is about 15 of those squared, so only
// isolated particles and those with neighbours only at the rim of the support are affected.)
constexpr float kDfsphAlphaEps = 1e-6f;

// The solves' under-relaxation: each iteration moves a particle's stiffness by this fraction of the paper's
// kappa (src/solvers/dfsph.h, ErrorFn, says why).
constexpr float kDfsphRelaxation = 0.5f;

// A particle takes part in the divergence solve when it has at least this fraction of the neighbours of a
// particle at rest density in the bulk (4/3 pi h^3 rho0 / m), wall ghosts included: about 20 at the default
// 32, SPlisHSPlasH's threshold. Below it (splashes, the free surface) the rate measures missing neighbours,
// not a divergence, and correcting it flung surface particles up at steps of 4 ms (measured).
constexpr float kDfsphMinSupport = 0.6f;

// W_ij [1/m^3] and grad W_ij / r_ij [1/m^5] (grad W_ij = fac * x_ij; r > 0) of DFSPH's kernel (above).
SPH_HD_ALWAYS_INLINE float dfsph_w(const SimConstants& c, float r) {
  return c.dfsph_poly6_spiky ? poly6(c.kernel, r * r) : cubic_spline(c.kernel, r);
}
SPH_HD_ALWAYS_INLINE float dfsph_grad_fac(const SimConstants& c, float r) {
  return c.dfsph_poly6_spiky ? spiky_grad_fac(c.kernel, r) : cubic_spline_grad_fac(c.kernel, r);
}

// Neighbour j's mass in particle i's sums: m_j, or m_i in the number-density form (above).
SPH_HD_ALWAYS_INLINE float dfsph_mass(const SimConstants& c, const ParticleView& p, int32_t i, int32_t j) {
  return c.number_density ? p.pos_mass[i].w : p.pos_mass[j].w;
}

// Seed eq. 7: rho_i = sum_j m_j W_ij with the cubic spline, the particle itself included, plus the wall
// ghosts. [kg/m^3]
SPH_HD inline float dfsph_density(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  float rho = 0.0f;
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3, float r2) {
    rho += dfsph_mass(c, p, i, j) * dfsph_w(c, sqrtf(r2));
  });
  const NearWalls walls = c.mirror_walls ? near_walls(c, xyz(p.pos_mass[i])) : NearWalls{};
  for_each_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t, Vec3, float r2) {
    rho += dfsph_mass(c, p, i, j) * dfsph_w(c, sqrtf(r2));
  });
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  for_each_boundary(grid.boundary, xyz(p.pos_mass[i]), k.h2, [&](int32_t, Vec3, float r2, float volume) {
    rho += rho0 * volume * dfsph_w(c, sqrtf(r2));
  });
  for_each_body_particle(grid.bodies, grid.num_bodies, xyz(p.pos_mass[i]), k.h2, [&](int32_t, int32_t, Vec3, float r2, float volume, Vec3) {
    rho += rho0 * volume * dfsph_w(c, sqrtf(r2));
  });
  return rho;
}

// Seed eq. 9 ([BK15] alpha factor): alpha_i = rho_i / (|sum_j m_j grad W_ij|^2 + sum_j |m_j grad W_ij|^2),
// rho_i = p.density[i] (dfsph_density); wall ghosts in the first sum (i's own images twice) and, for a neighbour's
// images, their motion with it in the second (see above). Depends on positions
// only: computed once per step after the grid and shared by both solvers. Returns 0 where the denominator is below kDfsphAlphaEps
// (isolated particle). [m^5/kg]
SPH_HD inline float dfsph_alpha(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  Vec3 sum_grad{0.0f, 0.0f, 0.0f};  // sum_j m_j grad W_ij [kg/m^4]
  float sum_grad2 = 0.0f;           // sum_j |m_j grad W_ij|^2 [kg^2/m^8]
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3 xij, float r2) {
    if (r2 <= 0.0f) return;
    const Vec3 g = (dfsph_mass(c, p, i, j) * dfsph_grad_fac(c, sqrtf(r2))) * xij;
    sum_grad += g;
    // Number density: (m_i^3 / m_j) |grad W|^2 = |m_i grad W|^2 m_i / m_j (above).
    sum_grad2 += c.number_density ? length2(g) * (p.pos_mass[i].w / p.pos_mass[j].w) : length2(g);
  });
  const Vec3 xi = xyz(p.pos_mass[i]);
  const NearWalls walls = c.mirror_walls ? near_walls(c, xi) : NearWalls{};
  for_each_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t image, Vec3 xg, float r2) {
    // i's own images twice (above): they move with i and push with kappa_i twice.
    const float weight = j == i ? 2.0f : 1.0f;
    if (!(r2 > 0.0f)) return;
    const Vec3 gig = (dfsph_mass(c, p, i, j) * dfsph_grad_fac(c, sqrtf(r2))) * (xi - xg);
    sum_grad += weight * gig;
    if (j == i) return;
    // j's image moves with j mirrored: the push kappa_i gives j moves it too.
    const Vec3 xij = xi - xyz(p.pos_mass[j]);
    const float rij2 = dot(xij, xij);
    if (!(rij2 < k.h2) || !(rij2 > 0.0f)) return;
    const Vec3 gij = (dfsph_mass(c, p, i, j) * dfsph_grad_fac(c, sqrtf(rij2))) * xij;
    const float cross = dot(mirror_velocity(walls, image, gij), gig);
    sum_grad2 += c.number_density ? cross * (p.pos_mass[i].w / p.pos_mass[j].w) : cross;
  });
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  for_each_boundary(grid.boundary, xi, k.h2, [&](int32_t, Vec3 xib, float r2, float volume) {
    if (r2 > 0.0f) sum_grad += (rho0 * volume * dfsph_grad_fac(c, sqrtf(r2))) * xib;
  });
  for_each_body_particle(grid.bodies, grid.num_bodies, xi, k.h2, [&](int32_t, int32_t, Vec3 xib, float r2, float volume, Vec3) {
    if (r2 > 0.0f) sum_grad += (rho0 * volume * dfsph_grad_fac(c, sqrtf(r2))) * xib;
  });
  const float denominator = length2(sum_grad) + sum_grad2;
  const float scale = p.pos_mass[i].w * k.cubic / k.h;
  if (denominator <= kDfsphAlphaEps * scale * scale) return 0.0f;
  return p.density[i] / denominator;
}

// 1 when particle i has kDfsphMinSupport of a bulk particle's neighbours within h (wall ghosts included),
// else 0.
SPH_HD inline int32_t dfsph_support(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const FluidConstants& f = c.fluids[p.fluid[i]];
  const float bulk = 4.0f / 3.0f * 3.14159265f * k.h2 * k.h * f.rest_density / f.mass;
  int32_t count = 0;
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t, Vec3, float) { ++count; });
  const NearWalls walls = c.mirror_walls ? near_walls(c, xyz(p.pos_mass[i])) : NearWalls{};
  for_each_ghost(c, grid, p, walls, i, [&](int32_t, int32_t, Vec3, float) { ++count; });
  for_each_boundary(grid.boundary, xyz(p.pos_mass[i]), k.h2, [&](int32_t, Vec3, float, float) { ++count; });
  for_each_body_particle(grid.bodies, grid.num_bodies, xyz(p.pos_mass[i]), k.h2,
                         [&](int32_t, int32_t, Vec3, float, float, Vec3) { ++count; });
  return float(count) >= kDfsphMinSupport * bulk ? 1 : 0;
}

// Seed eq. 18: D rho_i / Dt = sum_j m_j (v_i - v_j) . grad W_ij, with the velocities vel (the solver's
// predicted v*, not necessarily p.vel); each wall ghost moves with its particle's velocity mirrored, so a
// particle approaching a wall compresses against its own image at twice its speed.
// Positive: compression. Exact zero for a rigid translation without walls; for a rigid rotation
// each pair's term is zero (v_i - v_j is perpendicular to x_ij), so zero to round-off. [kg/(m^3 s)]
SPH_HD inline float dfsph_density_rate(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                       const Vec3* vel, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const Vec3 vi = vel[i];
  float rate = 0.0f;
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3 xij, float r2) {
    if (r2 <= 0.0f) return;
    rate += dfsph_mass(c, p, i, j) * dfsph_grad_fac(c, sqrtf(r2)) * dot(vi - vel[j], xij);
  });
  const Vec3 xi = xyz(p.pos_mass[i]);
  const NearWalls walls = c.mirror_walls ? near_walls(c, xi) : NearWalls{};
  for_each_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t image, Vec3 xg, float r2) {
    if (r2 > 0.0f)
      rate += dfsph_mass(c, p, i, j) * dfsph_grad_fac(c, sqrtf(r2)) *
              dot(vi - mirror_velocity(walls, image, vel[j]), xi - xg);
  });
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  for_each_boundary(grid.boundary, xi, k.h2, [&](int32_t, Vec3 xib, float r2, float volume) {
    if (r2 > 0.0f) rate += rho0 * volume * dfsph_grad_fac(c, sqrtf(r2)) * dot(vi, xib);
  });
  // A rigid body's particles move with it: the rate sees v_i - v_b.
  for_each_body_particle(grid.bodies, grid.num_bodies, xi, k.h2, [&](int32_t, int32_t, Vec3 xib, float r2, float volume, Vec3 vb) {
    if (r2 > 0.0f) rate += rho0 * volume * dfsph_grad_fac(c, sqrtf(r2)) * dot(vi - vb, xib);
  });
  return rate;
}

// Seed eq. 10: rho*_i = rho_i + dt D rho_i / Dt, the density after dt at the current velocities. [kg/m^3]
SPH_HD inline float dfsph_predicted_density(float rho, float density_rate, float dt) {
  return rho + dt * density_rate;
}

// Seed eq. 14, density solver: kappa_i = (rho*_i - rho0) alpha_i / dt^2. [m^2/s^2]
// (Whether to clamp rho*_i - rho0 at 0, so that a free surface is not pulled together, is the solver's choice:
// docs/solvers_plan.md.)
SPH_HD inline float dfsph_density_stiffness(float predicted_density, float rest_density, float alpha, float dt) {
  return (predicted_density - rest_density) * alpha / (dt * dt);
}

// Seed eq. 19, divergence solver: kappa^v_i = (D rho_i / Dt) alpha_i / dt. [m^2/s^2]
SPH_HD inline float dfsph_divergence_stiffness(float density_rate, float alpha, float dt) {
  return density_rate * alpha / dt;
}

// Seed eqs. 15-17 (the seed prints kappa_j / rho_i and drops the minus sign of eq. 16; [BK15] has both right):
// a_i = -sum_j m_j (kappa_i / rho_i + kappa_j / rho_j) grad W_ij, kappa either stiffness, rho = p.density; a
// wall ghost of j carries j's kappa and density (see above). The solver updates v_i += dt a_i. Each pair term of two
// particles is antisymmetric (grad W_ji = -grad W_ij), so without walls sum_i m_i a_i = 0: the pressure
// solves conserve linear momentum (the walls take up what the ghosts give). [m/s^2]
//
// Boundary and body particles ([AIA12] volumes, mass rho0 V_b) push as a fluid particle mirrored into the
// wall would, with kappa_i's share twice (P_b = P_i, rho_b = rho_i), as the mirror ghosts do; the wall's
// pressure P_b then also grows with depth below x_i (dfsph_boundary_hydrostatic), as WCSPH's boundary pair
// (forces.h). Measured (docs/results.md, "Bodies under DFSPH"): with kappa_i alone ([BK15] with
// [AIA12]; SPlisHSPlasH) the walls held the fluid with half the push, so the first layer sat at a quarter
// of a spacing from the floor instead of a half, and a fixed box 2.6 cm deep carried 0.80 of the
// hydrostatic force (a floating box of density 500 sank to 0.57 of its height); mirrored without the
// hydrostatic part the box carried 1.24 and floated at 0.44, since at that depth the pressure changes by
// half across the kernel's reach. alpha keeps the boundary in |sum grad|^2 only (as the ghosts).
SPH_HD inline Vec3 dfsph_pressure_acceleration(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                               const float* kappa, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const float ki = kappa[i] / p.density[i];
  Vec3 acc{0.0f, 0.0f, 0.0f};
  // The pair's weight: m_j (k_i + k_j), or the number-density form's m_i k_i + (m_j^2 / m_i) k_j.
  const float mi = p.pos_mass[i].w;
  const auto pair = [&](int32_t j) {
    const float mj = p.pos_mass[j].w, kj = kappa[j] / p.density[j];
    return c.number_density ? mi * ki + mj * (mj / mi) * kj : mj * (ki + kj);
  };
  for_each_neighbour(grid, p.pos_mass, i, k.h2, [&](int32_t j, Vec3 xij, float r2) {
    if (r2 <= 0.0f) return;
    acc -= (pair(j) * dfsph_grad_fac(c, sqrtf(r2))) * xij;
  });
  const Vec3 xi = xyz(p.pos_mass[i]);
  const NearWalls walls = c.mirror_walls ? near_walls(c, xi) : NearWalls{};
  for_each_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t, Vec3 xg, float r2) {
    if (r2 > 0.0f) acc -= (pair(j) * dfsph_grad_fac(c, sqrtf(r2))) * (xi - xg);
  });
  // Boundary and body particles push with the particle's stiffness mirrored (kappa_b / rho_b = kappa_i / rho_i,
  // dfsph_boundary_hydrostatic adds the hydrostatic rest of P_b).
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  for_each_boundary(grid.boundary, xi, k.h2, [&](int32_t, Vec3 xib, float r2, float volume) {
    if (r2 > 0.0f) acc -= (2.0f * rho0 * volume * ki * dfsph_grad_fac(c, sqrtf(r2))) * xib;
  });
  for_each_body_particle(grid.bodies, grid.num_bodies, xi, k.h2, [&](int32_t, int32_t, Vec3 xib, float r2, float volume, Vec3) {
    if (r2 > 0.0f) acc -= (2.0f * rho0 * volume * ki * dfsph_grad_fac(c, sqrtf(r2))) * xib;
  });
  return acc;
}

// What the pressure solves did between fluid particle i and rigid body `body` ([AIA12] section 4 with [BK15]):
// the reaction to the body's terms of dfsph_pressure_acceleration, force m_i sum_b 2 rho0 V_b (kappa_i / rho_i)
// grad W_ib [N] and its torque about the body's centre [N m], with kappa_i the stiffness the solve applied in
// all (the kept pressure over rho_i: the solves' velocity changes are linear in kappa, so the sum of what
// every iteration applied is the term of the total). Summed over the fluid it is minus the momentum the solve gave the fluid
// through the body, per dt.
SPH_HD inline void dfsph_body_reaction(const SimConstants& c, const GridView& grid, const ParticleView& p, float kappa_i,
                                       int32_t i, int32_t body, Vec3& force, Vec3& torque) {
  force = torque = Vec3{0.0f, 0.0f, 0.0f};
  if (p.age[i] < 0.0f) return;
  const KernelCoeffs& k = c.kernel;
  const float ki = kappa_i / p.density[i];
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  const Vec3 xi = xyz(p.pos_mass[i]);
  const BodyView& bv = grid.bodies[body];
  const float mi = p.pos_mass[i].w;
  for_each_body_particle(&bv, 1, xi, k.h2, [&](int32_t, int32_t, Vec3 xib, float r2, float volume, Vec3) {
    if (!(r2 > 0.0f)) return;
    const Vec3 f = (2.0f * mi * rho0 * volume * ki * dfsph_grad_fac(c, sqrtf(r2))) * xib;
    force += f;
    torque += cross(xi - bv.centre - xib, f);
  });
}

// The hydrostatic part of a wall's pressure in a DFSPH step ([Adami et al. 2012] eq. 27, as forces.h's
// boundary pair): boundary or body particle b at x_i - xib carries P_b = P_i + rho0 g.(x_b - x_i), of which
// dfsph_pressure_acceleration's mirrored stiffness is the P_i; this is the rest, -rho0 g.x_ib, kept so that
// P_b >= 0 (a wall never pulls), with P_i the pressure the last density solve ended with (p.pressure, of
// which the warm start carries dfsph.warm_start_fraction; the clamp takes all of it). It does not depend on the stiffnesses, so it is a force of the step's forces phase. Returns the
// acceleration of the fluid particle [m/s^2] from one such particle of volume V_b (0 < r2 < h^2).
SPH_HD inline Vec3 dfsph_wall_hydrostatic_pair(const SimConstants& c, float rho0, float pressure_i,
                                               Vec3 xib, float r2, float volume) {
  const float extra = -rho0 * dot(c.gravity, xib);
  const float kept = extra > -pressure_i ? extra : -pressure_i;
  return (-volume * kept / rho0 * dfsph_grad_fac(c, sqrtf(r2))) * xib;
}

// Fluid particle i's acceleration from the hydrostatic part of every boundary and body particle's pressure
// in reach (dfsph_wall_hydrostatic_pair). [m/s^2]
SPH_HD inline Vec3 dfsph_boundary_hydrostatic(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  const float pi = p.pressure[i] > 0.0f ? p.pressure[i] : 0.0f;
  const Vec3 xi = xyz(p.pos_mass[i]);
  Vec3 acc{0.0f, 0.0f, 0.0f};
  for_each_boundary(grid.boundary, xi, k.h2, [&](int32_t, Vec3 xib, float r2, float volume) {
    if (r2 > 0.0f) acc += dfsph_wall_hydrostatic_pair(c, rho0, pi, xib, r2, volume);
  });
  for_each_body_particle(grid.bodies, grid.num_bodies, xi, k.h2, [&](int32_t, int32_t, Vec3 xib, float r2, float volume, Vec3) {
    if (r2 > 0.0f) acc += dfsph_wall_hydrostatic_pair(c, rho0, pi, xib, r2, volume);
  });
  return acc;
}

// The reaction on body `body` to dfsph_boundary_hydrostatic's share of its particles, force -m_i a [N] and
// torque about the body's centre [N m]. It reads p.pressure as the forces phase did only if called before the
// density solve changes it: the DFSPH step calls it after, so under gravity the body's share lags the fluid's
// by one step's change of pressure (without gravity the term is zero and momentum exact).
SPH_HD inline void dfsph_body_hydrostatic_reaction(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                                   int32_t i, int32_t body, Vec3& force, Vec3& torque) {
  force = torque = Vec3{0.0f, 0.0f, 0.0f};
  if (p.age[i] < 0.0f) return;
  const KernelCoeffs& k = c.kernel;
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  const float pi = p.pressure[i] > 0.0f ? p.pressure[i] : 0.0f;
  const Vec3 xi = xyz(p.pos_mass[i]);
  const BodyView& bv = grid.bodies[body];
  const float mi = p.pos_mass[i].w;
  for_each_body_particle(&bv, 1, xi, k.h2, [&](int32_t, int32_t, Vec3 xib, float r2, float volume, Vec3) {
    if (!(r2 > 0.0f)) return;
    const Vec3 f = -mi * dfsph_wall_hydrostatic_pair(c, rho0, pi, xib, r2, volume);
    force += f;
    torque += cross(xi - bv.centre - xib, f);
  });
}

}  // namespace sph
