// Integrators (src/common/integrate.h) on the thesis's oscillators (thesis 2.3.2 and 2.3.3):
// M = 250 kg, x0 = 0.5 m, v0 = 0, dt = 0.1 s, a = -(K/M) x (undamped) or a = -(K/M) x - (C/M) v with
// C = 2 sqrt(K M) (critically damped), run with the library's own update rules in double precision.
//
// Theory, derived here independently of the library: each method is written from its defining equations
// (thesis eqs. 2.29, 2.30, 2.32; design.md section 3 for the Groot & Warren "modified velocity Verlet";
// drift-kick-drift for leapfrog) as a product of elementary linear sub-steps on the state (x, v, a), where a
// is the last evaluated acceleration. For the linear test problem the product is the one-step
// amplification matrix; its spectral radius decides stability, and bisection on it gives the critical
// stiffness K_crit of each method. With w = omega dt, omega^2 = K/M, c dt = 2w (critical damping):
//
//   undamped  explicit Euler       |lambda|^2 = 1 + w^2 > 1: unstable at every K, energy x (1 + w^2) a step.
//             symplectic methods   det = 1, trace = 2 - w^2: stable iff w < 2, K_crit = 4 M / dt^2 = 1e5.
//   damped    explicit Euler       double eigenvalue 1 - w: stable iff w < 2, K_crit = 1e5.
//             semi-implicit Euler  det = 1 - 2w, trace = 2 - 2w - w^2. The Jury condition 1 + trace + det > 0
//                                  gives w^2 + 4w - 4 < 0: w < 2 sqrt(2) - 2, K_crit = 17157.29.
//             leapfrog (DKD)       the same trace and determinant as semi-implicit Euler: K_crit = 17157.29.
//             modified vel. Verlet a' depends on x and v_half only, so one eigenvalue is 0 and the other two
//                                  are those of semi-implicit Euler (it is semi-implicit Euler sampled half
//                                  a kick later): K_crit = 17157.29.
//             velocity Verlet      the force sees the old velocity v_t, the state needs (x, v, a):
//                                  characteristic polynomial l^3 - (2 - w - w^2) l^2 + l - w. It loses
//                                  stability when a complex pair crosses the unit circle, (l - w)(l^2 + 1)
//                                  at w^2 + 2w - 2 = 0: w = sqrt(3) - 1, K_crit = 13397.46.
//
// Comparison with the thesis's observations (2.3.3, damped): velocity Verlet unstable at 15000 (theory:
// yes, K_crit 13397); modified velocity Verlet stable at 15000 and unstable at 20000 (theory: yes, 17157);
// semi-implicit Euler stable at 15000, unstable at 20000 (theory: yes, 17157); explicit Euler the most stable
// (theory: yes, 1e5). Leapfrog: the thesis saw it unstable at 15000; this project's leapfrog is the
// drift-kick-drift (position Verlet) form with a = f(x_half, v_t), whose K_crit is 17157, so it is stable at
// 15000; the thesis's own eq. 2.34 is ambiguous about the velocity the force sees. The thesis's undamped
// observations (leapfrog gaining energy at K = 1e4, semi-implicit Euler and Verlet at 1e5) are not what the
// linear theory of these forms gives (all four symplectic forms are stable up to exactly K = 1e5 and
// conserve a modified energy), so they are not asserted here.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

// integrate.h uses ParticleView without including its header (see the report); include it first.
#include "common/particle_view.h"
#include "common/integrate.h"

