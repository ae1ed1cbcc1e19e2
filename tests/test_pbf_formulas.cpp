// Position Based Fluids per-particle formulas (src/common/pbf.h, [MM13]):
//  - lambda is 0 where the density is the rest density, positive under expansion (C < 0), negative under
//    compression, and equals an independent double-precision evaluation of its formula;
//  - an isolated particle with epsilon = 0 gets lambda = 0 (the guard), not a division by zero;
//  - position corrections of a pair are equal and opposite, and sum to zero on a random cloud;
//  - s_corr is negative, -k at dq, zero at and beyond h;
//  - one Jacobi iteration reduces the compression of a lattice with max(C, 0), while the paper's C pulls the
//    free surface in and compresses it further;
//  - the vorticity of a rigid rotation is 2 w times the lattice sum inside the fluid; confinement acts along
//    grad |omega| x omega, and not at all for uniform vorticity;
//  - XSPH leaves a rigid translation alone and conserves momentum.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "common/density.h"
#include "common/pbf.h"
#include "formula_fixture.h"

namespace {

// The paper's constraint (clamp_expansion = 0) and s_corr (k = 0.1), which these tests check; the solver's
// default clamps and has k = 0 (params.h, pbf_defaults).
sph::PbfConstants paper_params() {
  sph::PbfConstants p = sph::pbf_defaults();
  p.clamp_expansion = 0;
  p.scorr_k = 0.1f;
  return p;
}

using sph::Vec3;
using sph_test::FormulaCloud;

constexpr float kSpacing = 0.01f;   // d [m]
constexpr double kH = 1.95 * 0.01;  // h [m]
constexpr float kMass = 1000.0f * kSpacing * kSpacing * kSpacing;  // [kg]
const Vec3 kOrigin{0.1f, 0.2f, 0.3f};

// Poly6 density of the interior of an infinite lattice of spacing d, in double: the rest density at which
// that lattice satisfies C = 0.
double lattice_density(double d) {
  const double h2 = kH * kH, c = 315.0 / (64.0 * 3.14159265358979323846 * std::pow(kH, 9));
  double rho = 0.0;
  for (int z = -3; z <= 3; ++z)
    for (int y = -3; y <= 3; ++y)
      for (int x = -3; x <= 3; ++x) {
        const double r2 = (x * x + y * y + z * z) * d * d;
        if (r2 < h2) rho += kMass * c * (h2 - r2) * (h2 - r2) * (h2 - r2);
      }
  return rho;
}

void compute_density(FormulaCloud& cloud) {
  sph::ParticleView p = cloud.view();
  for (int32_t i = 0; i < cloud.size(); ++i) sph::density_of(cloud.c(), cloud.grid(), p, i, 0.0f);
}

std::vector<float> lambdas(FormulaCloud& cloud, const sph::PbfConstants& params) {
  sph::ParticleView p = cloud.view();
  std::vector<float> out(std::size_t(cloud.size()));
  for (int32_t i = 0; i < cloud.size(); ++i)
    out[std::size_t(i)] = sph::pbf_lambda(cloud.c(), cloud.grid(), p, params, i);
  return out;
}

// Lattice points with a full neighbourhood: at least two layers from every face (h < 3 d for every spacing
// used here, so nothing within h is missing).
bool interior(Vec3 x, int n, float d) {
  return sph_test::interior(x, kOrigin, kOrigin + float(n - 1) * d * Vec3{1.0f, 1.0f, 1.0f}, 1.99f * d);
}

// Lattice points none of whose neighbours within h is missing: the nearest missing point, one spacing beyond
// the face, is at least h away.
bool full_neighbourhood(Vec3 x, int n, float d) {
  return sph_test::interior(x, kOrigin, kOrigin + float(n - 1) * d * Vec3{1.0f, 1.0f, 1.0f}, float(kH) - d);
}

}  // namespace

