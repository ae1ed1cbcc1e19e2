// DFSPH per-particle formulas (src/common/dfsph.h, [BK15] as seed 000 numbers it):
//  - alpha on a lattice against an independent double-precision brute force (cubic spline written out here);
//  - alpha, the density stiffness and the pressure acceleration together undo a particle's own density error
//    exactly (the derivation of alpha), and an isolated particle gets alpha = 0 (the guard);
//  - D rho / Dt: exactly 0 for a rigid translation, 0 to round-off for a rigid rotation, positive under
//    compression, and -rho0 div v for linear fields up to the lattice quadrature error;
//  - the pressure acceleration conserves linear momentum on a random cloud with random kappas, which the
//    seed's misprinted eq. 15 (kappa_j / rho_i) does not;
//  - the CFL step.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "common/dfsph.h"
#include "formula_fixture.h"

namespace {

using sph::Vec3;
using sph_test::FormulaCloud;

constexpr float kSpacing = 0.01f;  // d [m]
constexpr double kH = 1.95 * 0.01;  // h [m], the project's h / d of about 2
constexpr float kRho0 = 1000.0f;
constexpr float kMass = kRho0 * kSpacing * kSpacing * kSpacing;  // m = rho0 d^3 [kg]

// L = sum over the lattice offsets x_j of x_jx^2 / r (-dW/dr) [1/m^3], in double: an interior particle's
// sum_j m (x_j - x_i) (x) grad_i W_ij is m L I, and m L = rho0 in the continuum limit (L d^3 = 1).
double lattice_gradient_moment(double d, double h) {
  double sum = 0.0;
  for (int z = -3; z <= 3; ++z)
    for (int y = -3; y <= 3; ++y)
      for (int x = -3; x <= 3; ++x) {
        const double r = d * std::sqrt(double(x * x + y * y + z * z));
        if (r > 0.0 && r < h) sum += (x * d) * (x * d) / r * -sph_test::seed_cubic_dwdr(r, h);
      }
  return sum;
}

std::vector<Vec3> lattice(int n, float d = kSpacing) { return sph_test::cubic_lattice(n, d, Vec3{0.1f, 0.2f, 0.3f}); }

void compute_density(FormulaCloud& cloud) {
  sph::ParticleView p = cloud.view();
  for (int32_t i = 0; i < cloud.size(); ++i) p.density[i] = sph::dfsph_density(cloud.c(), cloud.grid(), p, i);
}

bool interior_of_lattice(Vec3 x, int n, float margin) {
  const Vec3 lo{0.1f, 0.2f, 0.3f};
  return sph_test::interior(x, lo, lo + float(n - 1) * kSpacing * Vec3{1.0f, 1.0f, 1.0f}, margin);
}

// [BK15]'s density and alpha of particle i by brute force over every particle, in double, with the kernel
// W(r) and dW/dr(r) given: rho = sum m W, alpha = rho / (|sum m grad W|^2 + sum |m grad W|^2).
struct BruteForce {
  double rho, alpha;
};
template <class W, class DwDr>
BruteForce brute_force_alpha(const sph::ParticleView& p, int32_t count, int32_t i, W w, DwDr dwdr) {
  double rho = 0.0, sx = 0.0, sy = 0.0, sz = 0.0, s2 = 0.0;
  for (int32_t j = 0; j < count; ++j) {
    const double dx = double(p.pos[i].x) - p.pos[j].x, dy = double(p.pos[i].y) - p.pos[j].y,
                 dz = double(p.pos[i].z) - p.pos[j].z;
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    rho += kMass * w(r);
    if (r == 0.0) continue;
    const double g = kMass * dwdr(r) / r;
    sx += g * dx;
    sy += g * dy;
    sz += g * dz;
    s2 += g * g * r * r;
  }
  return {rho, rho / (sx * sx + sy * sy + sz * sz + s2)};
}

}  // namespace

