#pragma once
// The LDL^T factor of the constraint coupling K (coupling_solve.cpp) and the lower bounds
// of K's smallest eigenvalue it gives.
#include <algorithm>
#include <cmath>
#include <limits>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "pair.hpp"

namespace achd {

// K = L D L^T for an n x n K (n = N fixed, so that the loops unroll, or N = 0 and n =
// K's size), L unit lower triangular, D diagonal, kept with the pivots' reciprocals. No
// square roots: one division per column is the whole sequential part.
// With N = 0 (more than 6 columns, several blocks; a dense K of 12 or 15 has N = 12 or
// 15, see solve_by_ldlt) the factor skips K's envelope: row i's entries left of first(i), its
// first nonzero, are exact zeros that stay zero in L, so every sum starts at first(i)
// (blocks on different limbs of a fixed-base tree couple nothing: K is block diagonal
// and costs the sum of its blocks). Skipping exact zeros changes no result.
template <int N>
struct Ldlt {
  static constexpr int C = N > 0 ? N : kMaxConstraintColumns;  // storage
  int n_ = N;        // the size when N = 0
  int first_[C]{};   // N = 0: the first nonzero column of each row of K's lower triangle
  double L[C][C], Dinv[C];  // L[k][i] = L_ik: L by columns, a column's rows adjacent

  int size() const {
    if constexpr (N > 0) return N;
    return n_;
  }
  int first(int i) const {
    if constexpr (N > 0) return 0;
    return first_[i];
  }

  // False if a pivot is not positive (K is not numerically positive definite).
  bool factor(const CouplingMatrix& K) {
    if constexpr (N > 0) return factor_dense(K);
    if constexpr (N == 0) {
      n_ = static_cast<int>(K.rows());
      bool dense = true;
      for (int i = 0; i < n_; ++i) {
        int f = 0;
        while (f < i && K(i, f) == 0) ++f;
        first_[i] = f;
        dense = dense && f == 0;
      }
      if (dense) return factor_by_columns(K);
    }
    const int n = size();
    double W[C][C];  // W[i][k] = L[i][k] d_k
    for (int j = 0; j < n; ++j) {
      // d_j = K_jj - sum_k L_jk W_jk;  L_ij = (K_ij - sum_k L_ik W_jk) / d_j
      double d = K(j, j);
      for (int k = first(j); k < j; ++k) d -= L[k][j] * W[j][k];
      if (!(d > 0)) return false;
      Dinv[j] = 1 / d;
      for (int i = j + 1; i < n; ++i) {
        if (first(i) > j) {  // outside the envelope: exactly 0
          W[i][j] = L[j][i] = 0;
          continue;
        }
        double w = K(i, j);
        for (int k = std::max(first(i), first(j)); k < j; ++k) w -= L[k][i] * W[j][k];
        W[i][j] = w;
        L[j][i] = w * Dinv[j];
      }
    }
    return true;
  }

  // factor for N > 0 (every first(i) = 0): the same operations in the same order, its
  // triangular loops unrolled, which clang does not do by itself for N = 12 (the factor,
  // solve and bounds of the floating quadruped's K: 4.2k instructions rolled, 2.0k) or 15,
  // and two rows of a column to a Pair (L and W by columns, so that the rows are adjacent).
  // The Delta robot's five loops (N = 15): 6.3k instructions right-looking by columns,
  // 3.6k unrolled one row at a time, 1.8k two rows at a time.
  bool factor_dense(const CouplingMatrix& K) {
    double W[C][C];  // W[k][i] = L_ik d_k, by columns like L
#pragma GCC unroll 15
    for (int j = 0; j < N; ++j) {
      double d = K(j, j);
#pragma GCC unroll 15
      for (int k = 0; k < j; ++k) d -= L[k][j] * W[k][j];
      if (!(d > 0)) return false;
      Dinv[j] = 1 / d;
      // rows i and i + 1 of column j together: each lane takes factor's terms in its order
      int i = j + 1;
#pragma GCC unroll 15
      for (; i + 1 < N; i += 2) {
        Pair w = load_pair(&K(i, j));
#pragma GCC unroll 15
        for (int k = 0; k < j; ++k) w -= load_pair(&L[k][i]) * splat(W[k][j]);
        store_pair(&W[j][i], w);
        store_pair(&L[j][i], w * splat(Dinv[j]));
      }
      if (i < N) {  // the last row, when N - j - 1 is odd
        double w = K(i, j);
#pragma GCC unroll 15
        for (int k = 0; k < j; ++k) w -= L[k][i] * W[k][j];
        W[j][i] = w;
        L[j][i] = w * Dinv[j];
      }
    }
    return true;
  }

