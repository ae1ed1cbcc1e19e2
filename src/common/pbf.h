// Per-particle formulas of Position Based Fluids [MM13] (Macklin & Mueller 2013; seed 002 describes the
// position-based pressure solver). The solver phases (issue 12) call them on the predicted positions x*, held
// in p.pos while the solver iterates; they read the particle and grid views only, and the arrays PBF adds
// (lambda, vorticity) are passed as raw pointers, not ParticleState fields. Each returns its value.
// The paper's text is not among the seeds: its equation numbers below are recalled, to check against it.
//
// Kernels as the paper: Poly6 for densities and weights, Spiky for gradients (kernels.h, support h). The
// density rho_i = sum_j m_j W_poly6 (pbf_density). The paper takes unit masses; here every sum carries m_j,
// written so that the corrections conserve linear momentum for any masses (sum_i m_i Delta p_i = 0).
//
// Several fluids (SimConstants::number_density, set where the fluids' masses differ; [SP08] as density.h and
// dfsph.h): every neighbour counts at i's own mass, rho_i = m_i sum_j W_ij, so C_i = rho_i / rho0_i - 1 reads
// the number density and a light particle beside heavy ones is not read as compressed. The corrections are
// the mass-weighted projection of position-based dynamics, Delta x_k = (1 / m_k) sum_c lambda^_c grad_k C_c
// with lambda^_c = -C_c / (sum_k |grad_k C_c|^2 / m_k + epsilon^): a constraint moves the lighter of its
// particles more, as a pressure accelerates a lighter particle of the same volume more, and sum_k m_k
// Delta x_k = 0. Written with lambda_c = lambda^_c / m_c, so that with equal masses every expression is the
// single-fluid one times exact factors of 1: lambda_c = -C_c / (sum_k (m_c / m_k) |grad_k C_c|^2 + epsilon),
// grad_j C_i = -(m_i / rho0_i) grad W_ij, and i moves by (1 / rho0_i) sum_j (m_i lambda_i + (m_j^2 / m_i)
// (rho0_i / rho0_j) lambda_j) grad W_ij.
//
// Units (SI): grad C [1/m], lambda [m^2], relaxation epsilon [1/m^2], Delta p [m], vorticity [1/s].
// The paper's k and epsilon carry no units (its scenes fix the length scale); they are read here in units of
// the support h (k h^2, epsilon / h^2), so a scene behaves the same at every resolution.
#pragma once

#include "forces.h"
#include "grid.h"
#include "kernels.h"
#include "mirror_walls.h"
#include "neighbour_list.h"
#include "params.h"

namespace sph {


// The neighbours as [MM13] finds them, once a step (algorithm 1, line 6): the pairs the grid phase selected
// by the list radius (neighbour_list.h, neighbour_radius2: kPbfListReach h, 1.1 h) at its positions,
// pos_mass, which the solver leaves as the grid phase wrote them; in the search's order, the same on every
// back end (the CPU builds read the lists). Each is evaluated at the current positions p.pos, while within h:
// f(j, x_i - x_j, r2) with r2 < h^2.
template <class F>
SPH_HD inline void for_each_pbf_pair(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i, F&& f) {
  const Vec3 xi = p.pos[i];
  const float h2 = c.kernel.h2;
  for_each_neighbour(grid, p.pos_mass, i, neighbour_radius2(c), [&](int32_t j, Vec3, float) {
    const Vec3 xij = xi - p.pos[j];
    const float r2 = length2(xij);
    if (r2 < h2) f(j, xij, r2);
  });
}

// The wall ghosts (mirror_walls.h) of those pairs' neighbours at their current positions:
// f(j, image, x_ghost, r2) for each ghost within h of x_i.
template <class F>
SPH_HD inline void for_each_pbf_ghost(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                      const NearWalls& walls, int32_t i, F&& f) {
  for_each_ghost_of(c, grid, p.pos_mass, neighbour_radius2(c), p.pos, walls, i, f);
}

// Neighbour (or wall ghost of) j's mass in particle i's sums: m_j, or m_i in the number-density form (above).
SPH_HD_ALWAYS_INLINE float pbf_mass(const SimConstants& c, const ParticleView& p, int32_t i, int32_t j) {
  return c.fluids[p.fluid[c.number_density ? i : j]].mass;
}

// rho_i = sum_j m_j W_poly6(x_i - x_j) (m_i with several fluids: pbf_mass), the particle itself included, at the positions p.pos (the predicted
// x* while the solver iterates): the density the constraint reads ([MM13] eq. 2). With mirror walls the
// neighbours' wall ghosts (mirror_walls.h, for_each_pbf_ghost) add their
// mass, so a particle at a wall is not read as under-dense. [kg/m^3]
SPH_HD inline float pbf_density(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  float rho = 0.0f;
  for_each_pbf_pair(c, grid, p, i, [&](int32_t j, Vec3, float r2) {
    rho += pbf_mass(c, p, i, j) * poly6(k, r2);
  });
  const NearWalls walls = c.mirror_walls ? near_walls(c, p.pos[i]) : NearWalls{};
  for_each_pbf_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t, Vec3, float r2) { rho += pbf_mass(c, p, i, j) * poly6(k, r2); });
  const float rho0 = c.fluids[p.fluid[i]].rest_density;
  for_each_boundary(grid.boundary, p.pos[i], k.h2, [&](int32_t, Vec3, float r2, float volume) { rho += rho0 * volume * poly6(k, r2); });
  return rho;
}

