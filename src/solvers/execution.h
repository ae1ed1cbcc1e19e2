// The execution interface a solver's step is written against (issue 12, item 1). A solver (src/solvers/
// wcsph.h, dfsph.h, pbf.h) is its phases in order, each a loop of a per-particle functor or one of the few operations
// below; a back end implements this interface and nothing of the physics or of the order, so a new solver
// touches no back end. Back ends differ in scheduling only: `cpu` runs the loops serially (the reference),
// `host` on OpenMP, `cuda` as kernels on one stream (src/cuda/device_launch.h).
//
// An Exec type provides (as members; a compile-time interface, so that every loop is inlined or becomes
// its own kernel, with no virtual call per particle):
//
//   using Constants = ...;                   trivially copyable; *c gives const SimConstants& in the
//                                            functor's operator() (SPH_KERNEL_FN, sph_hd.h)
//   Constants constants();                   the reference a functor carries
//   const SimConstants& host_constants();    the same constants, read by the solver on the host to choose
//                                            its loops (density method, force model, shapes present)
//   ParticleView particles();                the particle arrays (particle_view.h) in the current order
//   GridView grid();                         the grid of the last build_grid()
//   SpringView springs();                    the viscoelastic springs (springs.h), capacity 0 without
//   void for_each(const F& f);               f(i) for every particle i, in any order or in parallel: f may
//                                            write only particle i's fields
//   void for_index(int32_t n, const F& f);   f(q) for every q < n (a loop over something else than the
//                                            particles: PBF's coarse cells), in any order or in parallel
//   void* scratch(std::size_t bytes);        memory the loops may use (8-byte aligned; host memory on cpu and
//                                            host, device memory on cuda), kept until the next call
//   double sum(int32_t n, const F& f);       f(0) + ... + f(n - 1) in reduction.h's fixed order (the same bits
//                                            on every back end), read back to the host: on cuda a copy
//                                            that waits for the enqueued work (the solvers' convergence test)
//   void build_grid();                       sort by (cell key, id), reorder every array, build the
//                                            tables (and on the CPU builds the neighbour lists), grid.h
//   void recycle();                          drop the particles expired() says have left (params.h),
//                                            keeping the others; the next build_grid() orders them
//   std::vector<RigidBody>& bodies();        the rigid bodies' host state (rigid_body.h)
//   void upload_bodies();                    their poses to the loops' GridView (after they moved)
//
// Every back end gives the same bits for the same phases: the functors are the same code, the grid's order
// is unique, and the only reduction across particles, sum(), has a fixed order.
#pragma once
