// Smoothing kernels (src/common/kernels.h) against their defining properties, computed here independently:
//  - normalisation: 4 pi int_0^h r^2 W(r) dr = 1 (composite Simpson in double precision);
//  - compact support: W = 0 at and beyond h, W > 0 just inside h;
//  - gradients: fac * r equals dW/dr from central differences of the kernel itself;
//  - viscosity Laplacian: equals W'' + (2/r) W' of the viscosity kernel, differenced numerically;
//  - the near kernel is sharper than Spiky;
//  - a lattice sum of Poly6 reproduces the continuous integral (guided creation relies on it).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/guided_creation.h"
#include "common/kernels.h"

namespace {

constexpr double kPiD = 3.14159265358979323846;

// A kernel as a function of r (the library evaluates in float; the tests sum and difference in double).
using RadialFn = std::function<double(double)>;

struct NamedKernel {
  std::string name;
  RadialFn w;
};

std::vector<NamedKernel> all_kernels(const sph::KernelCoeffs& k) {
  return {
      {"poly6", [k](double r) { return double(sph::poly6(k, float(r * r))); }},
      {"spiky", [k](double r) { return double(sph::spiky(k, float(r))); }},
      {"viscosity", [k](double r) { return double(sph::viscosity_kernel(k, float(r))); }},
      {"near", [k](double r) { return double(sph::near_kernel(k, float(r))); }},
      {"cubic_spline", [k](double r) { return double(sph::cubic_spline(k, float(r))); }},
  };
}

// Composite Simpson rule of f on [a, b] with n (even) intervals.
double simpson(const RadialFn& f, double a, double b, int n) {
  const double dx = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * dx) * (i % 2 == 1 ? 4.0 : 2.0);
  return s * dx / 3.0;
}

// 4 pi int_0^R r^2 W(r) dr. At r = 0 the integrand is 0 for every kernel (r^2 W -> 0 even for the viscosity
// kernel, whose W ~ h/(2r)), so the origin is handled by its limit instead of evaluating W(0).
double mass_within(const RadialFn& w, double radius, int intervals = 20000) {
  const RadialFn integrand = [&w](double r) { return r == 0.0 ? 0.0 : 4.0 * kPiD * r * r * w(r); };
  return simpson(integrand, 0.0, radius, intervals);
}

// Radii strictly inside the support where derivatives are compared.
std::vector<double> sample_radii(double h, double lo, double hi, int count) {
  std::vector<double> r;
  for (int i = 0; i < count; ++i) r.push_back(h * (lo + (hi - lo) * i / (count - 1)));
  return r;
}

// dW/dr by central differences with Richardson extrapolation (fourth order): the kernel is evaluated in
// float, so the step cannot be tiny; with 4 D(d) - D(2d) the truncation error is O(d^4).
double radial_derivative(const RadialFn& w, double r, double d) {
  const double d1 = (w(r + d) - w(r - d)) / (2.0 * d);
  const double d2 = (w(r + 2.0 * d) - w(r - 2.0 * d)) / (4.0 * d);
  return (4.0 * d1 - d2) / 3.0;
}

}  // namespace

TEST_CASE("every kernel integrates to one over its support", "[kernels]") {
  for (double h : {1.0, 0.037}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    for (const NamedKernel& kernel : all_kernels(k)) {
      INFO("kernel " << kernel.name << ", h = " << h);
      const double integral = mass_within(kernel.w, h);
      CHECK(std::fabs(integral - 1.0) < 1e-4);
      // Nothing is left outside the support: integrating to 2h adds nothing.
      CHECK(std::fabs(mass_within(kernel.w, 2.0 * h, 40000) - integral) < 1e-6);
    }
  }
}