namespace {

using sph::Integrator;

constexpr double kMass = 250.0;
constexpr double kX0 = 0.5;
constexpr double kDt = 0.1;

const Integrator kAllMethods[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler,
                                  Integrator::VelocityVerlet, Integrator::ModifiedVelocityVerlet,
                                  Integrator::Leapfrog};
const Integrator kSymplectic[] = {Integrator::SemiImplicitEuler, Integrator::VelocityVerlet,
                                  Integrator::ModifiedVelocityVerlet, Integrator::Leapfrog};

std::string name_of(Integrator m) {
  switch (m) {
    case Integrator::ExplicitEuler: return "explicit Euler";
    case Integrator::SemiImplicitEuler: return "semi-implicit Euler";
    case Integrator::VelocityVerlet: return "velocity Verlet";
    case Integrator::ModifiedVelocityVerlet: return "modified velocity Verlet";
    case Integrator::Leapfrog: return "leapfrog";
  }
  return "?";
}

// a = -k x - c v with k = K/M and, when damped, c = C/M = 2 sqrt(K M)/M = 2 omega.
struct Oscillator {
  double k;
  double c;
};

Oscillator oscillator(double stiffness, bool damped) {
  const double k = stiffness / kMass;
  return {k, damped ? 2.0 * std::sqrt(k) : 0.0};
}

double omega_dt(double stiffness) { return std::sqrt(stiffness / kMass) * kDt; }
double stiffness_for(double w) { return kMass * (w / kDt) * (w / kDt); }

// ---------------------------------------------------------------------------------------------------------
// The library: one step is predict -> evaluate a = f(x, vf) -> correct; at t = 0, a = f(x0, v0).
struct State {
  double x, v, a;
};

State initial_state(const Oscillator& o) { return {kX0, 0.0, -o.k * kX0 - o.c * 0.0}; }

void library_step(Integrator m, const Oscillator& o, State& s) {
  double vf = 0.0;
  sph::integrate_predict(m, s.x, s.v, vf, s.a, kDt);
  s.a = -o.k * s.x - o.c * vf;
  sph::integrate_correct(m, s.x, s.v, s.a, kDt);
}

struct RunResult {
  double max_abs_x = 0.0;
  double final_abs_x = 0.0;
  int steps = 0;         // steps taken (fewer than asked when the run escaped)
  bool escaped = false;  // |x| passed the escape bound
  std::vector<double> abs_x;  // |x| after every step
};

// Growth per step measured over the second half of a run: the largest |x| of the last 10 steps against the
// largest of the 10 steps ending half-way (windows, because a complex dominant pair makes x oscillate).
// Starting half-way removes the projection of x0 on the modes; a Jordan block's polynomial factor n is
// left as a factor 2^(2/n) at most.
double measured_growth(const RunResult& r) {
  const int n = r.steps, mid = n / 2;
  const auto window_max = [&r](int end) {
    return *std::max_element(r.abs_x.begin() + std::max(0, end - 10), r.abs_x.begin() + end);
  };
  return std::pow(window_max(n) / window_max(mid), 1.0 / double(n - mid));
}

RunResult run_library(Integrator m, double stiffness, bool damped, int steps, double escape = 1e12 * kX0) {
  const Oscillator o = oscillator(stiffness, damped);
  State s = initial_state(o);
  RunResult r;
  for (r.steps = 0; r.steps < steps;) {
    library_step(m, o, s);
    ++r.steps;
    r.max_abs_x = std::max(r.max_abs_x, std::fabs(s.x));
    r.abs_x.push_back(std::fabs(s.x));
    if (!(std::fabs(s.x) < escape)) {  // also catches inf and NaN
      r.escaped = true;
      break;
    }
  }
  r.final_abs_x = std::fabs(s.x);
  return r;
}

// ---------------------------------------------------------------------------------------------------------
// Theory. Elementary sub-steps on the extended state (x, v, a, u), u being the velocity the force sees.
using Mat4 = std::array<std::array<double, 4>, 4>;
using Mat3 = std::array<std::array<double, 3>, 3>;
enum Slot { X = 0, V = 1, A = 2, U = 3 };

Mat4 identity4() {
  Mat4 m{};
  for (int i = 0; i < 4; ++i) m[i][i] = 1.0;
  return m;
}

Mat4 mul(const Mat4& l, const Mat4& r) {
  Mat4 p{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int q = 0; q < 4; ++q) p[i][j] += l[i][q] * r[q][j];
  return p;
}

Mat4 see_velocity() {  // u <- v: the force will see the current velocity
  Mat4 m = identity4();
  m[U] = {0.0, 1.0, 0.0, 0.0};
  return m;
}
Mat4 evaluate(const Oscillator& o) {  // a <- f(x, u) = -k x - c u
  Mat4 m = identity4();
  m[A] = {-o.k, 0.0, 0.0, -o.c};
  return m;
}
Mat4 drift(double s) {  // x <- x + s v
  Mat4 m = identity4();
  m[X][V] = s;
  return m;
}
Mat4 drift_acc(double s) {  // x <- x + s a
  Mat4 m = identity4();
  m[X][A] = s;
  return m;
}
Mat4 kick(double s) {  // v <- v + s a
  Mat4 m = identity4();
  m[V][A] = s;
  return m;
}

// The methods, sub-step by sub-step, in order of application.
std::vector<Mat4> substeps(Integrator m, const Oscillator& o, double h) {
  switch (m) {
    case Integrator::ExplicitEuler:  // a = f(x_t, v_t); x' = x + v_t h; v' = v + a h
      return {see_velocity(), evaluate(o), drift(h), kick(h)};
    case Integrator::SemiImplicitEuler:  // a = f(x_t, v_t); v' = v + a h; x' = x + v' h
      return {see_velocity(), evaluate(o), kick(h), drift(h)};
    case Integrator::VelocityVerlet:  // x' = x + v h + a h^2/2; a' = f(x', v_t); v' = v + (a + a') h/2
      return {see_velocity(), drift(h), drift_acc(0.5 * h * h), kick(0.5 * h), evaluate(o), kick(0.5 * h)};
    case Integrator::ModifiedVelocityVerlet:  // v_h = v + a h/2; x' = x + v_h h; a' = f(x', v_h); v' = v_h + a' h/2
      return {kick(0.5 * h), drift(h), see_velocity(), evaluate(o), kick(0.5 * h)};
    case Integrator::Leapfrog:  // x_h = x + v h/2; a = f(x_h, v_t); v' = v + a h; x' = x_h + v' h/2
      return {see_velocity(), drift(0.5 * h), evaluate(o), kick(h), drift(0.5 * h)};
  }
  return {};
}

Mat4 step_matrix4(Integrator m, const Oscillator& o) {
  Mat4 s = identity4();
  for (const Mat4& op : substeps(m, o, kDt)) s = mul(op, s);
  return s;
}

// The carried state is (x, v, a): u is set before every use, so its column is zero (checked in a test).
Mat3 step_matrix(Integrator m, const Oscillator& o) {
  const Mat4 s = step_matrix4(m, o);
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = s[i][j];
  return r;
}

// Eigenvalues of a 3x3 matrix: roots of l^3 + p2 l^2 + p1 l + p0. One real root by bisection inside the
// Cauchy bound, then the deflated quadratic.
std::array<std::complex<double>, 3> eigenvalues(const Mat3& m) {
  const double trace = m[0][0] + m[1][1] + m[2][2];
  const double minors = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) + (m[0][0] * m[2][2] - m[0][2] * m[2][0]) +
                        (m[1][1] * m[2][2] - m[1][2] * m[2][1]);
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  const double p2 = -trace, p1 = minors, p0 = -det;
  const auto poly = [&](double l) { return ((l + p2) * l + p1) * l + p0; };
  double lo = -(1.0 + std::max({std::fabs(p2), std::fabs(p1), std::fabs(p0)})), hi = -lo;  // poly(lo) < 0 < poly(hi)
  for (int i = 0; i < 400; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (poly(mid) < 0.0 ? lo : hi) = mid;
  }
  const double r = 0.5 * (lo + hi);
  const double b = p2 + r, c = p1 + r * b;  // l^3 + p2 l^2 + p1 l + p0 = (l - r)(l^2 + b l + c)
  const std::complex<double> sq = std::sqrt(std::complex<double>(b * b - 4.0 * c, 0.0));
  return {std::complex<double>(r, 0.0), 0.5 * (-b + sq), 0.5 * (-b - sq)};
}

