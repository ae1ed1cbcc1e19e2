// Smoothing kernels (3-D, support radius h: every kernel is zero for r >= h).
// Each is normalised so that its volume integral is 1; tests/test_kernels.cpp checks that by quadrature and
// checks each gradient and Laplacian against central differences of the kernel itself.
//
// Gradients are returned as a scalar "fac" with grad_a W(x_a - x_b) = fac * (x_a - x_b), the DualSPHysics
// convention: the caller multiplies by the pair vector it already holds and never divides by r twice.
#pragma once

#include <cmath>

#include "sph_hd.h"

namespace sph {

constexpr float kPi = 3.14159265358979323846f;
constexpr double kPiDouble = 3.14159265358979323846;

// Coefficients depend on h only: computed once per scene, kept in the simulation constants.
struct KernelCoeffs {
  float h;
  float h2;
  float poly6;          // 315 / (64 pi h^9)
  float spiky;          // 15 / (pi h^6)
  float spiky_grad;     // -45 / (pi h^6)
  float visc;           // 15 / (2 pi h^3)
  float visc_lap;       // 45 / (pi h^6)
  float near;           // 105 / (4 pi h^7)
  float near_grad;      // -4 * 105 / (4 pi h^7)
  float cubic;          // 8 / (pi h^3)
};

inline KernelCoeffs make_kernel_coeffs(double h) {
  const double pi = 3.14159265358979323846;
  const double h3 = h * h * h, h6 = h3 * h3, h7 = h6 * h, h9 = h6 * h3;
  KernelCoeffs k{};
  k.h = float(h);
  k.h2 = float(h * h);
  k.poly6 = float(315.0 / (64.0 * pi * h9));       // thesis eq. 2.44 [Mueller 2003]
  k.spiky = float(15.0 / (pi * h6));               // thesis eq. 2.45
  k.spiky_grad = float(-45.0 / (pi * h6));
  k.visc = float(15.0 / (2.0 * pi * h3));          // thesis eq. 2.46
  k.visc_lap = float(45.0 / (pi * h6));
  k.near = float(105.0 / (4.0 * pi * h7));         // (h - r)^4: normalised, integral of r^2 (h-r)^4 = h^7/105
  k.near_grad = float(-4.0 * 105.0 / (4.0 * pi * h7));
  k.cubic = float(8.0 / (pi * h3));
  return k;
}

// Poly6, for density: W = 315/(64 pi h^9) (h^2 - r^2)^3. Takes r^2, so no square root is needed.
SPH_HD inline float poly6(const KernelCoeffs& k, float r2) {
  if (r2 >= k.h2) return 0.0f;
  const float d = k.h2 - r2;
  return k.poly6 * d * d * d;
}

// grad Poly6 = -6 * 315/(64 pi h^9) (h^2 - r^2)^2 r_ab, returned as fac.
SPH_HD inline float poly6_grad_fac(const KernelCoeffs& k, float r2) {
  if (r2 >= k.h2) return 0.0f;
  const float d = k.h2 - r2;
  return -6.0f * k.poly6 * d * d;
}

// Spiky, for pressure: W = 15/(pi h^6) (h - r)^3.
SPH_HD inline float spiky(const KernelCoeffs& k, float r) {
  if (r >= k.h) return 0.0f;
  const float d = k.h - r;
  return k.spiky * d * d * d;
}

// dW/dr of Spiky: -45/(pi h^6) (h - r)^2. The force loop multiplies by the 1/r it already has.
SPH_HD inline float spiky_dwdr(const KernelCoeffs& k, float r) {
  if (r >= k.h) return 0.0f;
  const float d = k.h - r;
  return k.spiky_grad * d * d;
}

// grad Spiky = -45/(pi h^6) (h - r)^2 r_ab / r, returned as fac. r must be > 0.
SPH_HD inline float spiky_grad_fac(const KernelCoeffs& k, float r) { return spiky_dwdr(k, r) / r; }

// Viscosity kernel [Mueller 2003], thesis eq. 2.46:
// W = 15/(2 pi h^3) (-r^3/(2h^3) + r^2/h^2 + h/(2r) - 1); only its Laplacian is used by the solver.
SPH_HD inline float viscosity_kernel(const KernelCoeffs& k, float r) {
  if (r >= k.h) return 0.0f;
  const float q = r / k.h;
  return k.visc * (-0.5f * q * q * q + q * q + 0.5f / q - 1.0f);
}

// Laplacian of the viscosity kernel: 45/(pi h^6) (h - r), always positive (always dissipative).
SPH_HD inline float viscosity_laplacian(const KernelCoeffs& k, float r) {
  if (r >= k.h) return 0.0f;
  return k.visc_lap * (k.h - r);
}

// Near kernel for double density relaxation (thesis 3.1, after Clavet 2005): sharper than Spiky, so the
// near pressure it carries acts only at short range. W = 105/(4 pi h^7) (h - r)^4.
SPH_HD inline float near_kernel(const KernelCoeffs& k, float r) {
  if (r >= k.h) return 0.0f;
  const float d = k.h - r;
  return k.near * d * d * d * d;
}

// dW/dr of the near kernel: -4 * 105/(4 pi h^7) (h - r)^3.
SPH_HD inline float near_dwdr(const KernelCoeffs& k, float r) {
  if (r >= k.h) return 0.0f;
  const float d = k.h - r;
  return k.near_grad * d * d * d;
}

// grad W_near = -4 * 105/(4 pi h^7) (h - r)^3 r_ab / r, returned as fac. r must be > 0.
SPH_HD inline float near_grad_fac(const KernelCoeffs& k, float r) { return near_dwdr(k, r) / r; }

// Cubic spline [Monaghan & Lattanzio 1985] written with THIS project's convention: support radius h
// (the seed's 2 h_s equals our h). q = r/h:
//   W = 8/(pi h^3) * (6 q^3 - 6 q^2 + 1)  for q <= 1/2,
//   W = 8/(pi h^3) * 2 (1 - q)^3          for 1/2 < q < 1.
SPH_HD inline float cubic_spline(const KernelCoeffs& k, float r) {
  const float q = r / k.h;
  if (q >= 1.0f) return 0.0f;
  if (q <= 0.5f) return k.cubic * (6.0f * q * q * (q - 1.0f) + 1.0f);
  const float d = 1.0f - q;
  return k.cubic * 2.0f * d * d * d;
}

// dW/dq of the cubic spline (q = r/h < 1), shared by its gradient forms below.
SPH_HD inline float cubic_spline_dwdq(const KernelCoeffs& k, float q) {
  if (q <= 0.5f) return k.cubic * (18.0f * q * q - 12.0f * q);
  const float d = 1.0f - q;
  return -6.0f * k.cubic * d * d;
}

// grad of the cubic spline, returned as fac (grad W = fac * r_ab). r must be > 0.
SPH_HD inline float cubic_spline_grad_fac(const KernelCoeffs& k, float r) {
  const float q = r / k.h;
  if (q >= 1.0f) return 0.0f;
  return cubic_spline_dwdq(k, q) / (k.h * r);
}

// dW/dr of the cubic spline, as spiky_dwdr: the force loop multiplies by the 1/r it already has.
SPH_HD inline float cubic_spline_dwdr(const KernelCoeffs& k, float r) {
  const float q = r / k.h;
  if (q >= 1.0f) return 0.0f;
  return cubic_spline_dwdq(k, q) / k.h;
}

// WCSPH's kernel pair (scene key sph.kernel, SimConstants::cubic_spline): Poly6 for the density and Spiky for
// every gradient [Mueller 2003] (thesis eqs. 2.44, 2.45, the default), or the cubic spline for both
// [Monaghan 1992; Becker & Teschner 2007], DFSPH's default ([BK15]; dfsph.h, dfsph_w). One kernel for the density
// and its gradient is what holds a drop's pressure at Laplace's 2 sigma / R (+5% against Poly6 with Spiky's
// +29%, docs/results.md): with two, the summed density and the pressure force disagree on how much the
// surface's missing neighbours weigh.
SPH_HD inline float density_kernel(const KernelCoeffs& k, bool cubic, float r2) {
  return cubic ? cubic_spline(k, sqrtf(r2)) : poly6(k, r2);
}
SPH_HD inline float gradient_dwdr(const KernelCoeffs& k, bool cubic, float r) {
  return cubic ? cubic_spline_dwdr(k, r) : spiky_dwdr(k, r);
}

// Akinci, Akinci & Teschner 2013 eq. 2, the cohesion kernel, support h: C(r) = 32 / (pi h^3) c(r / h) with
//   c(q) = (1 - q)^3 q^3               for 1/2 < q < 1,
//   c(q) = 2 (1 - q)^3 q^3 - 1 / 64    for 0 < q <= 1/2,
// 0 beyond. Attractive (c > 0) from q = 0.273 to 1, repulsive below, so cohesion does not pull particles into
// pairs. Returns c(q); the 32 / (pi h^3) goes into the fluid's cohesion constant (calibration.h).
SPH_HD inline float akinci_cohesion_shape(float q) {
  if (q >= 1.0f) return 0.0f;
  const float d = 1.0f - q;
  const float c = d * d * d * q * q * q;
  return q > 0.5f ? c : 2.0f * c - 1.0f / 64.0f;
}

// Akinci, Akinci & Teschner 2013 eq. 7, the adhesion kernel, support h: A(r) = 0.007 / h^3.25 (-4 r^2 / h + 6 r -
// 2 h)^(1/4) for h / 2 < r <= h, 0 elsewhere, i.e. A = 0.007 h^-3 a(r / h) with
//   a(q) = (-4 q^2 + 6 q - 2)^(1/4)   for 1/2 < q < 1,
// 0 elsewhere: attractive only, peaking at q = 3/4, zero at half the support so that it never pulls a fluid
// particle into the wall's particles. Returns a(q); the rest goes into the fluid's adhesion constant
// (cohesion_energy.h, adhesion_constant).
SPH_HD inline float akinci_adhesion_shape(float q) {
  if (q <= 0.5f || q >= 1.0f) return 0.0f;
  return std::sqrt(std::sqrt((-4.0f * q + 6.0f) * q - 2.0f));
}

}  // namespace sph