TEST_CASE("DFSPH alpha on a lattice equals a double-precision brute force", "[dfsph]") {
  const int n = 8;
  FormulaCloud cloud(lattice(n), kH, kMass, kRho0);
  compute_density(cloud);
  sph::ParticleView p = cloud.view();
  int interior = 0;
  float interior_alpha = -1.0f;
  for (int32_t i = 0; i < cloud.size(); ++i) {
    const auto [rho, alpha] = brute_force_alpha(p, cloud.size(), i, [](double r) { return sph_test::seed_cubic_w(r, kH); },
                                                [](double r) { return sph_test::seed_cubic_dwdr(r, kH); });
    const float got = sph::dfsph_alpha(cloud.c(), cloud.grid(), p, i);
    INFO("particle " << i << ": rho " << p.density[i] << " (brute force " << rho << "), alpha " << got
                     << " (brute force " << alpha << ")");
    REQUIRE(std::fabs(p.density[i] - rho) <= 1e-5 * rho);
    REQUIRE(std::fabs(got - alpha) <= 1e-4 * alpha);
    if (interior_of_lattice(p.pos[i], n, float(kH))) {
      ++interior;
      // Every interior particle sees the same neighbourhood: the same alpha to round-off.
      if (interior_alpha < 0.0f) interior_alpha = got;
      CHECK(std::fabs(got - interior_alpha) <= 1e-5f * interior_alpha);
    }
  }
  CHECK(interior == 4 * 4 * 4);
  // Surface particles have fewer neighbours but a non-zero |sum grad|^2; alpha stays of the same order.
  INFO("interior alpha " << interior_alpha << " m^5/kg");
  CHECK(interior_alpha > 0.0f);
}

TEST_CASE("DFSPH alpha, kappa and the pressure acceleration undo a particle's own density error", "[dfsph]") {
  // [BK15]'s alpha is derived so that kappa_i = (rho*_i - rho0) alpha_i / dt^2, applied through the symmetric
  // pressure acceleration to i and its neighbours (all other kappas 0), changes rho_i by exactly
  // -(rho*_i - rho0) over dt (equal masses). Checked for an interior and a surface particle.
  const int n = 7;
  FormulaCloud cloud(lattice(n), kH, kMass, kRho0);
  compute_density(cloud);
  sph::ParticleView p = cloud.view();
  const float dt = 1e-3f, error = 2.5f;  // rho*_i - rho0 [kg/m^3]
  for (bool surface : {false, true}) {
    int32_t i = -1;
    for (int32_t a = 0; a < cloud.size() && i < 0; ++a)
      if (interior_of_lattice(p.pos[a], n, float(kH)) != surface) i = a;
    REQUIRE(i >= 0);
    std::vector<float> kappa(std::size_t(cloud.size()), 0.0f);
    const float alpha = sph::dfsph_alpha(cloud.c(), cloud.grid(), p, i);
    kappa[std::size_t(i)] = sph::dfsph_density_stiffness(kRho0 + error, kRho0, alpha, dt);
    std::vector<Vec3> dv(std::size_t(cloud.size()));
    for (int32_t a = 0; a < cloud.size(); ++a)
      dv[std::size_t(a)] = dt * sph::dfsph_pressure_acceleration(cloud.c(), cloud.grid(), p, kappa.data(), a);
    const float change = dt * sph::dfsph_density_rate(cloud.c(), cloud.grid(), p, dv.data(), i);
    INFO((surface ? "surface" : "interior") << " particle: alpha " << alpha << ", density change " << change
                                            << " kg/m^3 for an error of " << error);
    CHECK(std::fabs(change + error) <= 1e-4f * error);
  }
}

TEST_CASE("DFSPH alpha is 0 for an isolated particle, not a division by zero", "[dfsph]") {
  // One particle alone, and one whose only neighbour sits at 0.9999 h where grad W is 4e-8 of its peak.
  for (float gap : {0.0f, 0.9999f * float(kH)}) {
    std::vector<Vec3> pos{Vec3{0.1f, 0.1f, 0.1f}};
    if (gap > 0.0f) pos.push_back(Vec3{0.1f + gap, 0.1f, 0.1f});
    FormulaCloud cloud(pos, kH, kMass, kRho0);
    compute_density(cloud);
    sph::ParticleView p = cloud.view();
    INFO("neighbour at " << gap / kH << " h (0: none)");
    const float alpha = sph::dfsph_alpha(cloud.c(), cloud.grid(), p, 0);
    CHECK(alpha == 0.0f);
    // With alpha = 0 the stiffness, and so the pressure, is zero whatever the error.
    CHECK(sph::dfsph_density_stiffness(2.0f * kRho0, kRho0, alpha, 1e-3f) == 0.0f);
  }
}