TEST_CASE("kernels and gradient factors vanish at and beyond h and are positive just inside", "[kernels]") {
  for (double h : {1.0, 0.037}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    const float hf = float(h);
    for (const NamedKernel& kernel : all_kernels(k)) {
      INFO("kernel " << kernel.name << ", h = " << h);
      CHECK(kernel.w(h) == 0.0);
      CHECK(kernel.w(1.0001 * h) == 0.0);
      CHECK(kernel.w(1.5 * h) == 0.0);
      CHECK(kernel.w(10.0 * h) == 0.0);
      // The support is not shorter than h: the kernel is still positive at 0.95 h (the viscosity kernel
      // vanishes like (1 - q)^3 there, which float still resolves at this distance).
      CHECK(kernel.w(0.95 * h) > 0.0);
      // and, except for the viscosity kernel whose float evaluation cancels there, still positive at 0.9999 h.
      if (kernel.name != "viscosity") CHECK(kernel.w(0.9999 * h) > 0.0);
      CHECK(kernel.w(0.5 * h) > kernel.w(0.95 * h));
    }
    CHECK(sph::poly6(k, k.h2) == 0.0f);
    for (float r : {hf, 1.0001f * hf, 3.0f * hf}) {
      CHECK(sph::poly6_grad_fac(k, r * r) == 0.0f);
      CHECK(sph::spiky_grad_fac(k, r) == 0.0f);
      CHECK(sph::near_grad_fac(k, r) == 0.0f);
      CHECK(sph::cubic_spline_grad_fac(k, r) == 0.0f);
      CHECK(sph::viscosity_laplacian(k, r) == 0.0f);
    }
  }
}

TEST_CASE("gradient factors match central differences of the kernels", "[kernels]") {
  for (double h : {1.0, 0.037}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    struct Pair {
      std::string name;
      RadialFn w;
      RadialFn fac;  // grad W = fac * r_vec, so dW/dr = fac * r
    };
    const std::vector<Pair> pairs = {
        {"poly6", [k](double r) { return double(sph::poly6(k, float(r * r))); },
         [k](double r) { return double(sph::poly6_grad_fac(k, float(r * r))); }},
        {"spiky", [k](double r) { return double(sph::spiky(k, float(r))); },
         [k](double r) { return double(sph::spiky_grad_fac(k, float(r))); }},
        {"near", [k](double r) { return double(sph::near_kernel(k, float(r))); },
         [k](double r) { return double(sph::near_grad_fac(k, float(r))); }},
        {"cubic_spline", [k](double r) { return double(sph::cubic_spline(k, float(r))); },
         [k](double r) { return double(sph::cubic_spline_grad_fac(k, float(r))); }},
    };
    const double d = 1e-3 * h;
    for (const Pair& p : pairs) {
      // 19 radii in [0.05 h, 0.95 h]. The cubic spline's joint at h/2 is among them: W is C^2 there, so a
      // stencil straddling it still has an O(d^2) error, far below the tolerance.
      for (double r : sample_radii(h, 0.05, 0.95, 19)) {
        const double analytic = p.fac(r) * r;
        const double numeric = radial_derivative(p.w, r, d);
        INFO("kernel " << p.name << ", h = " << h << ", r/h = " << r / h << ": fac*r = " << analytic
                       << ", central difference = " << numeric);
        CHECK(analytic < 0.0);  // every kernel decreases monotonically inside its support
        CHECK(std::fabs(analytic - numeric) <= 1e-3 * std::fabs(numeric));
      }
    }
  }
}

