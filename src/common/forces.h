// Phase "forces": acceleration of one particle from pressure and near pressure, viscosity, surface
// tension and external forces; also the XSPH velocity correction when enabled. Every pair term is written
// so that the pair (a, b) and the pair (b, a) give equal and opposite momentum changes for equal masses
// and viscosities (tests/test_conservation.cpp). With mirror walls the ghosts of the neighbours add
// pressure, near pressure and viscosity (mirror_walls.h); the walls then take up momentum.
//
// Lean pair loop (issue 11, item 4): the pair terms divide by no density (1 / rho and P / rho^2 come from the
// pressure phase, pressure.h); a neighbour's position and mass, and its velocity and 1 / rho, are each one
// 16-byte record (pos_mass, vel_inv_rho: one 128-bit load on a GPU); and the pressure form and near pressure are template parameters (ForceModel),
// chosen once per loop by the back end (with_force_model). The other switches stay run-time tests, uniform
// over a loop: as template parameters too (viscosity model, artificial viscosity: 24 loops) they gained at most
// 3% more on cpu but made 14 of the 24 CUDA loops spill past the 80-register target (ptxas, sm_90).
#pragma once

#include "equation_of_state.h"
#include "grid.h"
#include "kernels.h"
#include "mirror_walls.h"
#include "params.h"

