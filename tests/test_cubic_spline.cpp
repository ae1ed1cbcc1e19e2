// The cubic spline (kernels.h) that DFSPH uses, beyond what test_kernels.cpp checks for every kernel
// (normalisation, support, gradient against central differences):
//  - it is Monaghan's M4 of the seed (000, eq. 5 and 6) with the seed's h_s = h / 2, evaluated here in double;
//  - W and dW/dr are continuous at the joint q = 1/2 (W = sigma / 4, dW/dq = -3 sigma / 2 from both sides);
//  - W(0) = sigma = 8 / (pi h^3);
//  - the simulation constants stay far below the 64 KiB of CUDA constant memory.
#include <catch2/catch.hpp>

#include <cmath>

#include "common/kernels.h"
#include "common/params.h"

#include "formula_fixture.h"

TEST_CASE("cubic spline equals the seed's M4 with h_s = h / 2", "[kernels]") {
  for (double h : {1.0, 0.0195}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    for (int i = 1; i < 100; ++i) {
      const double r = h * i / 100.0;
      INFO("h = " << h << ", r/h = " << r / h);
      CHECK(double(sph::cubic_spline(k, float(r))) == Approx(sph_test::seed_cubic_w(r, h)).epsilon(1e-5));
      CHECK(double(sph::cubic_spline_grad_fac(k, float(r))) * r == Approx(sph_test::seed_cubic_dwdr(r, h)).epsilon(1e-4));
    }
    const double sigma = 8.0 / (sph::kPiDouble * h * h * h);
    CHECK(double(sph::cubic_spline(k, 0.0f)) == Approx(sigma).epsilon(1e-6));
  }
}

TEST_CASE("cubic spline and its gradient are continuous at q = 1/2", "[kernels]") {
  for (double h : {1.0, 0.0195}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    const double sigma = 8.0 / (sph::kPiDouble * h * h * h);
    const float half = 0.5f * float(h);
    // Either side of the joint, a few float steps apart: both branches give sigma / 4 and dW/dr = -3 sigma / (2 h).
    const float below = std::nextafter(std::nextafter(half, 0.0f), 0.0f);
    const float above = std::nextafter(std::nextafter(half, 1e30f), 1e30f);
    INFO("h = " << h);
    for (float r : {below, half, above}) {
      CHECK(double(sph::cubic_spline(k, r)) == Approx(0.25 * sigma).epsilon(1e-5));
      CHECK(double(sph::cubic_spline_grad_fac(k, r)) * r == Approx(-1.5 * sigma / h).epsilon(1e-5));
    }
  }
}

TEST_CASE("simulation constants stay far below the 64 KiB of CUDA constant memory", "[kernels]") {
  INFO("sizeof(SimConstants) = " << sizeof(sph::SimConstants) << " bytes");
  CHECK(sizeof(sph::SimConstants) <= 16 * 1024);
}