TEST_CASE("PBF lambda: zero at rest density, its sign follows -C, and it equals its formula", "[pbf]") {
  const float rho0 = float(lattice_density(kSpacing));
  const int n = 8;
  const sph::PbfConstants params = paper_params();
  for (float stretch : {1.0f, 1.04f, 0.96f}) {
    const float d = kSpacing * stretch;
    FormulaCloud cloud(sph_test::cubic_lattice(n, d, kOrigin), kH, kMass, rho0);
    compute_density(cloud);
    const std::vector<float> lambda = lambdas(cloud, params);
    sph::ParticleView p = cloud.view();
    const float h2 = cloud.c().kernel.h2;
    int checked = 0;
    for (int32_t i = 0; i < cloud.size(); ++i) {
      // Independent double evaluation: spiky gradient -45/(pi h^6) (h - r)^2 x_ij / r.
      double gx = 0.0, gy = 0.0, gz = 0.0, g2 = 0.0;
      for (int32_t j = 0; j < cloud.size(); ++j) {
        const double dx = double(p.pos[i].x) - p.pos[j].x, dy = double(p.pos[i].y) - p.pos[j].y,
                     dz = double(p.pos[i].z) - p.pos[j].z, r = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (r == 0.0 || r >= kH) continue;
        const double f = kMass / rho0 * -45.0 / (3.14159265358979323846 * std::pow(kH, 6)) * (kH - r) * (kH - r) / r;
        gx += f * dx, gy += f * dy, gz += f * dz, g2 += f * f * r * r;
      }
      const double constraint = double(p.density[i]) / rho0 - 1.0;
      const double expected = -constraint / (g2 + gx * gx + gy * gy + gz * gz + params.relaxation / h2);
      const float got = lambda[std::size_t(i)];
      // The float constraint has a round-off of ~1e-6 (a sum of ~30 terms), lambda that over the denominator.
      const double tolerance = 1e-3 * std::fabs(expected) + 1e-5 * h2;
      INFO("spacing " << stretch << " d: C = " << constraint << ", lambda " << got << " m^2 (formula " << expected
                      << ")");
      CHECK(std::fabs(got - expected) <= tolerance);
      if (!full_neighbourhood(p.pos[i], n, d)) {
        // At the surface neighbours are missing: C < 0 at the rest spacing and beyond, lambda > 0 pulls the
        // surface in; under compression C may have either sign, lambda the other.
        if (stretch >= 1.0f) CHECK(got > 0.0f);
        if (std::fabs(constraint) > 1e-5) CHECK(got * constraint < 0.0);
        continue;
      }
      ++checked;
      if (stretch == 1.0f) {
        CHECK(std::fabs(constraint) < 1e-5);
        CHECK(std::fabs(got) <= 1e-5f * h2);
        // The bulk's denominator sum_k |grad_k C|^2, which PbfConstants::relaxation is measured against.
        INFO("bulk sum |grad C|^2 = " << g2 * h2 << " / h^2");
        CHECK(g2 * h2 > 1.3);
        CHECK(g2 * h2 < 1.7);
      } else {
        if (stretch > 1.0f) CHECK(got > 0.0f);  // expansion: C < 0, lambda > 0
        if (stretch < 1.0f) CHECK(got < 0.0f);  // compression: C > 0, lambda < 0
      }
    }
    CHECK(checked == (stretch < 1.0f ? 4 * 4 * 4 : 6 * 6 * 6));
  }
}

TEST_CASE("PBF lambda of an isolated particle with epsilon = 0 is 0, not a division by zero", "[pbf]") {
  sph::PbfConstants params = paper_params();
  params.relaxation = 0.0f;
  FormulaCloud cloud({Vec3{0.1f, 0.1f, 0.1f}}, kH, kMass, 1000.0f);
  compute_density(cloud);
  sph::ParticleView p = cloud.view();
  // Its own weight only: C = m W(0) / rho0 - 1 != 0, and no gradient at all.
  REQUIRE(sph::pbf_constraint(p.density[0], 1000.0f) != 0.0f);
  const float lambda = sph::pbf_lambda(cloud.c(), cloud.grid(), p, params, 0);
  CHECK(std::isfinite(lambda));
  CHECK(lambda == 0.0f);
  const std::vector<float> l{lambda};
  const Vec3 dp = sph::pbf_position_correction(cloud.c(), cloud.grid(), p, l.data(), params, 0);
  CHECK(length(dp) == 0.0f);
}