double spectral_radius(const Mat3& m) {
  double rho = 0.0;
  for (const std::complex<double>& l : eigenvalues(m)) rho = std::max(rho, std::abs(l));
  return rho;
}

double theory_radius(Integrator m, double stiffness, bool damped) {
  return spectral_radius(step_matrix(m, oscillator(stiffness, damped)));
}

// Spectral radius above 1 + this counts as unstable (the root finder is accurate to ~1e-8 at double roots).
constexpr double kUnstable = 1e-7;

struct Critical {
  bool unstable_everywhere = false;  // unstable already at the smallest stiffness scanned (K = 1)
  bool restabilises = false;         // stable again somewhere above K_crit on the scan
  double stiffness = 0.0;            // K_crit: stable below, unstable above
};

// Scan K from 1 to 1e7 on a log grid, then bisect the first stable -> unstable change.
Critical critical_stiffness(Integrator m, bool damped) {
  Critical c;
  std::vector<double> ks;
  for (int i = 0; i <= 700; ++i) ks.push_back(std::pow(10.0, i / 100.0));
  std::size_t first = ks.size();
  for (std::size_t i = 0; i < ks.size(); ++i) {
    const bool unstable = theory_radius(m, ks[i], damped) > 1.0 + kUnstable;
    if (unstable && first == ks.size()) first = i;
    if (!unstable && first < ks.size()) c.restabilises = true;
  }
  if (first == 0) {
    c.unstable_everywhere = true;
    return c;
  }
  if (first == ks.size()) {
    c.stiffness = INFINITY;
    return c;
  }
  double lo = ks[first - 1], hi = ks[first];
  while (hi - lo > 1e-12 * hi) {
    const double mid = 0.5 * (lo + hi);
    (theory_radius(m, mid, damped) > 1.0 + kUnstable ? hi : lo) = mid;
  }
  c.stiffness = 0.5 * (lo + hi);
  return c;
}