TEST_CASE("DFSPH density rate: rigid motions give zero, compression a positive rate of -rho0 div v", "[dfsph]") {
  const int n = 9;
  FormulaCloud cloud(lattice(n), kH, kMass, kRho0);
  sph::ParticleView p = cloud.view();
  const Vec3 centre = Vec3{0.1f, 0.2f, 0.3f} + 0.5f * float(n - 1) * kSpacing * Vec3{1.0f, 1.0f, 1.0f};
  const std::size_t count = std::size_t(cloud.size());
  std::vector<Vec3> vel(count);
  const auto rate = [&](int32_t i) { return sph::dfsph_density_rate(cloud.c(), cloud.grid(), p, vel.data(), i); };

  // Rigid translation: every v_i - v_j is exactly 0.
  for (std::size_t i = 0; i < count; ++i) vel[i] = Vec3{0.7f, -1.3f, 0.4f};
  for (int32_t i = 0; i < cloud.size(); ++i) REQUIRE(rate(i) == 0.0f);

  // Rigid rotation v = w x (x - c): each pair term is (w x x_ij) . x_ij = 0; round-off only. The scale of a
  // rate of this field's size is rho0 |w| (a divergence of order |w|).
  const Vec3 w{0.3f, -0.5f, 1.2f};
  for (std::size_t i = 0; i < count; ++i) vel[i] = cross(w, p.pos[i] - centre);
  float worst = 0.0f;
  for (int32_t i = 0; i < cloud.size(); ++i) worst = std::fmax(worst, std::fabs(rate(i)));
  INFO("rigid rotation: largest |D rho/Dt| " << worst << " kg/(m^3 s), against rho0 |w| = " << kRho0 * length(w));
  CHECK(worst <= 1e-4f * kRho0 * length(w));

  // Linear fields v = A (x - c) in the interior: D rho/Dt = -m L tr A exactly (L the lattice's gradient moment,
  // lattice_gradient_moment), which is the continuum's -rho0 div v up to the lattice quadrature L d^3 - 1; so
  // isotropic compression (tr A < 0) gives a positive rate, expansion a negative one and a shear none.
  const double moment = lattice_gradient_moment(kSpacing, kH);
  INFO("lattice quadrature L d^3 = " << moment * kSpacing * kSpacing * kSpacing);
  CHECK(std::fabs(moment * kSpacing * kSpacing * kSpacing - 1.0) < 0.02);
  struct Field {
    const char* name;
    float a[3][3];
  };
  const Field fields[] = {
      {"isotropic compression", {{-0.8f, 0.0f, 0.0f}, {0.0f, -0.8f, 0.0f}, {0.0f, 0.0f, -0.8f}}},
      {"uniaxial expansion", {{1.5f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}}},
      {"general", {{-0.4f, 0.9f, -0.2f}, {0.3f, 0.7f, 0.5f}, {-0.6f, 0.1f, -1.1f}}},
      {"pure shear", {{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}}},
  };
  for (const Field& f : fields) {
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3 x = p.pos[i] - centre;
      vel[i] = Vec3{f.a[0][0] * x.x + f.a[0][1] * x.y + f.a[0][2] * x.z,
                    f.a[1][0] * x.x + f.a[1][1] * x.y + f.a[1][2] * x.z,
                    f.a[2][0] * x.x + f.a[2][1] * x.y + f.a[2][2] * x.z};
    }
    const float trace = f.a[0][0] + f.a[1][1] + f.a[2][2];
    int checked = 0;
    for (int32_t i = 0; i < cloud.size(); ++i) {
      if (!interior_of_lattice(p.pos[i], n, float(kH))) continue;
      ++checked;
      const double expected = -kMass * moment * trace;
      INFO(f.name << ", particle at " << p.pos[i].x << " " << p.pos[i].y << " " << p.pos[i].z << ": D rho/Dt "
                  << rate(i) << ", lattice -m L tr A " << expected << ", continuum -rho0 div v " << -kRho0 * trace);
      // Float round-off of ~100 terms of size m L |A| h: 1e-4 of rho0 |A| (|A| of order 1 /s here).
      CHECK(std::fabs(rate(i) - expected) <= 1e-4 * std::fabs(expected) + 1e-4 * kRho0);
      if (trace < 0.0f) CHECK(rate(i) > 0.0f);
      if (trace > 0.0f) CHECK(rate(i) < 0.0f);
    }
    CHECK(checked == 5 * 5 * 5);
  }
}