TEST_CASE("PBF position corrections are equal and opposite and sum to zero", "[pbf]") {
  const sph::PbfConstants params = paper_params();
  SECTION("a pair, with s_corr") {
    FormulaCloud cloud({Vec3{0.1f, 0.1f, 0.1f}, Vec3{0.1f + 0.3f * float(kH), 0.1f, 0.1f}}, kH, kMass, 1000.0f);
    compute_density(cloud);
    const std::vector<float> lambda = lambdas(cloud, params);
    sph::ParticleView p = cloud.view();
    const Vec3 a = sph::pbf_position_correction(cloud.c(), cloud.grid(), p, lambda.data(), params, 0);
    const Vec3 b = sph::pbf_position_correction(cloud.c(), cloud.grid(), p, lambda.data(), params, 1);
    INFO("Delta p " << a.x << " " << a.y << " " << a.z << " and " << b.x << " " << b.y << " " << b.z);
    CHECK(length(a) > 0.0f);
    CHECK(a.x == -b.x);
    CHECK(a.y == -b.y);
    CHECK(a.z == -b.z);
    // Too light for rho0 (C < 0), lambda > 0 pulls them together; s_corr pushes apart but is smaller here.
    CHECK(dot(a, p.pos[1] - p.pos[0]) > 0.0f);
  }
  SECTION("a random cloud") {
    std::mt19937 rng(7);
    const std::vector<Vec3> pos = sph_test::random_positions(rng, 300, 6.0f * kSpacing);
    FormulaCloud cloud(pos, kH, kMass, 1000.0f);
    compute_density(cloud);
    const std::vector<float> lambda = lambdas(cloud, params);
    sph::ParticleView p = cloud.view();
    Vec3 total{0.0f, 0.0f, 0.0f};
    double magnitude = 0.0;
    for (int32_t i = 0; i < cloud.size(); ++i) {
      const Vec3 dp = sph::pbf_position_correction(cloud.c(), cloud.grid(), p, lambda.data(), params, i);
      total += dp;
      magnitude += length(dp);
    }
    INFO("|sum Delta p| " << length(total) << " m, sum |Delta p| " << magnitude << " m");
    REQUIRE(magnitude > 0.0);
    CHECK(length(total) <= 1e-5 * magnitude);
  }
}

TEST_CASE("PBF s_corr is negative, -k at dq and zero at and beyond h", "[pbf]") {
  const sph::PbfConstants params = paper_params();
  for (double h : {1.0, kH}) {
    const sph::KernelCoeffs k = sph::make_kernel_coeffs(h);
    const float hf = float(h);
    const float dq = params.scorr_dq * hf;
    INFO("h = " << h);
    CHECK(sph::pbf_scorr(k, params, dq * dq) == Approx(-params.scorr_k).epsilon(1e-5));
    float previous = -1e30f;
    for (float q = 0.0f; q < 0.999f; q += 0.05f) {
      const float s = sph::pbf_scorr(k, params, (q * hf) * (q * hf));
      CHECK(s < 0.0f);
      CHECK(s > previous);  // weaker with distance
      previous = s;
    }
    // A neighbour at the rest spacing (about h / 2) gets about 5% of k: (0.75 / 0.96)^12.
    const double at_half_h = -params.scorr_k * std::pow(0.75 / 0.96, 12);
    CHECK(sph::pbf_scorr(k, params, 0.25f * hf * hf) == Approx(at_half_h).epsilon(1e-4));
    for (float r : {hf, 1.0001f * hf, 2.0f * hf}) CHECK(sph::pbf_scorr(k, params, r * r) == 0.0f);
  }
}