// Closed forms of K_crit from the derivations in the header comment.
double expected_critical(Integrator m, bool damped) {
  if (!damped) return stiffness_for(2.0);  // symplectic methods: w < 2
  switch (m) {
    case Integrator::ExplicitEuler: return stiffness_for(2.0);
    case Integrator::VelocityVerlet: return stiffness_for(std::sqrt(3.0) - 1.0);
    default: return stiffness_for(2.0 * std::sqrt(2.0) - 2.0);
  }
}

// Undamped: a = -k x after every evaluation (and at t = 0), so the state reduces to (x, v) with the
// 2x2 matrix B = M[xv, xv] + M[xv, a] (-k, 0).
using Mat2 = std::array<std::array<double, 2>, 2>;

Mat2 reduced_undamped(Integrator m, double stiffness) {
  const Oscillator o = oscillator(stiffness, false);
  const Mat3 s = step_matrix(m, o);
  Mat2 b{};
  for (int i = 0; i < 2; ++i) {
    b[i][0] = s[i][0] - o.k * s[i][2];
    b[i][1] = s[i][1];
  }
  return b;
}

double quad(const Mat2& q, double x, double v) { return q[0][0] * x * x + 2.0 * q[0][1] * x * v + q[1][1] * v * v; }

// A symplectic B (det 1) conserves F(z) = z^T J B z (F(Bz) = z^T B^T J B B z = z^T J B z): its symmetric
// part, with the sign chosen so that Q[0][0] > 0, is the modified energy the method conserves.
Mat2 invariant_form(const Mat2& b) {
  const double s = b[1][0] < 0.0 ? -1.0 : 1.0;
  return {{{s * b[1][0], s * 0.5 * (b[1][1] - b[0][0])}, {s * 0.5 * (b[1][1] - b[0][0]), -s * b[0][1]}}};
}

// Bounds that follow from the conserved form: on the ellipse z^T Q z = z0^T Q z0 the true energy
// E = z^T diag(K/2, M/2) z ranges between the generalised eigenvalues mu of (E, Q) times q0, and |x| is at
// most sqrt(q0 (Q^-1)_xx).
struct EnergyTheory {
  double max_relative_excursion;
  double max_abs_x;
};