// [MM13] eq. 1: C_i = rho_i / rho0 - 1. Negative under expansion, positive under compression.
SPH_HD inline float pbf_constraint(float density, float rest_density) { return density / rest_density - 1.0f; }

// [MM13] section 3 (eqs. 8 to 11): lambda_i = -C_i / (sum_k |grad_k C_i|^2 + epsilon), with
// grad_j C_i = -(m_j / rho0) grad W_ij (k = j) and grad_i C_i = (1 / rho0) sum_j m_j grad W_ij (k = i), and
// the density rho_i (pbf_density's sum, the same bits) that C_i = rho_i / rho0 - 1 reads, both from one pass
// over the neighbours: the density into `density`, lambda returned. max(C_i, 0) with clamp_expansion.
// Positive under expansion (C < 0): lambda pulls neighbours in; negative under compression. Returns 0 where
// the denominator is not positive (an isolated particle with epsilon = 0). Wall ghosts are the mirror image
// of the fluid (mirror_walls.h), and the constraint counts them as fluid particles: a ghost of j moves with
// its own lambda_j (pbf_position_correction), so its |grad C_i|^2 is in the denominator as a neighbour's.
// (Counted as solid, moving i alone, a wall particle's lambda was too strong for what the iteration then
// did, and the column's layers beside the walls rattled: docs/results.md, issue 12.) Boundary particles
// are solid. [m^2]
SPH_HD inline float pbf_density_lambda(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                       const PbfConstants& params, int32_t i, float& density) {
  const KernelCoeffs& k = c.kernel;
  const float rest_density = c.fluids[p.fluid[i]].rest_density;
  float rho = 0.0f;
  Vec3 grad_i{0.0f, 0.0f, 0.0f};  // grad_i C_i [1/m]
  float sum_grad2 = 0.0f;         // sum_j |grad_j C_i|^2 [1/m^2]
  const float mi = c.fluids[p.fluid[i]].mass;
  // Neighbour j, or its wall ghost, at x_i - x_j = xij.
  const auto add = [&](int32_t j, Vec3 xij, float r2) {
    const float mj = pbf_mass(c, p, i, j);
    rho += mj * poly6(k, r2);
    if (r2 <= 0.0f) return;
    const Vec3 g = (mj / rest_density * spiky_grad_fac(k, sqrtf(r2))) * xij;
    grad_i += g;
    // Number density: (m_i / m_j) |grad_j C_i|^2, the mass-weighted projection's (above).
    sum_grad2 += c.number_density ? length2(g) * (mi / c.fluids[p.fluid[j]].mass) : length2(g);
  };
  for_each_pbf_pair(c, grid, p, i, add);
  const Vec3 xi = p.pos[i];
  const NearWalls walls = c.mirror_walls ? near_walls(c, xi) : NearWalls{};
  for_each_pbf_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t, Vec3 xg, float r2) { add(j, xi - xg, r2); });
  // Boundary particles [AIA12]: Psi_b = rho0 V_b, solid (no lambda of their own; i moves alone).
  for_each_boundary(grid.boundary, xi, k.h2, [&](int32_t, Vec3 xib, float r2, float volume) {
    rho += rest_density * volume * poly6(k, r2);
    if (r2 > 0.0f) grad_i += (volume * spiky_grad_fac(k, sqrtf(r2))) * xib;
  });
  density = rho;
  const float denominator = sum_grad2 + length2(grad_i) + params.relaxation / k.h2;
  if (!(denominator > 0.0f)) return 0.0f;
  const float constraint = pbf_constraint(rho, rest_density);
  return -(params.clamp_expansion && constraint < 0.0f ? 0.0f : constraint) / denominator;
}

