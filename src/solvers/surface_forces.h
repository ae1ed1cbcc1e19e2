// The continuum surface force (src/common/surface_tension_csf.h) as loops of a solver's forces phase, shared
// by WCSPH, DFSPH and PBF: the colour gradient of every particle, then its own estimate of the curvature
// (which reads its neighbours' gradients), then that estimate limited by its neighbours' (which reads their
// estimates), then the force added to an acceleration (the one the forces loop wrote; PBF's own array). And the cohesion between two
// fluids that sets their interface tension (forces.h, interface_cohesion), also after the forces loop.
#pragma once

#include <cstdint>

#include "../common/forces.h"
#include "../common/particle_view.h"
#include "../common/sph_hd.h"
#include "../common/surface_tension_csf.h"

namespace sph {

template <class C>
struct CsfNormalFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { p.surface_normal[i] = csf_normal(*c, g, p, i); }
};

// The second pass of the colour gradient under a contact angle, in place (it reads no neighbour's normal).
template <class C>
struct CsfContactNormalFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { p.surface_normal[i] = csf_contact_normal(*c, g, p, i); }
};

template <class C>
struct CsfCurvatureFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { p.curvature_own[i] = csf_curvature(*c, g, p, i); }
};

template <class C>
struct CsfLimitCurvatureFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const { p.curvature[i] = csf_limited_curvature(*c, g, p, i); }
};

// The force as an acceleration added to out [m/s^2] (p.acc under WCSPH and DFSPH).
template <class C>
struct CsfForceFn {
  C c;
  ParticleView p;
  Vec3* out;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) out[i] += csf_acceleration(*c, p, i);
  }
};

// The force of a fluid with an interface tension (surface_tension_csf.h, csf_interface_acceleration).
template <class C>
struct CsfInterfaceForceFn {
  C c;
  GridView g;
  ParticleView p;
  Vec3* out;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) out[i] += csf_interface_acceleration(*c, g, p, i);
  }
};

// A free drop's momentum (SimConstants::csf_momentum): m_i times component `axis` of particle i's force
// (axis 3: m_i) where i is of `fluid` and has a normal, else 0; summed over the particles (Exec::sum).
template <class C>
struct CsfMomentumOf {
  C c;
  ParticleView p;
  int32_t fluid, axis;
  SPH_HD double operator()(int32_t i) const {
    if (p.age[i] < 0.0f || int32_t(p.fluid[i]) != fluid || !csf_has_normal(*c, p, i)) return 0.0;
    const double m = double(p.pos_mass[i].w);
    if (axis == 3) return m;
    const Vec3 a = csf_acceleration(*c, p, i);
    return m * double(axis == 0 ? a.x : (axis == 1 ? a.y : a.z));
  }
};

// Subtracts from each particle with a normal its fluid's net force over their mass, `mean` [m/s^2].
template <class C>
struct CsfMomentumRemoveFn {
  C c;
  ParticleView p;
  Vec3* out;
  Vec3 mean[kMaxFluids];
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f && csf_has_normal(*c, p, i)) out[i] -= mean[p.fluid[i]];
  }
};

template <class C>
struct InterfaceCohesionFn {
  C c;
  GridView g;
  ParticleView p;
  SPH_KERNEL_FN void operator()(int32_t i) const {
    if (p.age[i] >= 0.0f) p.acc[i] += interface_cohesion(*c, g, p, i);
  }
};

// After the forces loop of a step whose constants give two fluids a cohesion (an interface tension).
template <class Exec>
void interface_cohesion_forces(Exec& x) {
  if (!x.host_constants().interface_cohesion_enabled) return;
  using C = typename Exec::Constants;
  x.for_each(InterfaceCohesionFn<C>{x.constants(), x.grid(), x.particles()});
}

// The continuum surface force, where the constants enable it, at the positions the grid's pos_mass holds and
// the densities in p.density, added to out [m/s^2] (one entry per particle).
template <class Exec>
void continuum_surface_force(Exec& x, Vec3* out) {
  if (!x.host_constants().csf_enabled) return;
  using C = typename Exec::Constants;
  x.for_each(CsfNormalFn<C>{x.constants(), x.grid(), x.particles()});
  if (x.host_constants().csf_contact_enabled) x.for_each(CsfContactNormalFn<C>{x.constants(), x.grid(), x.particles()});
  x.for_each(CsfCurvatureFn<C>{x.constants(), x.grid(), x.particles()});
  x.for_each(CsfLimitCurvatureFn<C>{x.constants(), x.grid(), x.particles()});
  if (x.host_constants().csf_interface_enabled)
    x.for_each(CsfInterfaceForceFn<C>{x.constants(), x.grid(), x.particles(), out});
  else
    x.for_each(CsfForceFn<C>{x.constants(), x.particles(), out});
  // A free drop: sum_i V_i sigma kappa_i n_i vanishes on a closed surface in the continuum but not on the
  // particles, and its remainder moved the drop (its centre at 2.8 mm/s after 1 s at sigma = 4.7 N/m, 0.6 m/s
  // at 300 N/m; docs/results.md, "A drop's energy budget"). Each fluid's net force, spread over the mass
  // that feels the force, is taken off it again.
  if (!x.host_constants().csf_momentum) return;
  CsfMomentumRemoveFn<C> remove{x.constants(), x.particles(), out, {}};
  bool any = false;
  for (int32_t f = 0; f < x.host_constants().num_fluids; ++f) {
    if (x.host_constants().fluids[f].csf_sigma == 0.0f) continue;
    const int32_t n = x.particles().n;
    const double mass = x.sum(n, CsfMomentumOf<C>{x.constants(), x.particles(), f, 3});
    if (!(mass > 0.0)) continue;
    remove.mean[f] = Vec3{float(x.sum(n, CsfMomentumOf<C>{x.constants(), x.particles(), f, 0}) / mass),
                          float(x.sum(n, CsfMomentumOf<C>{x.constants(), x.particles(), f, 1}) / mass),
                          float(x.sum(n, CsfMomentumOf<C>{x.constants(), x.particles(), f, 2}) / mass)};
    any = true;
  }
  if (any) x.for_each(remove);
}

// After the forces loop of a WCSPH or DFSPH step: the force into the acceleration that loop wrote.
template <class Exec>
void continuum_surface_force(Exec& x) {
  continuum_surface_force(x, x.particles().acc);
}

}  // namespace sph