EnergyTheory energy_theory(Integrator m, double stiffness) {
  const Mat2 q = invariant_form(reduced_undamped(m, stiffness));
  const double ek = 0.5 * stiffness, em = 0.5 * kMass;
  const double q0 = quad(q, kX0, 0.0), e0 = 0.5 * stiffness * kX0 * kX0;
  const double det_q = q[0][0] * q[1][1] - q[0][1] * q[0][1];
  // det(E - mu Q) = det_q mu^2 - (ek q11 + em q00) mu + ek em = 0
  const double bq = ek * q[1][1] + em * q[0][0];
  const double disc = std::sqrt(bq * bq - 4.0 * det_q * ek * em);
  const double mu_hi = (bq + disc) / (2.0 * det_q), mu_lo = (bq - disc) / (2.0 * det_q);
  return {std::max(mu_hi * q0 / e0 - 1.0, 1.0 - mu_lo * q0 / e0), std::sqrt(q0 * q[1][1] / det_q)};
}

double energy(const State& s, double stiffness) { return 0.5 * kMass * s.v * s.v + 0.5 * stiffness * s.x * s.x; }

}  // namespace

TEST_CASE("the hand-derived update matrices reproduce the library's integrators", "[integrators]") {
  for (Integrator m : kAllMethods) {
    for (bool damped : {false, true}) {
      for (double stiffness : {100.0, 1.0e4, 3.0e4}) {
        INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ", K = " << stiffness);
        const Oscillator o = oscillator(stiffness, damped);
        const Mat4 s4 = step_matrix4(m, o);
        for (int i = 0; i < 3; ++i) CHECK(s4[i][U] == 0.0);  // u is never carried from one step to the next
        const Mat3 s = step_matrix(m, o);
        // One step at a time along the library's own trajectory (comparing whole trajectories would also
        // measure how rounding differences grow, which for the defective critically damped Euler matrix is
        // ~ n sqrt(eps) / |lambda|).
        State lib = initial_state(o);
        for (int n = 0; n < 200; ++n) {
          const std::array<double, 3> prev = {lib.x, lib.v, lib.a};
          library_step(m, o, lib);
          std::array<double, 3> z{};
          for (int i = 0; i < 3; ++i) z[i] = s[i][0] * prev[0] + s[i][1] * prev[1] + s[i][2] * prev[2];
          // Relative to the state's size (velocity and acceleration scaled to lengths).
          const double scale = std::fabs(z[0]) + std::fabs(z[1]) * kDt + std::fabs(z[2]) * kDt * kDt;
          INFO("step " << n + 1 << ": library (x, v, a) = (" << lib.x << ", " << lib.v << ", " << lib.a
                        << "), matrix (" << z[0] << ", " << z[1] << ", " << z[2] << ")");
          REQUIRE(std::fabs(lib.x - z[0]) <= 1e-12 * scale);
          REQUIRE(std::fabs(lib.v - z[1]) * kDt <= 1e-12 * scale);
          REQUIRE(std::fabs(lib.a - z[2]) * kDt * kDt <= 1e-12 * scale);
        }
      }
    }
  }
}

TEST_CASE("critical stiffness of each method agrees with the closed forms", "[integrators]") {
  // Explicit Euler undamped: unstable at every stiffness, |lambda| = sqrt(1 + w^2).
  const Critical ee = critical_stiffness(Integrator::ExplicitEuler, false);
  CHECK(ee.unstable_everywhere);
  for (double stiffness : {1.0, 100.0, 1e4, 1e5, 1e6}) {
    const double w = omega_dt(stiffness);
    CHECK(theory_radius(Integrator::ExplicitEuler, stiffness, false) ==
          Approx(std::sqrt(1.0 + w * w)).epsilon(1e-7));
  }
  for (bool damped : {false, true}) {
    for (Integrator m : kAllMethods) {
      if (m == Integrator::ExplicitEuler && !damped) continue;
      const Critical c = critical_stiffness(m, damped);
      INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ": K_crit = " << c.stiffness << ", expected "
                      << expected_critical(m, damped));
      REQUIRE_FALSE(c.unstable_everywhere);
      CHECK_FALSE(c.restabilises);
      CHECK(std::fabs(c.stiffness - expected_critical(m, damped)) <= 1e-6 * expected_critical(m, damped));
    }
  }
  // Symplectic methods conserve phase-space area: det = 1 undamped, at any stable stiffness.
  for (Integrator m : kSymplectic) {
    for (double stiffness : {100.0, 1e4, 9e4}) {
      const Mat2 b = reduced_undamped(m, stiffness);
      CHECK(b[0][0] * b[1][1] - b[0][1] * b[1][0] == Approx(1.0).epsilon(1e-12));
    }
  }
}

