// The energy surface tension can release, for the energy budget (simulation.h): the cohesion (forces.h,
// cohesion_pair) is the pair potential u(r) = -gamma m_a m_b int_r^h C(s) ds between particles of one fluid,
// and a particle at a surface misses part of the bulk's (negative) share of it. Summed, that excess is the
// surface energy sigma A of the calibration (guided_creation.h); cohesion can turn at most this into motion
// (a cube pulling into a sphere releases sigma times the area it loses), so a drop that gains more is
// flagged as unstable like any other energy gain.
#pragma once

#include <vector>

#include "params.h"
#include "particle_state.h"

namespace sph {

// int_q^1 c(s) ds of the cohesion kernel's shape c (kernels.h, akinci_cohesion_shape), 0 <= q <= 1.
double akinci_cohesion_potential_shape(double q);

// Per particle of ps, its cohesive energy above that of a particle inside a cubic lattice of spacing d
// filled with its fluid [J/kg], e_a = 1/2 sum_b u(r_ab) over the particles of its fluid, (e_a - e_bulk) / m_a,
// at least 0. All zero (and no neighbour search) where no fluid has surface tension. ps: positions, fluids.
std::vector<double> cohesion_excess_energy(const SimConstants& c, const ParticleState& ps, double spacing);

}  // namespace sph
