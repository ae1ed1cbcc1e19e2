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
}

// After the forces loop of a WCSPH or DFSPH step: the force into the acceleration that loop wrote.
template <class Exec>
void continuum_surface_force(Exec& x) {
  continuum_surface_force(x, x.particles().acc);
}

}  // namespace sph
