// Chebyshev's semi-iterative acceleration of a Jacobi iteration ([Wan15]: H. Wang 2015, "A Chebyshev
// semi-iterative approach for accelerating projective and position-based dynamics", ACM TOG 34(6)), shared by
// DFSPH's pressure solves and PBF's constraint solve: iterate k is extrapolated from iterate k - 1 by the
// weight omega_k, x_k = omega_k (x_jacobi - x_(k-2)) + x_(k-2) in the paper's notation.
#pragma once

#include "../common/sph_hd.h"

namespace sph {

// The weight after `previous` ([Wan15]): omega_1 = 1, omega_2 = 2 / (2 - rho^2), omega_k =
// 4 / (4 - rho^2 omega_(k-1)); previous == 1 starts the sequence (omega_2). rho: the estimate of the plain
// iteration's spectral radius, in [0, 1) (at 1 the weights grow without bound); rho = 0 gives 1 throughout,
// plain Jacobi. Dimensionless.
inline float chebyshev_next_weight(float rho, float previous) {
  return previous == 1.0f ? 2.0f / (2.0f - rho * rho) : 4.0f / (4.0f - rho * rho * previous);
}

// The extrapolated iterate ([Wan15]): omega (next - previous) + previous, from the Jacobi iterate `next` and
// the iterate one iteration back, `previous`; omega = 1 (the first iteration, or rho = 0) gives next itself.
// T: float (DFSPH's stiffnesses [m^2/s^2]) or Vec3 (PBF's positions [m]).
template <class T>
SPH_HD inline T chebyshev_extrapolate(T next, T previous, float omega) {
  return omega != 1.0f ? omega * (next - previous) + previous : next;
}

}  // namespace sph