// lambda_i alone (pbf_density_lambda). [m^2]
SPH_HD inline float pbf_lambda(const SimConstants& c, const GridView& grid, const ParticleView& p,
                               const PbfConstants& params, int32_t i) {
  float density;
  return pbf_density_lambda(c, grid, p, params, i, density);
}

// [MM13] eq. 13: s_corr = -k (W(r) / W(dq))^n, W = Poly6, r^2 = |x_ij|^2. Dimensionless as in the paper;
// negative inside the support, -k at r = dq, 0 at and beyond h.
SPH_HD inline float pbf_scorr(const KernelCoeffs& k, const PbfConstants& params, float r2) {
  const float dq = params.scorr_dq * k.h;
  const float ratio = poly6(k, r2) / poly6(k, dq * dq);
  float power = 1.0f;
  for (int32_t e = 0; e < params.scorr_n; ++e) power *= ratio;
  return -params.scorr_k * power;
}

// [MM13] eq. 14: Delta p_i = (1 / rho0) sum_j m_j (lambda_i + lambda_j + s_corr h^2) grad W_ij (Spiky),
// lambda from pbf_lambda. The pair (i, j) moves i by m_j X and j by -m_i X for the same X: equal and opposite
// momentum, sum_i m_i Delta p_i = 0. Several fluids (above): the pair's weight is m_i lambda_i + (m_j^2 / m_i)
// (rho0_i / rho0_j) lambda_j, and s_corr's m_j 2 rho0_i / (rho0_i + rho0_j), so that m_i Delta p_i of the pair
// is again antisymmetric. [m]
SPH_HD inline Vec3 pbf_position_correction(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                           const float* lambda, const PbfConstants& params, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const float li = lambda[i];
  const FluidConstants& fi = c.fluids[p.fluid[i]];
  Vec3 dp{0.0f, 0.0f, 0.0f};
  // The pair's weight of Spiky's gradient, for neighbour j or its wall ghost (the mirror image of j, with
  // j's lambda: pbf_density_lambda).
  // s_corr's term is skipped where k = 0 (the default): it would add -0 to every weight.
  const bool scorr_on = params.scorr_k != 0.0f;
  const auto weight = [&](int32_t j, float r2) {
    const FluidConstants& fj = c.fluids[p.fluid[j]];
    if (c.number_density) {
      const float w = fi.mass * li + fj.mass * (fj.mass / fi.mass) * (fi.rest_density / fj.rest_density) * lambda[j];
      return scorr_on ? w + fj.mass * (2.0f * fi.rest_density / (fi.rest_density + fj.rest_density)) *
                                (pbf_scorr(k, params, r2) * k.h2)
                      : w;
    }
    return fj.mass * (scorr_on ? li + lambda[j] + pbf_scorr(k, params, r2) * k.h2 : li + lambda[j]);
  };
  for_each_pbf_pair(c, grid, p, i, [&](int32_t j, Vec3 xij, float r2) {
    if (r2 > 0.0f) dp += (weight(j, r2) * spiky_grad_fac(k, sqrtf(r2))) * xij;
  });
  const Vec3 xi = p.pos[i];
  const NearWalls walls = c.mirror_walls ? near_walls(c, xi) : NearWalls{};
  for_each_pbf_ghost(c, grid, p, walls, i, [&](int32_t j, int32_t, Vec3 xg, float r2) {
    if (r2 > 0.0f) dp += (weight(j, r2) * spiky_grad_fac(k, sqrtf(r2))) * (xi - xg);
  });
  const float rho0 = fi.rest_density;
  for_each_boundary(grid.boundary, xi, k.h2, [&](int32_t, Vec3 xib, float r2, float volume) {
    if (r2 <= 0.0f) return;
    const float s = scorr_on ? li + pbf_scorr(k, params, r2) * k.h2 : li;
    dp += (rho0 * volume * s * spiky_grad_fac(k, sqrtf(r2))) * xib;
  });
  return (1.0f / c.fluids[p.fluid[i]].rest_density) * dp;
}