TEST_CASE("one PBF Jacobi iteration reduces the compression of a lattice, and the paper's C pulls its surface in",
          "[pbf]") {
  const float rho0 = float(lattice_density(kSpacing));
  const int n = 8;
  const float d = 0.98f * kSpacing;  // 6% over rest density in the bulk
  for (int32_t clamp : {1, 0}) {
    FormulaCloud cloud(sph_test::cubic_lattice(n, d, kOrigin), kH, kMass, rho0);
    sph::PbfConstants params = paper_params();
    params.clamp_expansion = clamp;
    // Compression error: mean of max(C, 0) over all particles, and its largest value in the bulk.
    const auto errors = [&](double& mean, double& bulk_max) {
      compute_density(cloud);
      sph::ParticleView p = cloud.view();
      mean = 0.0;
      bulk_max = 0.0;
      for (int32_t i = 0; i < cloud.size(); ++i) {
        const double c = std::fmax(sph::pbf_constraint(p.density[i], rho0), 0.0f);
        mean += c / cloud.size();
        if (interior(p.pos[i], n, d)) bulk_max = std::fmax(bulk_max, c);
      }
    };
    const auto jacobi_iteration = [&]() {
      compute_density(cloud);
      const std::vector<float> lambda = lambdas(cloud, params);
      sph::ParticleView p = cloud.view();
      std::vector<Vec3> dp(std::size_t(cloud.size()));
      for (int32_t i = 0; i < cloud.size(); ++i)
        dp[std::size_t(i)] = sph::pbf_position_correction(cloud.c(), cloud.grid(), p, lambda.data(), params, i);
      for (int32_t i = 0; i < cloud.size(); ++i) p.pos[i] += dp[std::size_t(i)];  // Jacobi: all at once
      cloud.backend.build_grid();
    };
    double mean0, bulk0, mean1, bulk1;
    errors(mean0, bulk0);
    jacobi_iteration();
    errors(mean1, bulk1);
    INFO((clamp ? "max(C, 0)" : "the paper's C") << ": mean compression " << mean0 << " -> " << mean1
                                                 << ", largest in the bulk " << bulk0 << " -> " << bulk1);
    CHECK(bulk0 > 0.05);
    if (clamp) {
      // The compression is relieved from the free surface inwards: a uniformly compressed bulk has equal
      // lambdas whose gradients cancel, so one iteration moves the outer layers and not yet the bulk.
      CHECK(mean1 < 0.25 * mean0);
      CHECK(bulk1 <= bulk0 + 1e-5);
      for (int iteration = 2; iteration <= 4; ++iteration) jacobi_iteration();
      double mean4, bulk4;
      errors(mean4, bulk4);
      INFO("after 4 iterations: mean compression " << mean4 << ", largest in the bulk " << bulk4);
      CHECK(mean4 < 0.01 * mean0);
      CHECK(bulk4 < 0.01 * bulk0);
    } else {
      // The surface's C < 0 (missing neighbours) gives lambda > 0, which pulls the surface layer inwards: the
      // bulk ends up more compressed than before. Why PbfConstants::clamp_expansion exists.
      CHECK(mean1 > 2.0 * mean0);
    }
  }
}

TEST_CASE("PBF vorticity of a rigid rotation is 2 w in the interior", "[pbf]") {
  const int n = 9;
  FormulaCloud cloud(sph_test::cubic_lattice(n, kSpacing, kOrigin), kH, kMass, 1000.0f);
  compute_density(cloud);
  sph::ParticleView p = cloud.view();
  const Vec3 centre = kOrigin + 0.5f * float(n - 1) * kSpacing * Vec3{1.0f, 1.0f, 1.0f};
  const Vec3 w{0.3f, -0.5f, 1.2f};
  std::vector<Vec3> vel(std::size_t(cloud.size()));
  for (int32_t i = 0; i < cloud.size(); ++i) vel[std::size_t(i)] = cross(w, p.pos[i] - centre);
  std::vector<Vec3> omega(vel.size());
  int checked = 0;
  for (int32_t i = 0; i < cloud.size(); ++i) {
    omega[std::size_t(i)] = sph::pbf_vorticity(cloud.c(), cloud.grid(), p, vel.data(), i);
    if (!interior(p.pos[i], n, kSpacing)) continue;
    ++checked;
    // The SPH curl of a linear field is exact up to the lattice sum mu = sum_j V_j x_jx^2 / r (-dW/dr) (Spiky,
    // V_j = m / rho_j with the Poly6 densities, all equal in the interior), which is 1 in the continuum.
    double mu = 0.0;
    sph::for_each_neighbour(cloud.grid(), p.pos, i, cloud.c().kernel.h2, [&](int32_t j, Vec3 xij, float r2) {
      const double r = std::sqrt(double(r2));
      if (r == 0.0) return;
      const double dwdr = -45.0 / (3.14159265358979323846 * std::pow(kH, 6)) * (kH - r) * (kH - r);
      mu += double(kMass) / p.density[j] * double(xij.x) * xij.x / r * -dwdr;
    });
    const Vec3 err = omega[std::size_t(i)] - float(mu) * 2.0f * w;
    INFO("omega " << omega[std::size_t(i)].x << " " << omega[std::size_t(i)].y << " " << omega[std::size_t(i)].z
                  << " against 2 w = " << 2.0f * w.x << " " << 2.0f * w.y << " " << 2.0f * w.z << ", lattice sum mu = "
                  << mu);
    CHECK(length(err) <= 1e-4f * length(2.0f * w));
    // The lattice's quadrature error (Spiky at h = 1.95 d): omega is 2 w within 6%.
    CHECK(std::fabs(mu - 1.0) < 0.06);
  }
  CHECK(checked == 5 * 5 * 5);

  // Uniform vorticity: grad |omega| is exactly zero, so confinement has no direction and adds nothing (the
  // guard on |eta|, rather than a normalisation of a zero vector).
  sph::PbfConstants params = paper_params();
  params.vorticity_epsilon = 0.5f;
  const std::vector<Vec3> uniform(omega.size(), 2.0f * w);
  for (int32_t i = 0; i < cloud.size(); ++i) {
    const Vec3 a = sph::pbf_vorticity_confinement(cloud.c(), cloud.grid(), p, uniform.data(), params, i);
    REQUIRE(std::isfinite(a.x));
    CHECK(length(a) == 0.0f);
  }
}

