// The scene's "solver" and its own block ("dfsph" or "pbf"; issue 12), and the names of the solvers and
// integrators: part of the scene loader (scene_loader.cpp), kept apart so that each solver's keys are found
// in one place.
#include <cmath>
#include <sstream>
#include <string>

#include "scene.h"
#include "scene_reader.h"

namespace sph {

const char* integrator_name(Integrator m) {
  switch (m) {
    case Integrator::ExplicitEuler: return "explicit_euler";
    case Integrator::SemiImplicitEuler: return "semi_implicit_euler";
    case Integrator::VelocityVerlet: return "velocity_verlet";
    case Integrator::ModifiedVelocityVerlet: return "modified_velocity_verlet";
    case Integrator::Leapfrog: return "leapfrog";
  }
  return "?";
}

const char* solver_name(Solver m) {
  switch (m) {
    case Solver::Wcsph: return "wcsph";
    case Solver::Dfsph: return "dfsph";
    case Solver::Pbf: return "pbf";
  }
  return "?";
}

namespace scene_reading {

// "solver" and its own block ("dfsph" or "pbf"): a block for another solver than the one chosen is an error,
// not silently ignored.
void read_solver(ObjectReader& r, Scene& s) {
  const std::string& source = r.source();
  s.solver = r.choice<Solver>("solver", s.solver, {{"wcsph", Solver::Wcsph}, {"dfsph", Solver::Dfsph}, {"pbf", Solver::Pbf}});
  for (const Solver block : {Solver::Dfsph, Solver::Pbf}) {
    const std::string key = solver_name(block);
    if (r.has(key) && s.solver != block)
      fail(source, key,
           "this block holds the settings of solver \"" + key + "\", but solver is \"" + solver_name(s.solver) +
               "\"; set \"solver\": \"" + key + "\" or remove the block");
  }
  if (r.has("dfsph")) {
    ObjectReader dr(r.raw("dfsph"), source, "dfsph");
    dr.allow({"density_tolerance", "divergence_tolerance", "min_iterations", "max_iterations", "check_every",
              "divergence_solver", "warm_start", "warm_start_fraction", "chebyshev"});
    DfsphConstants& d = s.dfsph;
    d.density_tolerance = float(dr.number("density_tolerance", d.density_tolerance, 0.0, 0.1, true));
    d.divergence_tolerance = float(dr.number("divergence_tolerance", d.divergence_tolerance, 0.0, 1.0, true));
    d.min_iterations = int32_t(dr.integer("min_iterations", d.min_iterations, 1, 10000));
    d.max_iterations = int32_t(dr.integer("max_iterations", d.max_iterations, 1, 10000));
    if (d.min_iterations > d.max_iterations)  // name the values: a lowered max_iterations meets the default min
      fail(source, "dfsph.min_iterations",
           "value " + std::to_string(d.min_iterations) + " must not exceed dfsph.max_iterations = " +
               std::to_string(d.max_iterations) + " (min_iterations is " + std::to_string(dfsph_defaults().min_iterations) +
               " unless set)");
    d.check_every = int32_t(dr.integer("check_every", d.check_every, 1, 100));
    d.divergence_solver = dr.boolean("divergence_solver", d.divergence_solver != 0) ? 1 : 0;
    d.warm_start = dr.boolean("warm_start", d.warm_start != 0) ? 1 : 0;
    d.warm_start_fraction = float(dr.number("warm_start_fraction", d.warm_start_fraction, 0.0, 1.0, true));
    // Below 1: at rho = 1 the weights 4 / (4 - rho^2 omega) grow without bound.
    d.chebyshev = float(dr.number("chebyshev", d.chebyshev, 0.0, 0.99));
    dr.finish();
  }
  if (r.has("pbf")) {
    ObjectReader pr(r.raw("pbf"), source, "pbf");
    pr.allow({"iterations", "density_tolerance", "relaxation", "scorr_k", "scorr_n", "scorr_dq", "clamp_expansion",
              "xsph", "vorticity_epsilon", "jacobi_weight", "chebyshev", "artificial_viscosity",
              "coarse_grid", "coarse_iterations"});
    PbfConstants& b = s.pbf;
    b.iterations = int32_t(pr.integer("iterations", b.iterations, 1, 1000));
    b.density_tolerance = float(pr.number("density_tolerance", b.density_tolerance, 0.0, 0.1));
    // epsilon > 0: with none, a particle with few neighbours gets an unbounded lambda (a resting column blew up
    // within 0.2 s, measured).
    b.relaxation = float(pr.number("relaxation", b.relaxation, 0.0, 100.0, true));
    b.scorr_k = float(pr.number("scorr_k", b.scorr_k, 0.0, 10.0));
    b.scorr_n = int32_t(pr.integer("scorr_n", b.scorr_n, 1, 16));
    // dq / h is open at both ends, which number() does not print: checked here, in the stored precision
    // (W(dq) at dq = 1 is 0, the denominator of s_corr).
    const float dq = float(pr.number("scorr_dq", b.scorr_dq, -HUGE_VAL, HUGE_VAL));
    if (!(dq > 0.0f && dq < 1.0f)) {
      std::ostringstream os;
      os << "value " << dq << " is out of range: allowed (0, 1), a fraction of the support h";
      fail(source, "pbf.scorr_dq", os.str());
    }
    b.scorr_dq = dq;
    b.clamp_expansion = pr.boolean("clamp_expansion", b.clamp_expansion != 0) ? 1 : 0;
    b.xsph_c = float(pr.number("xsph", b.xsph_c, 0.0, 1.0));
    b.vorticity_epsilon = float(pr.number("vorticity_epsilon", b.vorticity_epsilon, 0.0, 1000.0));
    b.jacobi_weight = float(pr.number("jacobi_weight", b.jacobi_weight, 0.0, 1.0, true));
    b.chebyshev = float(pr.number("chebyshev", b.chebyshev, 0.0, 0.99));  // below 1, as dfsph.chebyshev
    b.artificial_viscosity = pr.boolean("artificial_viscosity", b.artificial_viscosity != 0) ? 1 : 0;
    b.coarse_grid = pr.boolean("coarse_grid", b.coarse_grid != 0) ? 1 : 0;
    b.coarse_iterations = int32_t(pr.integer("coarse_iterations", b.coarse_iterations, 1, 1000));
    pr.finish();
  }
}

}  // namespace scene_reading
}  // namespace sph