TEST_CASE("viscosity Laplacian matches W'' + 2 W'/r of the viscosity kernel", "[kernels]") {
  for (double h : {1.0, 0.037}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    const auto w = [k](double r) { return double(sph::viscosity_kernel(k, float(r))); };
    // In 3-D the radial Laplacian W'' + (2/r) W' equals (1/r) (r W)''. Differencing r W avoids the h/(2r)
    // singular term of W, whose own derivatives are large near the origin (it is harmonic, so it does not
    // contribute to the Laplacian). Second central difference with Richardson extrapolation (O(d^4)); the
    // step is large-ish because W is evaluated in float.
    const auto rw = [&w](double r) { return r * w(r); };
    const double d = 0.05 * h;
    for (double r : sample_radii(h, 0.2, 0.85, 14)) {
      const auto second = [&](double s) { return (rw(r + s) - 2.0 * rw(r) + rw(r - s)) / (s * s); };
      const double numeric = (4.0 * second(d) - second(2.0 * d)) / 3.0 / r;
      // Cross-check with the textbook form W'' + (2/r) W' from plain central differences of W, at a looser
      // tolerance (its truncation error is larger because of the 1/r term).
      const double dd = 0.01 * h;
      const double w2 = (w(r + dd) - 2.0 * w(r) + w(r - dd)) / (dd * dd);
      const double w1 = (w(r + dd) - w(r - dd)) / (2.0 * dd);
      const double textbook = w2 + 2.0 * w1 / r;
      const double analytic = double(sph::viscosity_laplacian(k, float(r)));
      INFO("h = " << h << ", r/h = " << r / h << ": laplacian = " << analytic << ", (rW)''/r = " << numeric
                  << ", W''+2W'/r = " << textbook);
      CHECK(analytic > 0.0);
      CHECK(std::fabs(analytic - numeric) <= 1e-3 * std::fabs(numeric));
      CHECK(std::fabs(analytic - textbook) <= 5e-3 * std::fabs(textbook));
    }
  }
}

TEST_CASE("the near kernel is sharper than Spiky", "[kernels]") {
  for (double h : {1.0, 0.037}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    const RadialFn spiky = [k](double r) { return double(sph::spiky(k, float(r))); };
    const RadialFn near = [k](double r) { return double(sph::near_kernel(k, float(r))); };
    // Both integrate to one (checked above); the near kernel holds more of its mass within h/2 and within
    // h/4, and its peak is higher.
    const double spiky_half = mass_within(spiky, 0.5 * h), near_half = mass_within(near, 0.5 * h);
    const double spiky_quarter = mass_within(spiky, 0.25 * h), near_quarter = mass_within(near, 0.25 * h);
    INFO("h = " << h << ": mass within h/2: spiky " << spiky_half << ", near " << near_half
                << "; within h/4: spiky " << spiky_quarter << ", near " << near_quarter);
    CHECK(near_half > spiky_half + 0.05);
    CHECK(near_quarter > spiky_quarter + 0.05);
    CHECK(near(0.0) > 1.5 * spiky(0.0));
    // Beyond h/2 the near kernel is the smaller one: the same mass, moved inwards.
    CHECK(near(0.6 * h) < spiky(0.6 * h));
  }
}

TEST_CASE("Poly6 and the cubic spline summed over a cubic lattice reproduce their integral", "[kernels]") {
  for (const bool cubic : {false, true}) {
    for (double d : {1.0, 0.013}) {
      for (double ratio : {1.969, 2.0, 2.5, 3.0}) {
        const double h = ratio * d;
        const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
        // Independent sum with the library's float kernel, over a block that surely contains the support.
        const int n = int(std::ceil(ratio)) + 1;
        double sum = 0.0;
        for (int z = -n; z <= n; ++z)
          for (int y = -n; y <= n; ++y)
            for (int x = -n; x <= n; ++x) {
              const double r2 = (double(x) * x + double(y) * y + double(z) * z) * d * d;
              sum += double(cubic ? sph::cubic_spline(k, float(std::sqrt(r2))) : sph::poly6(k, float(r2)));
            }
        sum *= d * d * d;
        const double library = sph::lattice_density_factor(d, h, cubic);
        INFO((cubic ? "cubic spline" : "Poly6") << ", d = " << d << ", h = " << h << ": own lattice sum " << sum
                                                << ", lattice_density_factor " << library);
        CHECK(std::fabs(sum - 1.0) < 0.02);
        CHECK(std::fabs(library - sum) < 1e-5 * sum);
      }
    }
  }
}