TEST_CASE("PBF vorticity confinement pushes across the vorticity, towards stronger vorticity", "[pbf]") {
  const int n = 9;
  FormulaCloud cloud(sph_test::cubic_lattice(n, kSpacing, kOrigin), kH, kMass, 1000.0f);
  compute_density(cloud);
  sph::ParticleView p = cloud.view();
  // omega = (0, 0, omega(x)), |omega| growing with x: v = (0, f(x), 0), omega_z = f'(x) = 2 + 40 x/m.
  std::vector<Vec3> omega(std::size_t(cloud.size()));
  for (int32_t i = 0; i < cloud.size(); ++i) {
    const float x = p.pos[i].x - kOrigin.x;
    omega[std::size_t(i)] = Vec3{0.0f, 0.0f, 2.0f + 40.0f * x};
  }
  sph::PbfConstants params = paper_params();
  for (int32_t i = 0; i < cloud.size(); ++i) {
    CHECK(length(sph::pbf_vorticity_confinement(cloud.c(), cloud.grid(), p, omega.data(), params, i)) == 0.0f);
  }
  params.vorticity_epsilon = 0.5f;  // [m/s]
  int checked = 0;
  for (int32_t i = 0; i < cloud.size(); ++i) {
    if (!interior(p.pos[i], n, kSpacing)) continue;
    ++checked;
    const Vec3 a = sph::pbf_vorticity_confinement(cloud.c(), cloud.grid(), p, omega.data(), params, i);
    const Vec3 wi = omega[std::size_t(i)];
    // N = +x, omega = +z: a = eps (x x z) = -eps |omega| y.
    INFO("a = " << a.x << " " << a.y << " " << a.z);
    CHECK(std::fabs(a.x) <= 1e-3f * length(a));
    CHECK(std::fabs(a.z) <= 1e-3f * length(a));
    CHECK(a.y == Approx(-params.vorticity_epsilon * length(wi)).epsilon(1e-3));
  }
  CHECK(checked == 5 * 5 * 5);
}

TEST_CASE("PBF XSPH leaves a rigid translation alone and conserves momentum", "[pbf]") {
  std::mt19937 rng(3);
  const std::vector<Vec3> pos = sph_test::random_positions(rng, 200, 5.0f * kSpacing);
  std::uniform_real_distribution<float> speed(-1.0f, 1.0f);
  FormulaCloud cloud(pos, kH, kMass, 1000.0f);
  compute_density(cloud);
  sph::ParticleView p = cloud.view();
  const sph::PbfConstants params = paper_params();
  std::vector<Vec3> vel(pos.size(), Vec3{0.3f, -0.2f, 0.9f});
  for (int32_t i = 0; i < cloud.size(); ++i)
    REQUIRE(length(sph::pbf_xsph(cloud.c(), cloud.grid(), p, vel.data(), params, i)) == 0.0f);
  for (Vec3& v : vel) v = Vec3{speed(rng), speed(rng), speed(rng)};
  Vec3 total{0.0f, 0.0f, 0.0f};
  double magnitude = 0.0, smoothing = 0.0;
  for (int32_t i = 0; i < cloud.size(); ++i) {
    const Vec3 dv = sph::pbf_xsph(cloud.c(), cloud.grid(), p, vel.data(), params, i);
    total += dv;
    magnitude += length(dv);
    smoothing += dot(dv, vel[std::size_t(i)]);
  }
  INFO("|sum dv| " << length(total) << ", sum |dv| " << magnitude << ", sum dv . v " << smoothing);
  REQUIRE(magnitude > 0.0);
  CHECK(length(total) <= 1e-5 * magnitude);
  CHECK(smoothing < 0.0);  // it smooths: the velocity field loses kinetic energy
}