TEST_CASE("DFSPH pressure acceleration conserves linear momentum on a random cloud", "[dfsph]") {
  std::mt19937 rng(12);
  const std::vector<Vec3> pos = sph_test::random_positions(rng, 300, 6.0f * kSpacing);
  std::uniform_real_distribution<float> kap(-50.0f, 200.0f);
  FormulaCloud cloud(pos, kH, kMass, kRho0);
  compute_density(cloud);
  sph::ParticleView p = cloud.view();
  std::vector<float> kappa(pos.size());
  for (float& k : kappa) k = kap(rng);  // [m^2/s^2], both signs as the divergence solver's
  Vec3 total{0.0f, 0.0f, 0.0f};
  double magnitude = 0.0;
  // The seed's printed eq. 15/16, kappa_j / rho_i instead of kappa_j / rho_j: not antisymmetric when the
  // densities differ, as in a random cloud, so it does not conserve momentum (why [BK15]'s form is used).
  double seed_x = 0.0, seed_y = 0.0, seed_z = 0.0;
  for (int32_t i = 0; i < cloud.size(); ++i) {
    const Vec3 a = sph::dfsph_pressure_acceleration(cloud.c(), cloud.grid(), p, kappa.data(), i);
    total += kMass * a;
    magnitude += kMass * double(length(a));
    sph::for_each_neighbour(cloud.grid(), p.pos, i, cloud.c().kernel.h2, [&](int32_t j, Vec3 xij, float r2) {
      if (r2 <= 0.0f) return;
      const double s = -double(kMass) * kMass * (kappa[std::size_t(i)] + kappa[std::size_t(j)]) / p.density[i] *
                       sph::cubic_spline_grad_fac(cloud.c().kernel, std::sqrt(r2));
      seed_x += s * xij.x;
      seed_y += s * xij.y;
      seed_z += s * xij.z;
    });
  }
  const double seed_total = std::sqrt(seed_x * seed_x + seed_y * seed_y + seed_z * seed_z);
  INFO("|sum m a| = " << length(total) << " N against sum m |a| = " << magnitude << " N; seed's eq. 15: "
                      << seed_total << " N");
  REQUIRE(magnitude > 0.0);
  CHECK(length(total) <= 1e-5 * magnitude);
  CHECK(seed_total > 1e-3 * magnitude);
  CHECK(seed_total > 1e4 * length(total));
}

TEST_CASE("DFSPH with Poly6 and Spiky: alpha equals a brute force and still undoes a particle's own error", "[dfsph]") {
  // sph.kernel = "poly6_spiky" under DFSPH (SimConstants::dfsph_poly6_spiky, dfsph.h dfsph_w): the density
  // sums Poly6, every gradient is Spiky's. Written out here in double: W = 315 / (64 pi h^9) (h^2 - r^2)^3,
  // dW/dr = -45 / (pi h^6) (h - r)^2 [Mueller 2003].
  const double pi = 3.14159265358979323846;
  const auto poly6 = [&](double r) { return r < kH ? 315.0 / (64.0 * pi * std::pow(kH, 9)) * std::pow(kH * kH - r * r, 3) : 0.0; };
  const auto spiky_dwdr = [&](double r) { return r < kH ? -45.0 / (pi * std::pow(kH, 6)) * (kH - r) * (kH - r) : 0.0; };
  const int n = 7;
  FormulaCloud cloud(lattice(n), kH, kMass, kRho0);
  sph::SimConstants c = cloud.c();
  c.dfsph_poly6_spiky = 1;
  sph::ParticleView p = cloud.view();
  for (int32_t i = 0; i < cloud.size(); ++i) p.density[i] = sph::dfsph_density(c, cloud.grid(), p, i);
  for (int32_t i = 0; i < cloud.size(); ++i) {
    const auto [rho, alpha] = brute_force_alpha(p, cloud.size(), i, poly6, spiky_dwdr);
    const float got = sph::dfsph_alpha(c, cloud.grid(), p, i);
    INFO("particle " << i << ": rho " << p.density[i] << " (brute force " << rho << "), alpha " << got
                     << " (brute force " << alpha << ")");
    REQUIRE(std::fabs(p.density[i] - rho) <= 1e-5 * rho);
    REQUIRE(std::fabs(got - alpha) <= 1e-4 * alpha);
    // Not the cubic spline's: the two kernels' sums differ by percents.
    REQUIRE(std::fabs(sph::dfsph_density(cloud.c(), cloud.grid(), p, i) - p.density[i]) > 1e-3f * p.density[i]);
  }
  // alpha is the inverse of d(D rho_i / Dt) / d kappa_i whatever the kernel, as long as the rate and the
  // pressure acceleration share the gradient: one interior particle's error is undone in one step.
  int32_t i = -1;
  for (int32_t a = 0; a < cloud.size() && i < 0; ++a)
    if (interior_of_lattice(p.pos[a], n, float(kH))) i = a;
  REQUIRE(i >= 0);
  const float dt = 1e-3f, error = 2.5f;
  std::vector<float> kappa(std::size_t(cloud.size()), 0.0f);
  kappa[std::size_t(i)] = sph::dfsph_density_stiffness(kRho0 + error, kRho0, sph::dfsph_alpha(c, cloud.grid(), p, i), dt);
  std::vector<Vec3> dv(std::size_t(cloud.size()));
  for (int32_t a = 0; a < cloud.size(); ++a) dv[std::size_t(a)] = dt * sph::dfsph_pressure_acceleration(c, cloud.grid(), p, kappa.data(), a);
  const float change = dt * sph::dfsph_density_rate(c, cloud.grid(), p, dv.data(), i);
  INFO("density change " << change << " kg/m^3 for an error of " << error);
  CHECK(std::fabs(change + error) <= 1e-4f * error);
}
