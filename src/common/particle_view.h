// Raw-pointer views of particle and grid arrays: trivially copyable, so the same struct is passed to a CUDA
// kernel, an OpenMP loop or the serial reference loop. Memory is owned elsewhere (ParticleState on the
// host, a RAII device buffer on the GPU).
#pragma once

#include <cstdint>

#include "boundary_view.h"
#include "params.h"
#include "vec3.h"

namespace sph {

struct ParticleView {
  int32_t n;
  Vec3* pos;
  Vec3* vel;            // the integrator's velocity state
  Vec3* vel_force;      // the velocity the forces see (differs per integrator, see integrate.h)
  Vec3* acc;            // last computed acceleration
  Vec3* xsph_dv;        // XSPH velocity correction from the forces pass (only when enabled)
  float* density;
  float* near_density;
  float* pressure;       // WCSPH: the equation of state's; DFSPH: rho kappa summed over the density solve [Pa],
                         // of which the next step's warm start carries dfsph.warm_start_fraction ([BK15] 4.3); PBF: 0
  float* near_pressure;  // WCSPH: near pressure; DFSPH: rho kappa_v dt summed over the divergence solve [Pa s],
                         // its warm start's source (as pressure)
  float* age;           // time since birth; < 0 while a jet particle is still in its inlet (kinematic)
  uint8_t* fluid;       // index into SimConstants::fluids
  int32_t* id;          // stable particle identity, survives reordering
  Vec3* pos_start;      // position at the start of the step: boundaries test the segment moved (boundaries.h)
  // Derived for the neighbour loops (SPH_DERIVED_FIELDS in particle_state.h), 16-byte records a GPU loads at once:
  Vec4* pos_mass;             // by the grid phase: x, y, z [m] and the fluid's mass [kg] (pack_position)
  Vec4* vel_inv_rho;          // by the pressure phase: vel_force [m/s] and 1 / rho [m^3/kg]
  float* pressure_rho2;       // by the pressure phase: P / rho^2 [m^5/(kg s^2)]
  float* near_pressure_rho2;  // by the pressure phase: P_near / rho^2, 0 without near pressure
  // The incompressible solvers' scratch (SPH_SOLVER_FIELDS in particle_state.h), null where
  // needs_solver_fields is false:
  float* alpha;         // DFSPH: alpha factor [m^5/kg]
  float* kappa;         // DFSPH: this iteration's stiffness kappa or kappa_v [m^2/s^2]
  float* lambda;        // PBF: Lagrange multiplier lambda [m^2]
  float* solver_error;  // each particle's share of the error the solver checks (dimensionless)
  Vec3* delta_pos;      // PBF: position correction [m]; after the solve, vorticity confinement [m/s^2]
  Vec3* omega;          // PBF: vorticity [1/s]
  Vec3* pos_previous;   // PBF: the constraint solve's position one iteration back [m] (Chebyshev weights)
  int32_t* support;     // DFSPH: 1 where the neighbourhood is full enough for the divergence solve
  Vec3* surface_normal; // continuum surface force: colour gradient n [1/m] (surface_tension_csf.h)
  float* curvature_own;  // continuum surface force: each particle's own estimate of the mean curvature [1/m], or
                         // kCsfNoCurvature where it has too few neighbours with a normal to make one
  float* curvature;     // continuum surface force: mean curvature kappa [1/m], curvature_own limited by the
                        // neighbours' (csf_limited_curvature), the force's
};

// Whether a step needs the solver fields above: the incompressible solvers and the continuum surface force.
inline bool needs_solver_fields(const SimConstants& c) { return c.solver != Solver::Wcsph || c.csf_enabled != 0; }

// The grid phase's part of the derived fields, after its reorder: particle i's position with its mass
// (the same float as c.fluids[fluid].mass, so sums keep their bits).
SPH_HD inline void pack_position(const SimConstants& c, const ParticleView& p, int32_t i) {
  p.pos_mass[i] = with_w(p.pos[i], c.fluids[p.fluid[i]].mass);
}

// The neighbour grid of the current particle order (grid.h, grid_build.h); arrays owned by the back end.
struct GridView {
  GridGeometry geom;
  const uint64_t* key;              // n: cell key of each particle, ascending
  const int32_t* particle_block;    // n: index of each particle's block
  const int32_t* block_neighbours;  // 27 per block: the blocks at offsets (-1..1)^3, z slowest; -1 = none
  const int32_t* cell_start;        // 129 per block: first particle of each of its 128 cells, then its end
  // CPU builds only (nullptr on the GPU, and where lists would be too long): each particle's neighbours
  // within h, in the search's order, list_capacity + kNeighbourListPad slots per particle, and their count
  // (not below list_capacity: the list is incomplete, search instead).
  const int32_t* neighbour_list;
  const int32_t* neighbour_count;
  int32_t list_capacity;
  // Blocks from block_capacity on have no tables (the device build sizes them from an earlier step's block
  // count, grid.h): a search finds their neighbours and cell ranges by binary search over these.
  const int32_t* block_begin;  // blocks + 1: each block's first particle, then n
  const uint64_t* block_code;  // blocks: each block's Morton code, ascending
  const int32_t* block_count;  // one value: blocks (device memory on the device build)
  int32_t block_capacity;      // blocks [0, block_capacity) have cell_start and block_neighbours entries
  BoundaryView boundary;       // the static boundary particles (boundary_view.h); n = 0 without
  const BodyView* bodies;      // the rigid bodies this step (boundary_view.h), num_bodies of them
  int32_t num_bodies;
};

}  // namespace sph
