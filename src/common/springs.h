// Viscoelastic fluids (issue 15): springs between close particles of an elastic fluid, created once at the
// start with their distance as rest length (Clavet, Beaudoin & Poulin 2005, section 5; thesis 2.2.6, eq.
// 2.26). A spring of stiffness k pulls its two particles with -k (r - L) along x_ab, equal and opposite; its
// rest length L yields when stretched or squeezed beyond gamma L: L += dt alpha sign(r - L) (|r - L| - gamma L)
// (Clavet's plasticity, so that a deformation held long enough is kept: the fluid flows, viscoelastically); a
// spring whose rest length grows past h breaks. alpha = 0 is an elastic jelly.
//
// Unlike Clavet's, the springs' stiffness depends on their rest length at the start (spring_law below), so
// that the network on the start's cubic lattice is isotropic with the shear modulus asked.
//
// Storage is by particle id, so that the grid's reorder never moves it: each id has `capacity` slots of
// (partner id, rest length, stiffness), both ends of a spring holding it with the same rest length (their
// updates are the same arithmetic on the same |x_ab|, so they stay equal) and the same stiffness.
// index_of_id maps an id to the particle's place in the current order; the solver rebuilds it after each
// grid build (index_particle).
#pragma once

#include <cstdint>
#include <vector>

#include "params.h"
#include "particle_state.h"
#include "particle_view.h"