TEST_CASE("library integrators are bounded at 0.8 K_crit and blow up at 1.25 K_crit", "[integrators]") {
  for (bool damped : {false, true}) {
    for (Integrator m : kAllMethods) {
      if (m == Integrator::ExplicitEuler && !damped) continue;  // no stable range (see the energy test)
      const double kc = critical_stiffness(m, damped).stiffness;
      {
        const double stiffness = 0.8 * kc;
        const RunResult r = run_library(m, stiffness, damped, 2000);
        INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ", K = 0.8 K_crit = " << stiffness
                        << ": max |x|/x0 = " << r.max_abs_x / kX0 << ", final |x|/x0 = " << r.final_abs_x / kX0);
        CHECK_FALSE(r.escaped);
        CHECK(r.max_abs_x < 5.0 * kX0);
        if (damped) {
          CHECK(r.final_abs_x < 1e-6 * kX0);  // spectral radius < 0.94: decays by many orders in 2000 steps
        } else {
          // Undamped: the trajectory stays on the conserved ellipse, so |x| is bounded by its half-axis.
          CHECK(r.max_abs_x <= energy_theory(m, stiffness).max_abs_x * (1.0 + 1e-9));
        }
      }
      {
        const double stiffness = 1.25 * kc;
        const double rho = theory_radius(m, stiffness, damped);
        const RunResult r = run_library(m, stiffness, damped, 2000);
        const double measured = measured_growth(r);
        INFO(name_of(m) << (damped ? ", damped" : ", undamped") << ", K = 1.25 K_crit = " << stiffness
                        << ": escaped after " << r.steps << " steps, theory rho = " << rho
                        << ", measured growth per step = " << measured);
        CHECK(r.escaped);  // |x| > 1e12 x0
        REQUIRE(r.steps >= 20);  // enough steps for the two windows of measured_growth
        CHECK(std::fabs(measured - rho) < 0.02 * rho);
      }
    }
  }
}

TEST_CASE("undamped symplectic methods are stable exactly below omega dt = 2", "[integrators]") {
  for (Integrator m : kSymplectic) {
    INFO(name_of(m));
    for (double w : {0.5, 1.0, 1.9, 1.99}) {
      const double stiffness = stiffness_for(w);
      const RunResult r = run_library(m, stiffness, false, 5000);
      INFO("K = " << stiffness << ": max |x|/x0 = " << r.max_abs_x / kX0);
      CHECK_FALSE(r.escaped);
      CHECK(r.max_abs_x <= energy_theory(m, stiffness).max_abs_x * (1.0 + 1e-9));
    }
    for (double w : {2.01, 2.1, 3.0}) {
      const double stiffness = stiffness_for(w);
      const RunResult r = run_library(m, stiffness, false, 5000);
      INFO("K = " << stiffness << ": escaped after " << r.steps << " steps");
      CHECK(r.escaped);
    }
  }
}

