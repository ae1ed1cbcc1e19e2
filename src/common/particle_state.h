// Particle state on the host: structure of arrays, one std::vector per field. The serial reference works on
// it directly; device back ends copy it in and out (upload / download).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "particle_view.h"
#include "vec3.h"

namespace sph {

// One particle to create: from an instant emitter at start-up or a jet emitter during the run.
struct Spawn {
  Vec3 pos;
  Vec3 vel;
  float age;      // < 0: still inside a jet's inlet, moved kinematically until age reaches 0
  float density;  // initial density (rest density: the continuity method integrates from there)
  uint8_t fluid;
  int32_t id;
};

// Every per-particle field, listed once: X(type, name). Wherever all fields are declared, resized, copied
// or moved (here and in the device arrays), this list is expanded, so adding a field is one line.
#define SPH_PARTICLE_FIELDS(X)                                                                     \
  X(Vec3, pos) X(Vec3, vel) X(Vec3, vel_force) X(Vec3, acc) X(Vec3, xsph_dv) X(float, density)      \
  X(float, near_density) X(float, pressure) X(float, near_pressure) X(float, age) X(uint8_t, fluid) \
  X(int32_t, id) X(Vec3, pos_start)

// Per-particle values derived from the fields above for the neighbour loops (issue 11, item 4), in the
// layout those loops read: pos_mass (x, y, z and the fluid's mass m, so density needs no fluid -> mass
// lookup) is written by the grid phase after its reorder (pack_position, particle_view.h); vel_inv_rho
// (vel_force and 1 / rho) and P / rho^2, P_near / rho^2 (so that the forces' pair loop has no division)
// by the pressure phase (pressure.h), before the forces read them. They are scratch: never copied,
// reordered, downloaded or written to frames; a restart recomputes them.
#define SPH_DERIVED_FIELDS(X) X(Vec4, pos_mass) X(Vec4, vel_inv_rho) X(float, pressure_rho2) X(float, near_pressure_rho2)

// The incompressible solvers' per-particle unknowns (src/solvers/dfsph.h, pbf.h): scratch like the derived
// fields, sized only while such a solver runs (fit_derived), written before every use within a step.
// - DFSPH: alpha [m^5/kg], kappa [m^2/s^2], solver_error (each particle's share of the error the solver
//   checks) and support (1: enough neighbours for the divergence solve, dfsph_support).
// - PBF: lambda [m^2], solver_error, delta_pos (the position correction [m], then the vorticity
//   confinement's acceleration [m/s^2]), omega (vorticity [1/s]) and pos_previous (the constraint
//   iteration's position one iteration back [m], for the Chebyshev weights).
// - The continuum surface force (surface_tension_csf.h), with any solver: surface_normal (the colour
//   gradient n [1/m]), curvature_own (each particle's own estimate [1/m]) and curvature (that estimate
//   limited by the neighbours', the one the force uses [1/m]).
// DFSPH's warm start, which must survive the reorder, is kept in the particle fields pressure and
// near_pressure (particle_view.h).
#define SPH_SOLVER_FIELDS(X) \
  X(float, alpha) X(float, kappa) X(float, lambda) X(float, solver_error) X(Vec3, delta_pos) X(Vec3, omega) \
  X(Vec3, pos_previous) X(int32_t, support) X(Vec3, surface_normal) X(float, curvature_own) X(float, curvature)

// Sizes the derived fields of `arrays` (ParticleState here, the device arrays in src/cuda/device_arrays.h:
// any type with the fields of these lists as resizable vectors) to n particles, and the solver fields to n
// when solver_fields is set, else to 0.
template <class Arrays>
void fit_derived_fields(Arrays& arrays, std::size_t n, bool solver_fields) {
#define SPH_FIT_DERIVED_FIELD(type, name) arrays.name.resize(n);
  SPH_DERIVED_FIELDS(SPH_FIT_DERIVED_FIELD)
#undef SPH_FIT_DERIVED_FIELD
#define SPH_FIT_SOLVER_FIELD(type, name) arrays.name.resize(solver_fields ? n : 0);
  SPH_SOLVER_FIELDS(SPH_FIT_SOLVER_FIELD)
#undef SPH_FIT_SOLVER_FIELD
}

struct ParticleState {
#define SPH_DECLARE_FIELD(type, name) std::vector<type> name;
  SPH_PARTICLE_FIELDS(SPH_DECLARE_FIELD)
  SPH_DERIVED_FIELDS(SPH_DECLARE_FIELD)
  SPH_SOLVER_FIELDS(SPH_DECLARE_FIELD)
#undef SPH_DECLARE_FIELD

