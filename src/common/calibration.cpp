#include "calibration.h"

#include <cmath>

#include "kernels.h"
#include "lattice_sum.h"

namespace sph {

double smoothing_length(double spacing, double neighbours) {
  const double pi = kPiDouble;
  return std::cbrt(3.0 * neighbours / (4.0 * pi)) * spacing;
}

double lattice_density_factor(double d, double h, bool cubic_spline) {
  if (cubic_spline) {  // the kernel itself (kernels.h), summed in double
    const KernelCoeffs k = make_kernel_coeffs(h);
    return lattice_sum(d, h, [&](double r2) { return double(sph::cubic_spline(k, float(std::sqrt(r2)))); }) * d * d * d;
  }
  const double c = 315.0 / (64.0 * kPiDouble * std::pow(h, 9));
  return lattice_sum(d, h, [&](double r2) { return c * std::pow(h * h - r2, 3); }) * d * d * d;
}

namespace {
constexpr double kCohesionJ3 = 33.0 / 28672.0;  // int_0^1 q^3 c(q) dq, c: akinci_cohesion_shape
constexpr double kCohesionJ4 = 21.0 / 28160.0;  // int_0^1 q^4 c(q) dq
}  // namespace

double cohesion_from_surface_tension(double sigma, double rest_density, double h) {
  return 8.0 * sigma / (3.14159265358979323846 * rest_density * rest_density * std::pow(h, 5) * kCohesionJ4);
}

double cross_cohesion(double sigma_a, double sigma_b, double sigma_ab, double rho_a, double rho_b, double h) {
  return 4.0 * (sigma_a + sigma_b - sigma_ab) / (kPiDouble * rho_a * rho_b * std::pow(h, 5) * kCohesionJ4);
}

double cohesion_pressure(double sigma, double h) { return 16.0 / 3.0 * (kCohesionJ3 / kCohesionJ4) * sigma / h; }

}  // namespace sph
