#pragma once
// Whether every number of an array is finite, in one multiply-add per pair of numbers:
// x * 0 is 0 for a finite x and NaN for an infinity or a NaN, and a NaN survives the sum.
// The probe only says whether something is wrong; the code that names the problem runs
// after it has failed.
#include <Eigen/Core>

#include "pair.hpp"

namespace achd {

// 0 when x[0..n) are all finite, NaN otherwise.
inline double finite_probe(const double* x, Eigen::Index n) {
  Pair s = splat(0);
  Eigen::Index i = 0;
  for (; i + 2 <= n; i += 2) s += load_pair(x + i) * splat(0);
  double t = s[0] + s[1];
  if (i < n) t += x[i] * 0.0;
  return t;
}

}  // namespace achd