  // factor for N = 0 when every first(i) = 0 (a dense K of more than 6 columns that is not
  // the unrolled 12 or 15), right-looking: once column j
  // is final, every entry (i, l) below and right of it takes its term,
  //   A_il -= L_ij W_lj  (i >= l > j),  A = K to start,
  // two rows i to a Pair (A is column-major like K, so rows i and i + 1 are adjacent), and
  // columns j and j + 1 applied in one pass (column j + 1 takes column j's term first, to
  // be final). Each entry receives the same terms in the same order (j ascending) as
  // factor's sums, so L, D and every result are factor's to the bit, in fewer instructions
  // (5.5 per term against 8 and more).
  bool factor_by_columns(const CouplingMatrix& K) {
    const int n = n_;
    // A(i, l) = A[l * n + i], K's layout; only its lower triangle is read. The last Pair of
    // a column reaches one row past it, into the next column's upper triangle (or the pad).
    double A[C * C + 1];
    std::copy(K.data(), K.data() + n * n, A);
    A[n * n] = 0;
    double lj[C + 1], lk[C + 1];  // L_ij and L_i,j+1 (0 past n)
    lj[n] = lk[n] = 0;
    // Column j final: its pivot and L_ij.
    const auto finish = [&](int j, double* l) {
      const double d = A[j * n + j];
      if (!(d > 0)) return false;
      Dinv[j] = 1 / d;
      for (int i = j + 1; i < n; ++i) l[i] = L[j][i] = A[j * n + i] * Dinv[j];  // W_ij = A(i, j)
      return true;
    };
    int j = 0;
    for (; j + 1 < n; j += 2) {
      if (!finish(j, lj)) return false;
      const int k = j + 1;
      {  // column k takes column j's term
        const Pair w = splat(A[j * n + k]);
        for (int i = k; i < n; i += 2) store_pair(&A[k * n + i], load_pair(&A[k * n + i]) - load_pair(&lj[i]) * w);
      }
      if (!finish(k, lk)) return false;
      for (int l = k + 1; l < n; ++l) {
        const Pair wj = splat(A[j * n + l]), wk = splat(A[k * n + l]);  // W_lj, W_lk
        double* a = &A[l * n];
        for (int i = l; i < n; i += 2)
          store_pair(a + i, (load_pair(a + i) - load_pair(&lj[i]) * wj) - load_pair(&lk[i]) * wk);
      }
    }
    return j == n || finish(j, lj);  // n odd: the last pivot
  }

  // x = K^-1 b: L y = b, then L^T x = D^-1 y.
  void solve(const ConstraintVector& b, ConstraintVector& x) const {
    const int n = size();
    double y[C];
    for (int i = 0; i < n; ++i) {
      double s = b[i];
      for (int k = first(i); k < i; ++k) s -= L[k][i] * y[k];
      y[i] = s;
    }
    x.resize(n);
    for (int i = n - 1; i >= 0; --i) {
      double s = y[i] * Dinv[i];
      for (int k = i + 1; k < n; ++k) s -= L[i][k] * x[k];
      x[i] = s;
    }
  }