// [MM13] eq. 17, XSPH viscosity: Delta v_i = c sum_j m_j / rho_ij (v_j - v_i) W_ij (Poly6), rho_ij the mean
// density of the pair: the form of forces.h's XSPH (the paper writes the unit-mass sum without m_j / rho_ij).
// The solver sets v_i += Delta v_i after the velocity update. [m/s]
SPH_HD inline Vec3 pbf_xsph(const SimConstants& c, const GridView& grid, const ParticleView& p, const Vec3* vel,
                            const PbfConstants& params, int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const Vec3 vi = vel[i];
  const float rho_i = p.density[i];
  Vec3 dv{0.0f, 0.0f, 0.0f};
  for_each_pbf_pair(c, grid, p, i, [&](int32_t j, Vec3, float r2) {
    if (r2 <= 0.0f) return;
    dv += xsph_pair_weight(k, false, 1.0f, c.fluids[p.fluid[j]].mass, r2, rho_i, p.density[j]) * (vel[j] - vi);
  });
  return params.xsph_c * dv;
}

// [MM13] eq. 15, vorticity: omega_i = curl v = sum_j (m_j / rho_j) (v_j - v_i) x grad_j W_ij, grad_j W_ij =
// -grad_i W_ij (Spiky). The paper's unit-mass sum with the volumes m_j / rho_j, which makes it the SPH curl:
// a rigid rotation v = w x x gives omega = 2 w where the neighbourhood is full. [1/s]
SPH_HD inline Vec3 pbf_vorticity(const SimConstants& c, const GridView& grid, const ParticleView& p, const Vec3* vel,
                                 int32_t i) {
  const KernelCoeffs& k = c.kernel;
  const Vec3 vi = vel[i];
  Vec3 omega{0.0f, 0.0f, 0.0f};
  for_each_pbf_pair(c, grid, p, i, [&](int32_t j, Vec3 xij, float r2) {
    if (r2 <= 0.0f) return;
    const Vec3 grad_j = (-c.fluids[p.fluid[j]].mass / p.density[j] * spiky_grad_fac(k, sqrtf(r2))) * xij;
    omega += cross(vel[j] - vi, grad_j);
  });
  return omega;
}

// [MM13] eq. 16, vorticity confinement: a_i = epsilon (N x omega_i), N = eta / |eta|, eta = grad |omega| at i
// = sum_j (m_j / rho_j) (|omega_j| - |omega_i|) grad_i W_ij; omega from pbf_vorticity. Zero where |eta|
// vanishes (uniform vorticity: nothing to confine) or epsilon = 0. Acceleration, the paper's force per unit
// mass. [m/s^2]
SPH_HD inline Vec3 pbf_vorticity_confinement(const SimConstants& c, const GridView& grid, const ParticleView& p,
                                             const Vec3* omega, const PbfConstants& params, int32_t i) {
  const Vec3 zero{0.0f, 0.0f, 0.0f};
  if (params.vorticity_epsilon == 0.0f) return zero;
  const KernelCoeffs& k = c.kernel;
  const float wi = length(omega[i]);
  Vec3 eta{0.0f, 0.0f, 0.0f};
  for_each_pbf_pair(c, grid, p, i, [&](int32_t j, Vec3 xij, float r2) {
    if (r2 <= 0.0f) return;
    eta += (c.fluids[p.fluid[j]].mass / p.density[j] * (length(omega[j]) - wi) * spiky_grad_fac(k, sqrtf(r2))) *
           xij;
  });
  const float eta_len = length(eta);
  // |eta| below 1e-6 |omega_i| / h: a vorticity gradient lost in round-off, no direction to push along.
  if (!(eta_len > 1e-6f * wi / k.h)) return zero;
  return params.vorticity_epsilon * cross((1.0f / eta_len) * eta, omega[i]);
}

}  // namespace sph
