// The energy surface tension can release, for the energy budget (simulation.h): the cohesion (forces.h,
// cohesion_pair) is the pair potential u(r) = -gamma m_a m_b int_r^h C(s) ds between particles of one fluid,
// and a particle at a surface misses part of the bulk's (negative) share of it. Summed, that excess is the
// surface energy sigma A of the calibration (calibration.h); cohesion can turn at most this into motion
// (a cube pulling into a sphere releases sigma times the area it loses), so a drop that gains more is
// flagged as unstable like any other energy gain. Under the continuum surface force, with no solid about
// the fluid, the budget counts sigma times the start's area less the ball's sigma A it cannot go below.
#pragma once

#include <optional>
#include <vector>

#include "params.h"
#include "particle_state.h"
#include "scene.h"

namespace sph {

// int_q^1 c(s) ds of the cohesion kernel's shape c (kernels.h, akinci_cohesion_shape), 0 <= q <= 1.
double akinci_cohesion_potential_shape(double q);

// int_q^1 a(s) ds of the adhesion kernel's shape a (kernels.h, akinci_adhesion_shape), 0 <= q <= 1: with s = 3/4 -
// cos(phi) / 4, a = sqrt(sin(phi) / 2), a smooth integrand in phi (Simpson, 512 intervals; within 1e-5 of
// the midpoint rule on the kernel itself, tests/test_adhesion.cpp).
double akinci_adhesion_potential_shape(double q);

// The adhesion constant k_a [m/(kg s^2)] of a fluid with cohesion constant `cohesion` (its fluids.N.cohesion,
// calibrated to sigma: calibration.h) that meets boundary particles at the contact angle theta [degrees],
// on the lattice of spacing d [m] with support h [m] that set-up lays the fluid and the walls on. The adhesion
// pair force -k_a m_a Psi_b a(r / h) x_ab / r ([AKT13] eq. 6 with their kernel A, eq. 7; Psi_b = rho0 V_b, the
// fluid's mass on the lattice) is the pair potential -k_a m^2 h int_{r/h}^1 a, as the cohesion's is
// -gamma' m^2 h int_{r/h}^1 c. The work per area to part the fluid from a wall is then W_a = k_a m^2 h B_a / d^2
// and to part the fluid from itself W_c = gamma' m^2 h B_c / d^2 = 2 sigma_eff, B the half-lattice bindings
// (lattice_sum.h) of the two potential shapes; Young and Dupre: a liquid meets its wall at theta when
// W_a = sigma (1 + cos theta) = W_c (1 + cos theta) / 2, so k_a = gamma' (1 + cos theta) / 2 B_c / B_a. Taken
// on the lattice rather than in the continuum, where the same ratio is J_C4 / J_A4 (int q^4 of the shapes):
// the lattice binds with the cohesion kernel at 0.75 of its continuum value and with the adhesion kernel at
// 0.93, so the continuum ratio would make every wall 24% more wetting than asked. theta = 180: no adhesion;
// theta -> 0: the wall binds as the fluid itself does (complete wetting).
double adhesion_constant(double cohesion, double contact_angle_deg, double spacing, double h);

// The adhesion energy one particle of a fluid with adhesion constant k_a and mass m releases by reaching a wall
// [J/kg]: its binding in the first layer at a flat wall of boundary particles, k_a m h sum_b int_{r_b/h}^1 a
// over the wall's half-lattice. The energy budget (simulation.cpp) counts it for every particle, as if each
// could reach a wall. An estimate, not a bound on one particle: one pressed closer than a spacing to the wall
// binds more (15% at 0.9 d), one in an edge or a corner of walls about 2 or 3 times as much.
double adhesion_first_layer_energy(double adhesion, double mass, double spacing, double h);

// The work of adhesion one particle of a fluid with surface tension sigma [N/m] and mass m [kg] releases by
// reaching a wall it meets at the contact angle theta [degrees] under the continuum surface force
// (surface_tension_csf.h) [J/kg]: Young and Dupre's sigma (1 + cos theta) over the particle's face d^2, d
// the spacing [m]. The energy budget counts it for every particle, as adhesion_first_layer_energy above.
double csf_contact_energy(double sigma, double contact_angle_deg, double spacing, double mass);

// Per particle of ps, its cohesive energy above that of a particle inside a cubic lattice of spacing d
// filled with its fluid [J/kg], e_a = 1/2 sum_b u(r_ab) over the particles of its fluid, (e_a - e_bulk) / m_a,
// at least 0. All zero (and no neighbour search) where no fluid has surface tension. ps: positions, fluids.
std::vector<double> cohesion_excess_energy(const SimConstants& c, const ParticleState& ps, double spacing);

// Per particle of ps, its share of the surface energy of its fluid's sigma [J/kg]: sigma d^2 / m for each of
// the six faces of its lattice cell (spacing d [m]) beyond which no particle of its fluid stands within d / 4
// of the next lattice site. Summed with the masses: sigma times the area of the union of the particles' cells
// where the fluid stands on a cubic lattice, as emitters lay it out (a box's own area); elsewhere more (a
// particle away from the lattice counts up to all six faces), so a budget built on it is never too small.
// Zero for fluids without sigma.
std::vector<double> lattice_surface_energy(const Scene& scene, const SimConstants& c, const ParticleState& ps, double spacing);

// The least surface energy [J] the fluids of ps can reach under the continuum surface force, where the
// isoperimetric inequality gives it: a fluid of volume V (its particles' mass over rest density) has at
// least the area of a ball, 4 pi (3 V / (4 pi))^(2/3), in one piece or in many, so sigma times that is
// never released. Only where nothing else bounds the fluid: no container, wall, obstacle, mesh or body (a
// fluid spread on a solid has less free surface: a half ball on a plate 0.79 of a ball's) and no interface
// tension between fluids. std::nullopt elsewhere, and under the cohesion model.
std::optional<double> least_surface_energy(const Scene& scene, const SimConstants& c, const ParticleState& ps);

}  // namespace sph