TEST_CASE("damped oscillator: the thesis's observations at K = 15000 and 20000", "[integrators]") {
  const auto stable = [](Integrator m, double stiffness) {
    const RunResult r = run_library(m, stiffness, true, 2000);
    return !r.escaped && r.final_abs_x < 1e-6 * kX0;
  };
  const auto unstable = [](Integrator m, double stiffness) { return run_library(m, stiffness, true, 2000).escaped; };
  // Thesis: semi-implicit Euler and modified velocity Verlet stable at 15000, unstable at 20000.
  CHECK(stable(Integrator::SemiImplicitEuler, 15000.0));
  CHECK(unstable(Integrator::SemiImplicitEuler, 20000.0));
  CHECK(stable(Integrator::ModifiedVelocityVerlet, 15000.0));
  CHECK(unstable(Integrator::ModifiedVelocityVerlet, 20000.0));
  // Thesis: velocity Verlet unstable at 15000 (theory: K_crit 13397); stable at 10000 (all but Beeman).
  CHECK(unstable(Integrator::VelocityVerlet, 15000.0));
  CHECK(stable(Integrator::VelocityVerlet, 10000.0));
  // Thesis: explicit Euler the only one left stable at 20000.
  CHECK(stable(Integrator::ExplicitEuler, 20000.0));
  // Leapfrog (drift-kick-drift here) follows its own theory, K_crit 17157, not the thesis's observation.
  CHECK(stable(Integrator::Leapfrog, 15000.0));
  CHECK(unstable(Integrator::Leapfrog, 20000.0));
}

TEST_CASE("explicit Euler gains energy by a factor 1 + (omega dt)^2 every step at any stiffness", "[integrators]") {
  for (double stiffness : {1.0, 100.0, 1e4, 1e5}) {
    const double w = omega_dt(stiffness);
    const Oscillator o = oscillator(stiffness, false);
    State s = initial_state(o);
    double e = energy(s, stiffness);
    const double e0 = e;
    for (int n = 1; n <= 300; ++n) {
      library_step(Integrator::ExplicitEuler, o, s);
      const double e_new = energy(s, stiffness);
      INFO("K = " << stiffness << ", step " << n);
      REQUIRE(e_new / e == Approx(1.0 + w * w).epsilon(1e-9));
      e = e_new;
    }
    if (stiffness == 100.0) {
      // (1 + 0.004)^300 = 3.31: the energy grew by 231 % in 300 steps (thesis fig. 2.3: Euler diverges).
      const double expected = std::pow(1.0 + w * w, 300);
      INFO("K = 100: E_300 / E_0 = " << e / e0 << ", theory " << expected);
      CHECK(e / e0 == Approx(expected).epsilon(1e-9));
      CHECK(e / e0 > 3.3);
    }
  }
}

TEST_CASE("symplectic methods show no secular energy drift at K = 100", "[integrators]") {
  const double stiffness = 100.0;
  const double w = omega_dt(stiffness);  // 0.0632
  for (Integrator m : kSymplectic) {
    const Oscillator o = oscillator(stiffness, false);
    State s = initial_state(o);
    const double e0 = energy(s, stiffness);
    double first = 0.0, last = 0.0, all = 0.0;
    const int steps = 10000;
    for (int n = 0; n < steps; ++n) {
      library_step(m, o, s);
      const double dev = std::fabs(energy(s, stiffness) / e0 - 1.0);
      if (n < 1000) first = std::max(first, dev);
      if (n >= steps - 1000) last = std::max(last, dev);
      all = std::max(all, dev);
    }
    const EnergyTheory t = energy_theory(m, stiffness);
    INFO(name_of(m) << ": max relative energy deviation, first 1000 steps " << first << ", last 1000 " << last
                    << ", all " << all << "; theory " << t.max_relative_excursion << "; (omega dt)^2 = " << w * w);
    CHECK(last <= 1.5 * first);
    CHECK(all <= t.max_relative_excursion * (1.0 + 1e-6) + 1e-12);  // never leaves the conserved ellipse
    CHECK(first >= 0.9 * t.max_relative_excursion);                 // and the bound is a real one
    if (m == Integrator::SemiImplicitEuler) {
      // x and v are half a step apart, so E = M v^2/2 + K x^2/2 oscillates by O(omega dt), ~ w/2.
      CHECK(t.max_relative_excursion < w);
      CHECK(t.max_relative_excursion > 0.4 * w);
    } else {
      // Position and velocity at the same time: O((omega dt)^2), ~ w^2/4.
      CHECK(t.max_relative_excursion < 0.5 * w * w);
    }
  }
}
