// sph_oscillators: the thesis's integrator comparison (thesis 2.3.2 to 2.3.4) with this project's
// integrators (src/common/integrate.h, the code the fluid uses). A mass M = 250 kg on a spring of stiffness
// K, x0 = 0.5 m, dt = 0.1 s, undamped or critically damped (C = 2 sqrt(K M)). For each integrator: the
// largest stable K (bisection on the growth over 2000 steps) and the energy drift at K = 100.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli_errors.h"
#include "common/integrate.h"
#include "common/scene.h"

using namespace sph;

namespace {

constexpr double kMass = 250.0, kX0 = 0.5, kDt = 0.1;

struct Run {
  double max_abs_x = 0.0;
  double early_amplitude = 0.0;   // max |x| over steps [n/4, n/2)
  double late_amplitude = 0.0;    // max |x| over steps [3n/4, n)
  double energy_drift = 0.0;      // (E_end - E_0) / E_0
  double energy_max_dev = 0.0;    // max |E - E_0| / E_0
};

Run simulate(Integrator m, double k, bool damped, int steps) {
  const double c = damped ? 2.0 * std::sqrt(k * kMass) : 0.0;
  auto accel = [&](double x, double v) { return -(k / kMass) * x - (c / kMass) * v; };
  double x = kX0, v = 0.0, vf = 0.0, a = accel(x, v);
  auto energy = [&] { return 0.5 * kMass * v * v + 0.5 * k * x * x; };
  const double e0 = energy();
  Run r;
  for (int i = 0; i < steps && std::isfinite(x); ++i) {
    integrate_predict(m, x, v, vf, a, kDt);
    a = accel(x, vf);
    integrate_correct(m, x, v, a, kDt);
    r.max_abs_x = std::max(r.max_abs_x, std::fabs(x));
    if (i >= steps / 4 && i < steps / 2) r.early_amplitude = std::max(r.early_amplitude, std::fabs(x));
    if (i >= 3 * steps / 4) r.late_amplitude = std::max(r.late_amplitude, std::fabs(x));
    r.energy_max_dev = std::max(r.energy_max_dev, std::fabs(energy() - e0) / e0);
  }
  if (!std::isfinite(x)) r.max_abs_x = r.late_amplitude = INFINITY;
  r.energy_drift = (energy() - e0) / e0;
  return r;
}

// Stable: the motion does not grow. Over 4000 steps (400 s) the amplitude of the last quarter is at most
// 1% above that of the second quarter (a bounded orbit, however elongated, or a decay passes; explicit
// Euler's slow growth does not).
bool stable(Integrator m, double k, bool damped) {
  const Run r = simulate(m, k, damped, 4000);
  return std::isfinite(r.late_amplitude) && r.late_amplitude <= 1.01 * r.early_amplitude + 1e-300;
}

double critical_stiffness(Integrator m, bool damped) {
  double lo = 1.0, hi = 1e7;
  if (!stable(m, lo, damped)) return 0.0;
  if (stable(m, hi, damped)) return hi;
  for (int i = 0; i < 60; ++i) {
    const double mid = std::sqrt(lo * hi);
    (stable(m, mid, damped) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "out/oscillators";
  CLI::App app{"sph_oscillators: largest stable stiffness and energy drift of each integrator on the thesis's oscillators"};
  sph::use_error_prefix(app);
  app.add_option("--out,-o", out, "output directory (oscillators.csv, oscillators.md)")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;  // --help: 0; every parse error is bad input (CLI11's own codes are 100+)
  }

  struct Row {
    Integrator m;
    const char* thesis_undamped;  // what the thesis observed (section 2.3.2)
    const char* thesis_damped;    // section 2.3.3
  };
  const std::vector<Row> rows{
      {Integrator::ExplicitEuler, "diverges at every K (even 100)", "the most stable (still stable at 20000)"},
      {Integrator::SemiImplicitEuler, "gains energy at 1e5", "stable at 15000, unstable at 20000"},
      {Integrator::VelocityVerlet, "stable at 1e5 (loses energy)", "unstable at 15000"},
      {Integrator::ModifiedVelocityVerlet, "(not in the undamped test)", "stable at 15000, unstable at 20000"},
      {Integrator::Leapfrog, "gains energy at 1e4", "unstable at 15000"}};

  std::error_code made;
  std::filesystem::create_directories(out, made);
  std::ofstream csv(out + "/oscillators.csv"), md(out + "/oscillators.md");
  if (made || !csv || !md) {
    std::fprintf(stderr, "error: --out %s: cannot write oscillators.csv and oscillators.md there%s%s\n", out.c_str(),
                 made ? ": " : "", made ? made.message().c_str() : "");
    return 1;
  }
  csv << "integrator,k_crit_undamped,omega_dt_crit_undamped,k_crit_damped,omega_dt_crit_damped,energy_drift_k100_300_steps,"
         "energy_max_dev_k100_10000_steps,energy_drift_k100_10000_steps\n";
  md << "| integrator | largest stable K, undamped (omega dt) | thesis, undamped | largest stable K, damped (omega dt) | "
        "thesis, damped | energy drift at K = 100: 30 s / 1000 s (max deviation) |\n|---|---|---|---|---|---|\n";
  std::printf("M = %.0f kg, x0 = %.1f m, dt = %.1f s; damped: C = 2 sqrt(K M)\n\n", kMass, kX0, kDt);
  for (const Row& row : rows) {
    const double ku = critical_stiffness(row.m, false), kd = critical_stiffness(row.m, true);
    const double wu = std::sqrt(ku / kMass) * kDt, wd = std::sqrt(kd / kMass) * kDt;
    const Run short_run = simulate(row.m, 100.0, false, 300), long_run = simulate(row.m, 100.0, false, 10000);
    const char* name = integrator_name(row.m);
    char ku_s[64], kd_s[64];
    std::snprintf(ku_s, sizeof ku_s, ku > 0.0 ? "%.0f (%.3f)" : "none (unstable at K = 1)", ku, wu);
    std::snprintf(kd_s, sizeof kd_s, "%.0f (%.3f)", kd, wd);
    std::printf("%-26s undamped K_crit %-26s damped K_crit %-18s E drift K=100: %+.3e (300 steps), %+.3e (10000 steps, max %.3e)\n",
                name, ku_s, kd_s, short_run.energy_drift, long_run.energy_drift, long_run.energy_max_dev);
    csv << name << ',' << ku << ',' << wu << ',' << kd << ',' << wd << ',' << short_run.energy_drift << ','
        << long_run.energy_max_dev << ',' << long_run.energy_drift << '\n';
    char drift[128];
    std::snprintf(drift, sizeof drift, "%+.2e / %+.2e (%.2e)", short_run.energy_drift, long_run.energy_drift, long_run.energy_max_dev);
    md << "| " << name << " | " << ku_s << " | " << row.thesis_undamped << " | " << kd_s << " | " << row.thesis_damped << " | "
       << drift << " |\n";
  }
  std::printf("\nwritten: %s/oscillators.csv, %s/oscillators.md\n", out.c_str(), out.c_str());
  return 0;
}