  std::size_t size() const { return pos.size(); }

  // Resizes the particle fields; the derived ones are sized by fit_derived where a back end uses them.
  void resize(std::size_t n) {
#define SPH_RESIZE_FIELD(type, name) name.resize(n);
    SPH_PARTICLE_FIELDS(SPH_RESIZE_FIELD)
#undef SPH_RESIZE_FIELD
  }

  // Sizes the derived fields to the particle count (their values are written before every use), and the
  // solver fields too when solver_fields is set (else frees them).
  void fit_derived(bool solver_fields) { fit_derived_fields(*this, size(), solver_fields); }

  // After a swap with a reordering buffer: takes back the derived fields, so that only one of the two
  // states ever holds them (the memory estimate below counts them once).
  void take_derived(ParticleState& other) {
#define SPH_TAKE_DERIVED_FIELD(type, name) name.swap(other.name);
    SPH_DERIVED_FIELDS(SPH_TAKE_DERIVED_FIELD)
    SPH_SOLVER_FIELDS(SPH_TAKE_DERIVED_FIELD)
#undef SPH_TAKE_DERIVED_FIELD
  }

  void append(const Spawn& s) {
    const std::size_t i = size();
    resize(i + 1);
    pos[i] = s.pos;
    vel[i] = s.vel;
    vel_force[i] = s.vel;
    acc[i] = Vec3{0.0f, 0.0f, 0.0f};
    xsph_dv[i] = Vec3{0.0f, 0.0f, 0.0f};
    density[i] = s.density;
    near_density[i] = 0.0f;
    pressure[i] = 0.0f;
    near_pressure[i] = 0.0f;
    age[i] = s.age;
    fluid[i] = s.fluid;
    id[i] = s.id;
    pos_start[i] = s.pos;
  }

  // Copies particle `from` of `src` into slot `to` of this state (used by reordering and removal); the
  // derived fields are not copied (recomputed before use).
  void copy_particle(std::size_t to, const ParticleState& src, std::size_t from) {
#define SPH_COPY_FIELD(type, name) name[to] = src.name[from];
    SPH_PARTICLE_FIELDS(SPH_COPY_FIELD)
#undef SPH_COPY_FIELD
  }

  ParticleView view() {
    return ParticleView{int32_t(size()),      pos.data(),           vel.data(),      vel_force.data(),
                        acc.data(),           xsph_dv.data(),       density.data(),  near_density.data(),
                        pressure.data(),      near_pressure.data(), age.data(),      fluid.data(),
                        id.data(),            pos_start.data(),     pos_mass.data(), vel_inv_rho.data(),
                        pressure_rho2.data(), near_pressure_rho2.data(), alpha.data(),       kappa.data(),
                        lambda.data(),        solver_error.data(),       delta_pos.data(),   omega.data(),
                        pos_previous.data(),  support.data(),       surface_normal.data(),     curvature_own.data(),
                        curvature.data()};
  }
};

// Bytes of memory one particle needs at peak, used to refuse particle counts that cannot fit before
// allocating anything. The fields above take 97 bytes and the derived ones 40 (held by one state only:
// take_derived); the state, its reorder copy, the downloaded copy, the grid (sort records and the CPU
// sort's merge buffers, keys, block tables) and the CPU builds' neighbour lists (64 slots at the default
// 32 neighbours) make about eight times the 97. Measured peak resident size of scenes/dam_break.json
// (/usr/bin/time -v, 5 steps) at 128,000 particles, 2026-11-29 after issue 11: 727 bytes per particle on
// cpu, 816 on host (687 and 775 per added particle from 16k). The estimate, 816 bytes, is not below
// either.
constexpr std::size_t kParticleFieldBytes = 6 * sizeof(Vec3) + 5 * sizeof(float) + sizeof(uint8_t) + sizeof(int32_t);
constexpr std::size_t kDerivedFieldBytes = 2 * sizeof(Vec4) + 2 * sizeof(float);
// DFSPH, PBF and the continuum surface force add their solver fields, 64 bytes, counted here for every
// solver (not re-measured).
constexpr std::size_t kSolverFieldBytes = 6 * sizeof(float) + 3 * sizeof(Vec3) + sizeof(int32_t);
constexpr std::size_t kBytesPerParticle = 8 * kParticleFieldBytes + kDerivedFieldBytes + kSolverFieldBytes;

}  // namespace sph