namespace sph {

// The springs as the loops see them (arrays in the back end's memory).
struct SpringView {
  int32_t capacity;      // slots per id; 0: no springs
  int32_t num_ids;       // ids below this may have springs (the particles present at the start)
  int32_t* partner;      // num_ids x capacity: the partner's id, or -1 (none or broken)
  float* rest;           // num_ids x capacity: rest length L [m]
  float* stiffness;      // num_ids x capacity: the spring's k / m [1/s^2], fixed at the start (spring_law)
  int32_t* index_of_id;  // num_ids: the particle's index in the current order
};

// The springs on the host (set-up, the serial reference's storage).
struct SpringNetwork {
  int32_t capacity = 0;
  std::vector<int32_t> partner;
  std::vector<float> rest;
  std::vector<float> stiffness;
  std::vector<int32_t> index_of_id;
  bool empty() const { return capacity == 0; }
  std::size_t bytes() const { return partner.size() * 12 + index_of_id.size() * 4; }
  SpringView view() {
    return SpringView{capacity, int32_t(index_of_id.size()), partner.data(), rest.data(), stiffness.data(),
                      index_of_id.data()};
  }
};

// The most springs one particle may hold: at the default 32 neighbours a lattice particle has 26 within h.
constexpr int32_t kMaxSpringsPerParticle = 64;

// The springs' stiffness for a network of shear modulus G [Pa] on the cubic lattice of spacing d [m] that
// set-up lays the particles on, with bonds to every lattice point within the support h [m]:
// k(L) = stiffness (d / L)^exponent [N/m] for a spring of rest length L.
// Under a small uniform strain eps a bond x (length r, stiffness k_b) stretches by x.eps.x / r and stores
// k_b (x_i x_j x_k x_l / r^2) eps_ij eps_kl / 2; each bond is shared by two particles, so per particle volume
// d^3 the network's elastic tensor is C_ijkl = sum_b k_b x_i x_j x_k x_l / (2 d^3 r_b^2). Central bonds give
// C12 = C44 (Cauchy's relation, Poisson's ratio 1/4 if isotropic). On a cubic lattice the network is
// isotropic only if C11 - C12 = 2 C44, i.e. sum_b k_b (x^4 - 3 x^2 y^2) / r_b^2 = 0. With one stiffness for
// every bond (Clavet's springs) it is not: at h = 1.97 d, 2 C44 / (C11 - C12) = 2.33, and a jelly ball's
// torsional period measured 0.94 of the isotropic theory's when twisted about a lattice axis and 1.28 about
// a body diagonal (docs/results.md). So k_b = stiffness (d / r_b)^exponent, the exponent the root of that
// sum (2.7 at 32 neighbours), and stiffness from C44 = G. Throws std::invalid_argument when h <= sqrt(2) d
// (the bonds along the axes alone carry no shear) or when no exponent in [-8, 24] makes the sum vanish.
// G = 0: {0, 0}.
struct SpringLaw {
  double stiffness;  // k at L = d [N/m]
  double exponent;   // p
};
SpringLaw spring_law(double modulus, double spacing, double h);

// The fastest angular frequency [1/s] of the spring network of a fluid with k / m = stiffness_per_mass
// (d / L)^exponent [1/s^2] (spring_law) on the start's cubic lattice of spacing d [m] and support h [m]:
// omega_max^2 <= 2/3 sum_b k_b / m over one particle's bonds. The lattice's dynamical matrix at wave vector q
// is D(q) = sum_b k_b (1 - cos q.x_b) e_b e_b^T / m, each term at most 2 k_b e_b e_b^T / m, and on the cubic
// lattice sum_b k_b e_b e_b^T = (sum_b k_b / 3) I. (Gershgorin's bound on the stiffness matrix, 2 sum_b k_b /
// m, is 3 times that: a step at its limit would be 1.7 times shorter than needed; tests/test_viscoelastic.cpp
// measures 0.96 of this bound on a 7^3 block.) An explicit step (symplectic Euler, as DFSPH advances its
// non-pressure forces) is stable for omega dt < 2; DFSPH's step keeps omega_max dt below a fraction of that
// (time_step.h, choose_incompressible_step), which also covers a network strained away from the lattice. The
// stiffness is fixed at the start (plasticity changes rest lengths only). 0 without springs.
double spring_rate(double stiffness_per_mass, double exponent, double spacing, double h);

// Springs between every two particles of one fluid with spring_stiffness > 0 closer than h, with their
// distance L as rest length and k / m = spring_stiffness (d / L)^spring_exponent (spring_law; d: the
// lattice spacing [m]). Empty when no fluid has springs. Throws std::invalid_argument when a particle would
// hold more than kMaxSpringsPerParticle springs. ps: the particles at the start (ids 0..n-1).
SpringNetwork create_springs(const SimConstants& c, const ParticleState& ps, double spacing);

// After a grid build: particle i's place under its id.
SPH_HD inline void index_particle(const SpringView& s, const ParticleView& p, int32_t i) {
  const int32_t id = p.id[i];
  if (id >= 0 && id < s.num_ids) s.index_of_id[id] = i;
}

// Particle i's acceleration from its springs this step [m/s^2], with the plasticity and breaking of its own
// copies of them (dt [s]), the springs measured between the positions x_of(j) [m] (any callable int32_t ->
// Vec3: WCSPH and DFSPH read the grid's pos_mass, PBF the step's start, p.pos). A partner that has left the
// simulation breaks its spring.
template <class Positions>
SPH_HD inline Vec3 spring_acceleration_at(const SimConstants& c, const SpringView& s, const ParticleView& p, int32_t i,
                                          float dt, Positions x_of) {
  Vec3 acc{0.0f, 0.0f, 0.0f};
  const int32_t id = p.id[i];
  const FluidConstants& f = c.fluids[p.fluid[i]];
  if (id < 0 || id >= s.num_ids || f.spring_stiffness == 0.0f) return acc;
  const Vec3 xi = x_of(i);
  for (int32_t slot = id * s.capacity, end = slot + s.capacity; slot < end; ++slot) {
    const int32_t partner = s.partner[slot];
    if (partner < 0) continue;
    const int32_t j = s.index_of_id[partner];
    if (j < 0 || j >= p.n || p.id[j] != partner) {
      s.partner[slot] = -1;
      continue;
    }
    const Vec3 xij = xi - x_of(j);
    const float r = sqrtf(dot(xij, xij));
    float rest = s.rest[slot];
    const float tolerated = f.spring_yield * rest;  // Clavet's plasticity (above)
    if (r > rest + tolerated) rest += dt * f.spring_plasticity * (r - rest - tolerated);
    else if (r < rest - tolerated) rest -= dt * f.spring_plasticity * (rest - tolerated - r);
    if (rest > c.kernel.h || !(r > 0.0f)) {
      s.partner[slot] = -1;
      continue;
    }
    s.rest[slot] = rest;
    acc -= (s.stiffness[slot] * (r - rest) / r) * xij;
  }
  return acc;
}

// spring_acceleration_at with the positions the grid phase wrote (pos_mass): WCSPH's and DFSPH's forces.
SPH_HD inline Vec3 spring_acceleration(const SimConstants& c, const SpringView& s, const ParticleView& p, int32_t i,
                                       float dt) {
  return spring_acceleration_at(c, s, p, i, dt, [&](int32_t j) { return xyz(p.pos_mass[j]); });
}

}  // namespace sph
