#include "surface_tension_csf.h"

#include <cmath>

namespace sph {

double csf_band_integral(double spacing, double h, double lattice_density) {
  const KernelCoeffs k = make_kernel_coeffs(float(h));
  const double volume = spacing * spacing * spacing / lattice_density;
  const long reach = long(std::ceil(h / spacing)) + 1;
  double chi = 0.0;
  // Layer `layer` lies (layer + 1/2) d below the surface; the lattice fills every layer at or below 0.
  for (long layer = 0; layer <= reach; ++layer) {
    double nz = 0.0;
    for (long k2 = 0; k2 <= layer + reach; ++k2)
      for (long j = -reach; j <= reach; ++j)
        for (long i = -reach; i <= reach; ++i) {
          const double dz = double(k2 - layer) * spacing;  // x_i - x_j along z (into the fluid is +z here)
          const double r2 = (double(i * i + j * j)) * spacing * spacing + dz * dz;
          if (r2 <= 0.0 || r2 >= h * h) continue;
          nz += volume * double(poly6_grad_fac(k, float(r2))) * (-dz);
        }
    if (std::fabs(nz) * h > double(kCsfNormalFloor)) chi += spacing * std::fabs(nz);
  }
  return chi;
}

}  // namespace sph
