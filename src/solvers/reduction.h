// Deterministic sums over particles (issue 12, item 1): the iterative solvers' convergence tests. The order of
// the additions is fixed here, once, for every back end: values f(i) are summed in double in groups of
// kReduceWidth consecutive indices, each group from its first index to its last; the group sums again in
// groups of kReduceWidth, and so on until one value is left. `cpu` runs the groups one after another,
// `host` and `cuda` in parallel (one loop per level), and all get the same bits, whatever the scheduling.
// (A serial sum from 0 to n - 1 would be the plainest order, but a GPU can only run it on one thread.)
#pragma once

#include <cstdint>

#include "../common/sph_hd.h"

namespace sph {

constexpr int32_t kReduceWidth = 32;

// Groups at a level of n values.
SPH_HD inline int32_t reduce_groups(int32_t n) { return (n + kReduceWidth - 1) / kReduceWidth; }

// The first level: out[g] = f(g w) + f(g w + 1) + ... over the group's indices below n, in double. f: a
// functor of a particle index returning a number (SPH_HD: it runs where the loop runs).
template <class F>
struct GroupSumFn {
  F f;
  int32_t n;
  double* out;
  SPH_HD void operator()(int32_t g) const {
    const int32_t begin = g * kReduceWidth;
    const int32_t end = begin + kReduceWidth < n ? begin + kReduceWidth : n;
    double sum = 0.0;
    for (int32_t i = begin; i < end; ++i) sum += double(f(i));
    out[g] = sum;
  }
};

// The values of an array as f(i): a solver's per-particle errors (float), and the levels above the first
// (double: out[g] = in[g w] + ... over the group's entries below n).
template <class T>
struct ValuesOf {
  const T* values;
  SPH_HD double operator()(int32_t i) const { return double(values[i]); }
};

// The whole sum of f(0) ... f(n - 1) in the order above, with loop(count, functor) running functor(g) for
// every g < count (a back end's for_each over groups) and two buffers of at least reduce_groups(n) doubles
// each, where the levels go. Returns where the sum is (one of the two buffers: the caller reads it, on a GPU
// the one copy to the host), or nullptr for n = 0 (the sum is 0).
template <class F, class Loop>
const double* reduce_sum_into(int32_t n, const F& f, double* a, double* b, Loop&& loop) {
  if (n <= 0) return nullptr;
  int32_t m = reduce_groups(n);
  loop(m, GroupSumFn<F>{f, n, a});
  while (m > 1) {
    const int32_t next = reduce_groups(m);
    loop(next, GroupSumFn<ValuesOf<double>>{ValuesOf<double>{a}, m, b});
    double* t = a;
    a = b;
    b = t;
    m = next;
  }
  return a;
}

// The mean of values[0 .. n - 1] through the back end's deterministic sum (Exec::sum, execution.h); 0 for
// n = 0. The iterative solvers' convergence test.
template <class Exec>
double mean_of(Exec& x, const float* values, int32_t n) {
  return n > 0 ? x.sum(n, ValuesOf<float>{values}) / double(n) : 0.0;
}

}  // namespace sph
