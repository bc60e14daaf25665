#pragma once
// The smallest eigenvalue of the constraint coupling K (coupling_solve.cpp), for the
// eigen-decomposition-free paths of its solve.
#include <algorithm>
#include <cmath>
#include <limits>

#include "achd/data.hpp"

namespace achd {

// The smallest eigenvalue of the symmetric K (nc <= 6), without eigenvectors:
// Householder reduction to a tridiagonal T = Q^T K Q, then Laguerre's iteration on
// p(x) = det(T - x 1) started below every eigenvalue, which for a polynomial with real
// roots rises monotonically and cubically to the smallest one. The start is the larger
// of Gershgorin's bound and `below`, a lower bound the caller may know (0 if none).
// (N is a template parameter so that the short loops unroll, N = 0 for a size known at
// run time only; see smallest_eigenvalue_of.)
template <int N>
double smallest_eigenvalue_n(const CouplingMatrix& K, double below) {
  constexpr int C = N > 0 ? N : kMaxConstraintColumns;  // storage
  const int n = N > 0 ? N : static_cast<int>(K.rows());
  double A[C][C], d[C] = {0}, e[C] = {0};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A[i][j] = K(i, j);
  for (int k = 0; k + 2 < n; ++k) {
    // H = 1 - 2 v v^T maps x = A(k+1:, k) to [alpha; 0]; A(k+1:, k+1:) <- H A H
    //   = A - 2 (v w^T + w v^T),  w = A v - (v^T A v) v.
    double norm2 = 0, v[C], w[C];
    for (int i = k + 1; i < n; ++i) norm2 += A[i][k] * A[i][k];
    const double alpha = A[k + 1][k] > 0 ? -std::sqrt(norm2) : std::sqrt(norm2);
    e[k] = alpha;
    double vn2 = 0;
    for (int i = k + 1; i < n; ++i) {
      v[i] = A[i][k] - (i == k + 1 ? alpha : 0.0);
      vn2 += v[i] * v[i];
    }
    if (vn2 == 0) continue;  // already tridiagonal in this column
    const double vinv = 1 / std::sqrt(vn2);
    double vw = 0;
    for (int i = k + 1; i < n; ++i) v[i] *= vinv;
    for (int i = k + 1; i < n; ++i) {
      w[i] = 0;
      for (int j = k + 1; j < n; ++j) w[i] += A[i][j] * v[j];
      vw += v[i] * w[i];
    }
    for (int i = k + 1; i < n; ++i) w[i] -= vw * v[i];
    for (int i = k + 1; i < n; ++i)
      for (int j = k + 1; j < n; ++j) A[i][j] -= 2 * (v[i] * w[j] + w[i] * v[j]);
  }
  for (int k = 0; k < n; ++k) d[k] = A[k][k];
  if (n >= 2) e[n - 2] = A[n - 1][n - 2];
  double x = d[0], scale = 0;
  for (int k = 0; k < n; ++k) {
    const double r = (k ? std::abs(e[k - 1]) : 0.0) + (k + 1 < n ? std::abs(e[k]) : 0.0);
    x = std::min(x, d[k] - r);
    scale = std::max(scale, std::abs(d[k]) + r);
  }
  x = std::max(x, below);
  for (int it = 0; it < 100; ++it) {
    // p_k = (d_k - x) p_{k-1} - e_{k-1}^2 p_{k-2}, with its first and second derivatives
    double p0 = 1, p1 = 0, q0 = 0, q1 = 0, r0 = 0, r1 = 0;
    for (int k = 0; k < n; ++k) {
      const double e2 = k ? e[k - 1] * e[k - 1] : 0.0, t = d[k] - x;
      const double pn = t * p0 - e2 * p1, qn = t * q0 - p0 - e2 * q1, rn = t * r0 - 2 * q0 - e2 * r1;
      p1 = p0, p0 = pn, q1 = q0, q0 = qn, r1 = r0, r0 = rn;
    }
    if (p0 == 0) break;
    const double G = q0 / p0, H = G * G - r0 / p0;
    const double root = std::sqrt(std::max(0.0, (n - 1) * (n * H - G * G)));
    const double den = G < 0 ? G - root : G + root;
    if (den == 0) break;
    const double step = -n / den;
    if (!(step > 0)) break;  // converged: round-off turned the step around
    x += step;
    if (step <= 4 * std::numeric_limits<double>::epsilon() * scale) break;
  }
  return x;
}

}  // namespace achd