  // An upper bound of ||K^-1||_inf, K^-1's largest absolute row sum: with M = L's comparison
  // matrix (1 on the diagonal, -|L_ik| below it), |L^-1| <= M^-1 entrywise (by induction
  // over forward substitution; M^-1 >= 0), so |K^-1| = |L^-T D^-1 L^-1| <= M^-T D^-1 M^-1
  // and ||K^-1||_inf <= max_i (M^-T D^-1 M^-1 1)_i: one forward and one backward
  // substitution of nonnegative terms, O(n^2). Rows outside the envelope add exact zeros.
  double inverse_row_sum_bound() const {
    const int n = size();
    double y[C], z[C];
    for (int i = 0; i < n; ++i) {  // y = M^-1 1
      double s = 1;
      for (int k = first(i); k < i; ++k) s += std::abs(L[k][i]) * y[k];
      y[i] = s;
    }
    double largest = 0;
    for (int i = n - 1; i >= 0; --i) {  // z = M^-T D^-1 y
      double s = Dinv[i] * y[i];
      for (int k = i + 1; k < n; ++k) s += std::abs(L[i][k]) * z[k];
      z[i] = s;
      largest = std::max(largest, s);
    }
    return largest;
  }

  // trace(K^-1) = sum_ij (L^-1)_ij^2 / d_i, column by column of L^-1 (forward
  // substitution; the columns are independent). In column j, `reach` is the last row
  // whose entry may be nonzero: a row whose envelope starts after it has an exact 0.
  double inverse_trace() const {
    const int n = size();
    double t = 0;
    for (int j = 0; j < n; ++j) {
      double c[C];
      t += Dinv[j];
      c[j] = 1;
      int reach = j;
      for (int i = j + 1; i < n; ++i) {
        if (first(i) > reach) {
          c[i] = 0;
          continue;
        }
        double s = -L[j][i];
        for (int k = std::max(j + 1, first(i)); k < i; ++k) s -= L[k][i] * c[k];
        c[i] = s;
        t += s * s * Dinv[i];
        reach = i;
      }
    }
    return t;
  }
};

// 1 / trace(K^-1) <= lambda_min (trace(K^-1) = sum 1/lambda), within a factor n of it;
// shrunk by a few ulps to stay below it despite its own round-off. O(n^3).
template <int N>
double lower_bound_of_lambda_min(const Ldlt<N>& f) {
  return (1 - 16 * f.size() * std::numeric_limits<double>::epsilon()) / f.inverse_trace();
}

// 1 / ||K^-1||_inf <= 1 / ||K^-1||_2 = lambda_min (Ldlt::inverse_row_sum_bound), within a
// small factor of it when L's entries do not cancel (0.47 to 0.94 of lambda_min on the
// quadruped's, the dual-arm torso's and the floating humanoid's K of 12 columns); shrunk
// by a few ulps, as above (its sums add nonnegative terms: their computed values are
// within 2n roundings of the exact ones). O(n^2).
template <int N>
double row_sum_bound_of_lambda_min(const Ldlt<N>& f) {
  return (1 - 16 * f.size() * std::numeric_limits<double>::epsilon()) / f.inverse_row_sum_bound();
}

// det K ((n - 1) / trace K)^(n-1) <= lambda_min for n >= 2 (0 for n = 1): the other n - 1
// eigenvalues sum to at most trace K, so their product is at most (trace K / (n - 1))^(n-1)
// (AM-GM), and det K = prod d_i. With t = trace K / (n - 1): lambda_min >= t / prod (t / d_i).
// O(n) from the pivots, and as tight as 1 / trace(K^-1) when the other eigenvalues are alike
// (the quadruped's four feet); a spread spectrum (positions and angles mixed) makes it
// small, and the caller tries the next bound. Shrunk by (n^2 + 2n) eps, twice its round-off: the n roundings of t (the
// trace's n - 1, the division's) enter to the power n - 1, the 3n of the pivots'
// reciprocals and the products once. (A product that overflows gives 0.)
template <int N>
double determinant_bound_of_lambda_min(const Ldlt<N>& f, double trace) {
  const int n = f.size();
  if (n < 2) return 0;
  const double t = trace / (n - 1);
  double p = 1;
  for (int i = 0; i < n; ++i) p *= f.Dinv[i] * t;
  return (1 - (n * n + 2 * n) * std::numeric_limits<double>::epsilon()) * (t / p);
}

}  // namespace achd