namespace sph {

// eps^2 / h^2 of the pair terms that divide by r^2 + eps^2 (Morris and artificial viscosity): keeps them finite
// as r -> 0.
constexpr float kPairEps2 = 0.01f;

// XSPH [Monaghan 1989] pair weight, coef m_b W_ab / rho_ab with rho_ab = (rho_a + rho_b) / 2 (the density
// kernel: Poly6, or the cubic spline where `cubic`, SimConstants::cubic_spline): particle a's velocity
// correction is the sum of weight * (v_b - v_a). Shared by WCSPH's forces (coef: the fluid's xsph) and PBF
// ([MM13] eq. 17, pbf.h, coef 1 and c applied to the sum, Poly6). Dimensionless.
SPH_HD inline float xsph_pair_weight(const KernelCoeffs& k, bool cubic, float coef, float mb, float r2, float rho_a,
                                     float rho_b) {
  return coef * mb * density_kernel(k, cubic, r2) / (0.5f * (rho_a + rho_b));
}

// The user force field at x (UserForce, params.h): towards the point (strength > 0), fading linearly to zero
// at the radius; zero outside it and at the point itself. [m/s^2]
SPH_HD inline Vec3 user_force_acceleration(const SimConstants& c, Vec3 x) {
  const Vec3 to_point = c.user_force.point - x;
  const float dist = length(to_point);
  if (!(dist < c.user_force.radius && dist > 0.0f)) return Vec3{0.0f, 0.0f, 0.0f};
  return (c.user_force.strength * (1.0f - dist / c.user_force.radius) / dist) * to_point;
}

// The force model's compile-time switches: the pressure form, whether any fluid has near pressure, whether
// there is a pressure term at all (kPressure = false: the non-pressure forces of the incompressible solvers,
// src/solvers/dfsph.h, whose pressure is their own solve's), and whether the viscosity is all there is
// (kViscousOnly: PBF's viscosity, src/solvers/pbf.h, apply_viscosity, whose step applies gravity, the user
// force, XSPH and its surface tension in phases of its own; no cohesion, adhesion, XSPH, gravity or user force).
template <PressureForm kForm, bool kNear, bool kPressure = true, bool kViscousOnly = false>
struct ForceModel {
  static constexpr PressureForm form = kForm;
  static constexpr bool near = kNear;
  static constexpr bool pressure = kPressure && !kViscousOnly;
  static constexpr bool viscous_only = kViscousOnly;
};
// Viscosity, surface tension, gravity and the user force; no pressure, no near pressure.
using NonPressureForces = ForceModel<PressureForm::MonaghanSymmetric, false, false>;
// The fluids' laminar and artificial viscosity alone (with the walls' and boundary particles' friction).
using ViscousForces = ForceModel<PressureForm::MonaghanSymmetric, false, false, true>;

// Calls f(ForceModel<...>{}) with the model of c: one dispatch per loop over particles, not per pair.
template <class F>
void with_force_model(const SimConstants& c, F&& f) {
  constexpr PressureForm kMonaghan = PressureForm::MonaghanSymmetric, kMueller = PressureForm::Mueller;
  const bool mueller = c.pressure_form == kMueller, near = c.near_enabled != 0;
  if (mueller && near) f(ForceModel<kMueller, true>{});
  else if (mueller) f(ForceModel<kMueller, false>{});
  else if (near) f(ForceModel<kMonaghan, true>{});
  else f(ForceModel<kMonaghan, false>{});
}

// Pressure (and near pressure) pair term, returned as the scalar s with a_a += s * grad W; takes P / rho^2
// and 1 / rho of each side, computed once per particle (pressure.h), so the pair term does not divide.
// Monaghan symmetric, thesis eq. 2.18 divided by rho_a: -(wa P_a / rho_a^2 + wb P_b / rho_b^2), wa = wb = m_b.
// Mueller, thesis eq. 2.19 divided by rho_a: -wb (P_a + P_b) / (2 rho_a rho_b), wb = m_b.
// Several fluids in the number-density form ([SP08] eq. 8, thesis eq. 3.6; SimConstants::number_density):
// the force -sum_b (P_a / delta_a^2 + P_b / delta_b^2) grad W with delta = rho / m, divided by m_a, is
// Monaghan's with wa = m_a and wb = m_b^2 / m_a (pair_weights); equal and opposite on a and b whatever the
// masses. Mueller's form, -(1 / m_a) sum_b (P_a + P_b) / (2 delta_a delta_b) grad W, is the plain one.
template <PressureForm kForm>
SPH_HD inline float pressure_pair(float wa, float wb, float pa, float pa_rho2, float inv_rhoa, float pb, float pb_rho2,
                                  float inv_rhob) {
  if (kForm == PressureForm::MonaghanSymmetric) return -(wa * pa_rho2 + wb * pb_rho2);
  return -0.5f * wb * (pa + pb) * inv_rhoa * inv_rhob;
}

// The pair terms a particle a gets from a neighbour b or from a wall's ghost of b: pressure, near pressure
// and viscosity, added to acc. xab = x_a - x_b, vab = v_a - v_b, 0 < r2 < h^2.
struct PairSide {  // what the pair needs of one side; *_rho2 = P / rho^2 (over_rho2)
  const FluidConstants* fluid;
  Vec3 vel;    // vel_force
  float mass;  // the fluid's mass, from pos_mass
  float rho, inv_rho, pressure, pressure_rho2, near_pressure, near_pressure_rho2;
};

// Particle i as a side of a pair. A model reads only some of the values; the compiler drops the other loads.
SPH_HD_ALWAYS_INLINE PairSide particle_side(const SimConstants& c, const ParticleView& p, int32_t i) {
  const Vec4 v = p.vel_inv_rho[i];
  return PairSide{&c.fluids[p.fluid[i]], xyz(v),         p.pos_mass[i].w,    p.density[i],
                  v.w,                   p.pressure[i],  p.pressure_rho2[i], p.near_pressure[i],
                  p.near_pressure_rho2[i]};
}

// Monaghan's artificial viscosity, thesis eq. 2.20-2.22 (beta = 0), approaching pairs only: -m_b Pi_ab, to be
// multiplied by grad W_ab's scalar (the caller's grad) and x_ab, as the pressure term is.
// Pi_ab = -alpha cbar mu_ab / rho_ab, mu_ab = h v_ab.x_ab / (r^2 + eps^2), rho_ab = (rho_a + rho_b) / 2: both
// quotients in one division. Receding pairs (v_ab.x_ab >= 0) get mu_ab = 0, without a branch: whether a pair
// approaches is a coin toss in a splashing fluid, which a CPU mispredicts. min(v_ab.x_ab, 0), exactly, as
// (x - |x|) / 2: fminf is a library call on x86 (1.4% of a dam-break step), and GCC turns a
// compare-and-select into a branch.
SPH_HD_ALWAYS_INLINE float artificial_viscosity_pair(const SimConstants& c, const PairSide& a, const PairSide& b, Vec3 xab,
                                                     float r2, Vec3 vab) {
  const KernelCoeffs& k = c.kernel;
  const float approach = dot(vab, xab);
  const float vx = 0.5f * (approach - fabsf(approach));
  const float alpha = 0.5f * (a.fluid->artificial_alpha + b.fluid->artificial_alpha);
  const float cbar = 0.5f * (a.fluid->speed_of_sound + b.fluid->speed_of_sound);
  const float pi_ab = -alpha * cbar * k.h * vx / ((r2 + kPairEps2 * k.h2) * (0.5f * (a.rho + b.rho)));
  return -b.mass * pi_ab;
}

// The laminar viscosity of the fluids' mu on pair a-b (the scene's sph.viscosity): its acceleration of a
// [m/s^2]. r = |x_ab|, grad: grad W_ab's scalar (dW/dr / r of Spiky or the cubic spline: gradient_dwdr).
SPH_HD_ALWAYS_INLINE Vec3 laminar_viscosity_pair(const SimConstants& c, const PairSide& a, const PairSide& b, float r,
                                                 float r2, float grad, Vec3 vab) {
  const KernelCoeffs& k = c.kernel;
  const float mb = b.mass;
  switch (c.viscosity) {
    case ViscosityModel::Mueller:  // thesis eq. 2.24 / rho_a with the fluids' mean mu (thesis 3.3), symmetric
      return -(0.5f * (a.fluid->viscosity + b.fluid->viscosity) * mb * viscosity_laplacian(k, r) * a.inv_rho * b.inv_rho) * vab;
    case ViscosityModel::Morris:  // Morris 1997: sum m_b (mu_a + mu_b)/(rho_a rho_b) (x_ab.gradW)/(r^2+eps^2) v_ab
      return (mb * (a.fluid->viscosity + b.fluid->viscosity) * grad * r2 * a.inv_rho * b.inv_rho /
              (r2 + kPairEps2 * k.h2)) * vab;
    case ViscosityModel::Artificial:
    case ViscosityModel::None:
      break;
  }
  return Vec3{0.0f, 0.0f, 0.0f};
}

// Surface tension as cohesion between two particles of one fluid (calibration.h: the pair force
// -gamma m_a m_b C(r) x_ab / r of [AKT13] eq. 1 with their kernel C, eq. 2, and gamma calibrated from sigma in
// N/m): particle a's acceleration, to be subtracted. Akinci's curvature term and the factor
// K_ab = 2 rho0 / (rho_a + rho_b) are left out: the calibration counts the missing neighbours of a surface
// particle as they are, and the curvature term carries no units that sigma could fix. Two fluids pull on
// each other only with the cross cohesion of the scene's interface_tension (SimConstants::cross_cohesion);
// without it they meet with an interface tension of sigma_1 + sigma_2. `cohesion`: the pair's constant.
SPH_HD_ALWAYS_INLINE Vec3 cohesion_pair(const KernelCoeffs& k, float cohesion, float mb, float r2, Vec3 xab) {
  const float r = sqrtf(r2);
  return (cohesion * mb * akinci_cohesion_shape(r / k.h) / r) * xab;
}

template <class Model>
SPH_HD_ALWAYS_INLINE void pressure_viscosity_pair(const SimConstants& c, const PairSide& a, const PairSide& b, Vec3 xab,
                                                  float r2, Vec3 vab, Vec3& acc) {
  const KernelCoeffs& k = c.kernel;
  const float r = sqrtf(r2);
  const float inv_r = 1.0f / r;  // the gradients are dW/dr x_ab / r (kernels.h)
  const float mb = b.mass;
  const float grad = gradient_dwdr(k, c.cubic_spline != 0, r) * inv_r;  // grad W_ab = grad * xab (Spiky, or the cubic spline)

  // The pressure terms' weights (pressure_pair): m_b, or Monaghan's number-density form's m_a and m_b^2 / m_a.
  const bool number_density = Model::form == PressureForm::MonaghanSymmetric && c.number_density;
  const float wa = number_density ? a.mass : mb;
  const float wb = number_density ? mb * (mb / a.mass) : mb;
  float s = Model::pressure ? pressure_pair<Model::form>(wa, wb, a.pressure, a.pressure_rho2, a.inv_rho, b.pressure,
                                                         b.pressure_rho2, b.inv_rho) * grad
                            : 0.0f;
  if (Model::near && Model::pressure)  // double density relaxation, thesis 3.1: near pressures on the sharper kernel
    s += pressure_pair<Model::form>(wa, wb, a.near_pressure, a.near_pressure_rho2, a.inv_rho, b.near_pressure,
                                    b.near_pressure_rho2, b.inv_rho) * near_dwdr(k, r) * inv_r;

  acc += laminar_viscosity_pair(c, a, b, r, r2, grad, vab);
  if (c.artificial_enabled) s += artificial_viscosity_pair(c, a, b, xab, r2, vab) * grad;
  acc += s * xab;
}

// A boundary pair ([AIA12] section 3.2): fluid particle a and a boundary or body particle b, which stands for
// fluid at rest density, mass Psi_b = rho0_a V_b, moving with its solid (in the number-density form too: b
// counts as V_b / V_a particles of a's fluid, whose weights m_a and m_a^2 / m_a times V_b / V_a are Psi_b):
// - pressure: a's pressure extrapolated hydrostatically to x_b (as the mirror ghosts, mirror_walls.h;
//   SPlisHSPlasH mirrors P_a unchanged), P_a and P_b at least 0 so a wall never pulls: the pressure pair term
//   of the form Model::form; the near pressure mirrored unchanged;
// - friction [AIA12] eq. 11: the fluid's viscosity terms against the solid's velocity v_b, times the solid's
//   factor 1 - slip (0 on a free-slip wall).
struct BoundaryPairSides {
  PairSide fluid, wall;
  float rho0, inv_rho0;
};

SPH_HD inline BoundaryPairSides boundary_pair_sides(const PairSide& a) {
  BoundaryPairSides s{a, a, a.fluid->rest_density, 1.0f / a.fluid->rest_density};
  s.fluid.pressure = a.pressure > 0.0f ? a.pressure : 0.0f;
  s.fluid.pressure_rho2 = a.pressure > 0.0f ? a.pressure_rho2 : 0.0f;
  s.fluid.near_pressure = a.near_pressure > 0.0f ? a.near_pressure : 0.0f;
  s.fluid.near_pressure_rho2 = a.near_pressure > 0.0f ? a.near_pressure_rho2 : 0.0f;
  s.wall.rho = s.rho0;
  s.wall.inv_rho = s.inv_rho0;
  s.wall.near_pressure = s.fluid.near_pressure;
  s.wall.near_pressure_rho2 = s.fluid.near_pressure * s.inv_rho0 * s.inv_rho0;
  return s;
}

// The acceleration of the fluid particle from boundary particle b at x_a - xab (0 < r2 < h^2), volume V_b,
// velocity vb, friction factor. [m/s^2]
template <class Model>
SPH_HD_ALWAYS_INLINE Vec3 boundary_pair(const SimConstants& c, BoundaryPairSides& s, Vec3 xab, float r2, float volume,
                                        Vec3 vb, float friction, Vec3 normal) {
  const KernelCoeffs& k = c.kernel;
  s.wall.mass = s.rho0 * volume;
  s.wall.vel = vb;
  const float r = sqrtf(r2), inv_r = 1.0f / r;
  float f = 0.0f;
  if (Model::pressure) {
    // [Adami et al. 2012] eq. 27 for a wall at rest: P_b = P_a + rho0 g.(x_b - x_a), so a column at rest is
    // held without extra compression at the floor.
    const float pb = s.fluid.pressure - s.rho0 * dot(c.gravity, xab);
    const float pw = pb > 0.0f ? pb : 0.0f;
    f = pressure_pair<Model::form>(s.wall.mass, s.wall.mass, s.fluid.pressure, s.fluid.pressure_rho2, s.fluid.inv_rho, pw,
                                   pw * s.inv_rho0 * s.inv_rho0, s.wall.inv_rho) * gradient_dwdr(k, c.cubic_spline != 0, r) * inv_r;
    if (Model::near)
      f += pressure_pair<Model::form>(s.wall.mass, s.wall.mass, s.fluid.near_pressure, s.fluid.near_pressure_rho2, s.fluid.inv_rho,
                                      s.wall.near_pressure, s.wall.near_pressure_rho2, s.wall.inv_rho) * near_dwdr(k, r) * inv_r;
  }
  // The artificial viscosity at every wall on the velocity along the wall's normal, whatever the slip, as
  // against the mirror walls' ghosts (whose mirrored velocity differs from the particle's only there): without
  // it nothing damped a particle's motion into and out of the wall, and still water over a floor of boundary
  // particles heated up (docs/results.md); on the velocity along the wall only with the wall's friction
  // factor 1 - slip, as the laminar viscosity ([AIA12] eq. 11), so a free-slip wall does not drag.
  const float grad = gradient_dwdr(k, c.cubic_spline != 0, r) * inv_r;
  const Vec3 vab = s.fluid.vel - vb;
  if (c.artificial_enabled) {
    const Vec3 vn = dot(vab, normal) * normal;
    f += artificial_viscosity_pair(c, s.fluid, s.wall, xab, r2, vn + friction * (vab - vn)) * grad;
  }
  // Adhesion ([AKT13] eq. 6, calibrated from the fluid's contact angle: cohesion_energy.h): a pull towards the
  // boundary particle, -k_a Psi_b a(r / h) x_ab / r.
  if (!Model::viscous_only && c.adhesion_enabled)
    f -= s.fluid.fluid->adhesion * s.wall.mass * akinci_adhesion_shape(r / k.h) * inv_r;
  Vec3 acc = f * xab;
  if (friction > 0.0f) acc += friction * laminar_viscosity_pair(c, s.fluid, s.wall, r, r2, grad, vab);
  return acc;
}

// The static boundary particles' forces on fluid particle a at xa. [m/s^2]
template <class Model>
SPH_HD inline Vec3 boundary_forces(const SimConstants& c, const GridView& grid, const PairSide& a, Vec3 xa) {
  BoundaryPairSides s = boundary_pair_sides(a);
  const Vec3 zero{0.0f, 0.0f, 0.0f};
  Vec3 acc = zero;
  for_each_boundary(grid.boundary, xa, c.kernel.h2, [&](int32_t b, Vec3 xab, float r2, float volume) {
    if (r2 > 0.0f)
      acc += boundary_pair<Model>(c, s, xab, r2, volume, zero, grid.boundary.friction[b], xyz(grid.boundary.normal_depth[b]));
  });
  return acc;
}

// The rigid bodies' forces on fluid particle a at xa: their particles as boundary pairs moving with them. A
// loop of its own after the forces' (src/solvers/rigid_bodies.h): inside the forces loop the bodies' frames
// pushed the GPU kernel past its 80 registers into spills (ptxas, sm_90). [m/s^2]
template <class Model>
SPH_HD inline Vec3 body_forces(const SimConstants& c, const GridView& grid, const PairSide& a, Vec3 xa) {
  BoundaryPairSides s = boundary_pair_sides(a);
  Vec3 acc{0.0f, 0.0f, 0.0f};
  for_each_body_particle(grid.bodies, grid.num_bodies, xa, c.kernel.h2,
                         [&](int32_t k, int32_t b, Vec3 xab, float r2, float volume, Vec3 vb) {
                           const BodyView& body = grid.bodies[k];
                           if (r2 > 0.0f)
                             acc += boundary_pair<Model>(c, s, xab, r2, volume, vb, body.local.friction[b],
                                                         body_to_world(body, xyz(body.local.normal_depth[b])));
                         });
  return acc;
}

// What fluid particle a does to body k: the reaction to the accelerations boundary_forces gives a from the
// body's particles, force -m_a sum_b a_ab [N] and its torque about the body's centre, sum_b (x_b - c) x
// (-m_a a_ab) [N m] (the solver sums them over the fluid, src/solvers/rigid_bodies.h).
template <class Model>
SPH_HD inline void body_reaction(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t a, int32_t body,
                                 Vec3& force, Vec3& torque) {
  force = torque = Vec3{0.0f, 0.0f, 0.0f};
  if (p.age[a] < 0.0f) return;
  const PairSide side = particle_side(c, p, a);
  BoundaryPairSides s = boundary_pair_sides(side);
  const Vec3 xa = xyz(p.pos_mass[a]);
  const BodyView& bv = grid.bodies[body];
  const float ma = side.mass;
  for_each_body_particle(&bv, 1, xa, c.kernel.h2, [&](int32_t, int32_t b, Vec3 xab, float r2, float volume, Vec3 vb) {
    if (!(r2 > 0.0f)) return;
    const Vec3 f = -ma * boundary_pair<Model>(c, s, xab, r2, volume, vb, bv.local.friction[b],
                                              body_to_world(bv, xyz(bv.local.normal_depth[b])));
    force += f;
    torque += cross(xa - bv.centre - xab, f);
  });
}

// The cohesion between particle a and the other fluids' particles, which sets their interface tension
// (SimConstants::cross_cohesion, calibration.h): a loop of its own after the forces loop
// (src/solvers/surface_forces.h), run only where the scene gives an interface_tension; inside the forces loop
// the table's lookup pushed the GPU kernel past its 80 registers into spills (ptxas, sm_90). [m/s^2]
SPH_HD inline Vec3 interface_cohesion(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t a) {
  const KernelCoeffs& k = c.kernel;
  const uint8_t fa = p.fluid[a];
  Vec3 acc{0.0f, 0.0f, 0.0f};
  for_each_neighbour(grid, p.pos_mass, a, k.h2, [&](int32_t b, Vec3 xab, float r2) {
    const uint8_t fb = p.fluid[b];
    if (fb == fa || r2 <= 0.0f) return;
    const float cohesion = c.cross_cohesion[fa][fb];
    if (cohesion != 0.0f) acc -= cohesion_pair(k, cohesion, p.pos_mass[b].w, r2, xab);
  });
  return acc;
}

// The forces on particle a under the model Model (with_force_model picks it once per loop).
template <class Model>
SPH_HD inline void forces_with(const SimConstants& c, const GridView& grid, const ParticleView& p, int32_t a) {
  if (p.age[a] < 0.0f) {  // inlet particle: kinematic until it leaves the inlet (thesis 4.1.6)
    p.acc[a] = Vec3{0.0f, 0.0f, 0.0f};
    if (!Model::viscous_only && c.xsph_enabled) p.xsph_dv[a] = Vec3{0.0f, 0.0f, 0.0f};
    return;
  }
  const KernelCoeffs& k = c.kernel;
  const PairSide side_a = particle_side(c, p, a);
  const FluidConstants& fa = *side_a.fluid;
  const Vec3 xa = xyz(p.pos_mass[a]);
  const Vec3 va = side_a.vel;
  Vec3 acc{0.0f, 0.0f, 0.0f};
  Vec3 dv{0.0f, 0.0f, 0.0f};
  for_each_neighbour(grid, p.pos_mass, a, k.h2, [&](int32_t b, Vec3 xab, float r2) SPH_INLINE_LAMBDA {
    // r2 = 0: the particle itself, or a coincident one, which has no direction to push along.
    if (r2 <= 0.0f) return;
    const PairSide side_b = particle_side(c, p, b);
    const FluidConstants& fb = *side_b.fluid;
    const Vec3 vab = va - side_b.vel;
    pressure_viscosity_pair<Model>(c, side_a, side_b, xab, r2, vab, acc);
    const float mb = side_b.mass;
    if (Model::viscous_only) return;
    if (c.surface_tension_enabled && &fa == &fb) acc -= cohesion_pair(k, fa.cohesion, mb, r2, xab);
    if (c.xsph_enabled) {  // XSPH [Monaghan 1989]: v_a += eps sum m_b / rho_ab (v_b - v_a) W_ab
      dv -= xsph_pair_weight(k, c.cubic_spline != 0, fa.xsph, mb, r2, side_a.rho, side_b.rho) * vab;
    }
  });
  // Mirror walls: the ghosts of the neighbours, the particle's own included, add pressure, near pressure and
  // viscosity (mirror_walls.h). A second pass, so the loop above stays as lean as without walls.
  const NearWalls walls = c.mirror_walls ? near_walls(c, xa) : NearWalls{};
  for_each_ghost(c, grid, p, walls, a, [&](int32_t b, int32_t image, Vec3 xg, float r2) {
    if (r2 <= 0.0f) return;  // a ghost on the particle itself: no direction to push along
    PairSide ghost = particle_side(c, p, b);  // b's own, but the pressure extrapolated to the ghost
    const Vec3 vg = mirror_velocity(walls, image, ghost.vel);
    if (Model::pressure) {
      ghost.pressure = ghost_pressure(c, ghost.pressure, ghost.rho, xyz(p.pos_mass[b]), xg);
      ghost.pressure_rho2 = over_rho2(ghost.pressure, ghost.inv_rho);
    }
    const Vec3 xag = xa - xg;
    Vec3 pair{0.0f, 0.0f, 0.0f};
    pressure_viscosity_pair<Model>(c, side_a, ghost, xag, r2, va - vg, pair);
    acc += push_only(walls, xg, pair);
  });
  if (grid.boundary.n > 0) acc += boundary_forces<Model>(c, grid, side_a, xa);
  if (!Model::viscous_only) {
    acc += c.gravity;  // external forces, thesis eq. 2.25
    if (c.user_force.strength != 0.0f) acc += user_force_acceleration(c, xa);
  }
  p.acc[a] = acc;
  if (!Model::viscous_only && c.xsph_enabled) p.xsph_dv[a] = dv;
}

}  // namespace sph
