#include "coupling_solve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"  // sigma_min
#include "constraint_count.hpp"

namespace achd {
namespace {

// K is solved by its LDL^T factor when its smallest eigenvalue is provably at least this
// fraction of trace(K) >= sigma_max and above the truncation threshold: then no direction
// is truncated, and the factorisation, backward stable for any positive definite K, keeps
// its pivots well away from round-off (the eigen-decomposition is as accurate there, not
// more).
constexpr double kFactorMinRatio = 1e-11;

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

// K = L D L^T for an n x n K (n = N fixed, so that the loops unroll, or N = 0 and n =
// K's size), L unit lower triangular, D diagonal, kept with the pivots' reciprocals. No
// square roots: one division per column is the whole sequential part.
// With N = 0 (more than 6 columns, several blocks; a dense K of 12 has N = 12, see
// solve_by_ldlt) the factor skips K's envelope: row i's entries left of first(i), its
// first nonzero, are exact zeros that stay zero in L, so every sum starts at first(i)
// (blocks on different limbs of a fixed-base tree couple nothing: K is block diagonal
// and costs the sum of its blocks). Skipping exact zeros changes no result.
template <int N>
struct Ldlt {
  static constexpr int C = N > 0 ? N : kMaxConstraintColumns;  // storage
  int n_ = N;        // the size when N = 0
  int first_[C]{};   // N = 0: the first nonzero column of each row of K's lower triangle
  double L[C][C], Dinv[C];

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
      for (int i = 0; i < n_; ++i) {
        int f = 0;
        while (f < i && K(i, f) == 0) ++f;
        first_[i] = f;
      }
    }
    const int n = size();
    double W[C][C];  // W[i][k] = L[i][k] d_k
    for (int j = 0; j < n; ++j) {
      // d_j = K_jj - sum_k L_jk W_jk;  L_ij = (K_ij - sum_k L_ik W_jk) / d_j
      double d = K(j, j);
      for (int k = first(j); k < j; ++k) d -= L[j][k] * W[j][k];
      if (!(d > 0)) return false;
      Dinv[j] = 1 / d;
      for (int i = j + 1; i < n; ++i) {
        if (first(i) > j) {  // outside the envelope: exactly 0
          W[i][j] = L[i][j] = 0;
          continue;
        }
        double w = K(i, j);
        for (int k = std::max(first(i), first(j)); k < j; ++k) w -= L[i][k] * W[j][k];
        W[i][j] = w;
        L[i][j] = w * Dinv[j];
      }
    }
    return true;
  }

  // factor for N > 0 (every first(i) = 0): the same operations in the same order, its
  // triangular loops unrolled, which clang does not do by itself for N = 12 (the factor,
  // solve and bounds of the floating quadruped's K: 4.2k instructions rolled, 2.0k).
  bool factor_dense(const CouplingMatrix& K) {
    double W[C][C];  // W[i][k] = L[i][k] d_k
#pragma GCC unroll 12
    for (int j = 0; j < N; ++j) {
      double d = K(j, j);
#pragma GCC unroll 12
      for (int k = 0; k < j; ++k) d -= L[j][k] * W[j][k];
      if (!(d > 0)) return false;
      Dinv[j] = 1 / d;
#pragma GCC unroll 12
      for (int i = j + 1; i < N; ++i) {
        double w = K(i, j);
#pragma GCC unroll 12
        for (int k = 0; k < j; ++k) w -= L[i][k] * W[j][k];
        W[i][j] = w;
        L[i][j] = w * Dinv[j];
      }
    }
    return true;
  }

  // x = K^-1 b: L y = b, then L^T x = D^-1 y.
  void solve(const ConstraintVector& b, ConstraintVector& x) const {
    const int n = size();
    double y[C];
    for (int i = 0; i < n; ++i) {
      double s = b[i];
      for (int k = first(i); k < i; ++k) s -= L[i][k] * y[k];
      y[i] = s;
    }
    x.resize(n);
    for (int i = n - 1; i >= 0; --i) {
      double s = y[i] * Dinv[i];
      for (int k = i + 1; k < n; ++k) s -= L[k][i] * x[k];
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
      for (int k = first(i); k < i; ++k) s += std::abs(L[i][k]) * y[k];
      y[i] = s;
    }
    double largest = 0;
    for (int i = n - 1; i >= 0; --i) {  // z = M^-T D^-1 y
      double s = Dinv[i] * y[i];
      for (int k = i + 1; k < n; ++k) s += std::abs(L[k][i]) * z[k];
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
        double s = -L[i][j];
        for (int k = std::max(j + 1, first(i)); k < i; ++k) s -= L[i][k] * c[k];
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

// The fast path of truncate and variable_damping for an n x n K: when the lower bound of
// its smallest eigenvalue is above the truncation threshold, above
// kFactorMinRatio * trace(K) >= kFactorMinRatio * sigma_max and (variable_damping) above
// the singular region singular_region * trace(K) >= singular_region * sigma_max, nothing
// is truncated or damped, and nu = K^-1 rhs is accurate by LDL^T. False (nothing written)
// when K needs the eigen-decomposition.
template <int N>
bool solve_by_ldlt_n(Data& data, const Options& options) {
  const CouplingMatrix& K = data.K;
  Ldlt<N> f;
  if (!f.factor(K)) return false;
  const int n = f.size();
  const double trace = K.trace();
  double threshold = options.absolute_tolerance ? options.tolerance : options.tolerance * trace;
  if (options.policy == SingularityPolicy::VariableDamping)
    threshold = std::max(threshold, options.singular_region * trace);
  auto clears = [&](double below) { return below > threshold && below >= kFactorMinRatio * trace; };
  // The test is lower_bound_of_lambda_min's, O(n^3). A cheaper bound b <= lambda_min
  // settles it first when it can: 1 / trace(K^-1) >= lambda_min / n >= b / n, so b / n
  // clearing (less 64 n ulps for the round-off of both) means the trace bound clears too,
  // and the path taken, and so every result, is the same to the bit.
  const double room = (1 - 64 * n * std::numeric_limits<double>::epsilon()) / n;
  if (!clears(room * determinant_bound_of_lambda_min(f, trace)) && !clears(room * row_sum_bound_of_lambda_min(f)) &&
      !clears(lower_bound_of_lambda_min(f)))
    return false;
  f.solve(data.workspace.rhs, data.nu);
  data.rank = n;
  data.dropped.resize(n, 0);
  data.damped.resize(n, 0);
  data.damped_sigma.resize(0);
  data.damped_lambda.resize(0);
  return true;
}

// m = 12 (four points held in 3D, two poses in 6D) has its own unrolled factor when K is
// dense (a floating base, or blocks sharing joints): every row's envelope starts at column
// 0, so Ldlt<0> would do the same operations in the same order, with loop bounds read at
// run time. A K of separate blocks (legs on a fixed base) keeps Ldlt<0>'s envelope.
bool solve_by_ldlt(Data& data, const Options& options) {
  const int m = static_cast<int>(data.K.rows());
  if (m == 12) {
    bool dense = true;
    for (int i = 1; i < m; ++i) dense = dense && data.K(i, 0) != 0;
    if (dense) return solve_by_ldlt_n<12>(data, options);
  }
  return with_coupling_size(m, [&](auto n) { return solve_by_ldlt_n<decltype(n)::value>(data, options); });
}

// The smallest eigenvalue of the n x n K: by Laguerre's iteration from the LDL^T bound
// when K is clearly positive definite, else from the eigen-decomposition (round-off
// negatives count as zero).
template <int N>
double smallest_eigenvalue_of(const CouplingMatrix& K) {
  Ldlt<N> f;
  if (f.factor(K)) {
    const double below = lower_bound_of_lambda_min(f);
    if (below >= kFactorMinRatio * K.trace()) return N == 1 ? K(0, 0) : smallest_eigenvalue_n<N>(K, below);
  }
  return Eigen::SelfAdjointEigenSolver<CouplingMatrix>(K, Eigen::EigenvaluesOnly).eigenvalues().cwiseMax(0.0).minCoeff();
}

// nu = K^-1 rhs by the eigen-decomposition K = V diag(sigma) V^T with the singularity
// policy (K is symmetric positive semi-definite, so its eigenvalues are its singular
// values; round-off negatives count as zero).
void solve_by_eigen_decomposition(Data& data, const Options& options) {
  const int nc = static_cast<int>(data.K.rows());
  Eigen::SelfAdjointEigenSolver<CouplingMatrix> eig(data.K);
  const ConstraintVector sigma = eig.eigenvalues().cwiseMax(0.0);
  const CouplingMatrix& V = eig.eigenvectors();
  const double sigma_max = sigma.size() ? sigma.maxCoeff() : 0.0;
  const double threshold =
      options.absolute_tolerance ? options.tolerance : options.tolerance * sigma_max;
  const double lambda = options.damping * sigma_max;
  // variable_damping: the singular region sigma < eps and the damping at sigma = 0
  const double eps = options.singular_region * sigma_max;
  const double lambda_max = options.max_damping * sigma_max;

  // nu = sum_k v_k w_k (v_k^T rhs) with w_k = 1/sigma_k above the threshold and 0 below
  // it (truncate), w_k = sigma_k / (sigma_k^2 + lambda^2) (damped least squares), or the
  // same with lambda_k^2 = lambda_max^2 (1 - (sigma_k / eps)^2) in the singular region and
  // w_k = 1/sigma_k outside it (variable damping).
  data.nu.setZero(nc);
  data.rank = 0;
  bool dropped[kMaxConstraintColumns], damped[kMaxConstraintColumns];
  double damping[kMaxConstraintColumns];
  int ndropped = 0, ndamped = 0;
  for (int k = 0; k < nc; ++k) {
    const bool kept = sigma[k] > threshold;
    data.rank += kept;
    double w;
    damped[k] = false;
    if (options.policy == SingularityPolicy::Truncate) {
      w = kept ? 1.0 / sigma[k] : 0.0;
      dropped[k] = !kept;
    } else if (options.policy == SingularityPolicy::Damped) {
      // (0, not 0 / 0, when K = 0: then lambda = 0 too, and no direction has a force)
      w = sigma[k] > 0 ? sigma[k] / (sigma[k] * sigma[k] + lambda * lambda) : 0.0;
      dropped[k] = sigma[k] <= lambda;  // damping dominates this direction
    } else {
      damped[k] = !(sigma[k] > eps);
      const double ratio = sigma[k] / eps;
      damping[k] = damped[k] ? lambda_max * std::sqrt(1 - ratio * ratio) : 0.0;
      const double den = sigma[k] * sigma[k] + damping[k] * damping[k];
      if (!damped[k]) w = 1.0 / sigma[k];   // the exact solve, as truncate's
      else w = den > 0 ? sigma[k] / den : 0.0;  // den = 0 only for K = 0: nothing to solve
      dropped[k] = damped[k] && sigma[k] <= damping[k];
      ndamped += damped[k];
    }
    if (w != 0.0) data.nu.noalias() += V.col(k) * (w * V.col(k).dot(data.workspace.rhs));
    ndropped += dropped[k];
  }
  data.dropped.resize(nc, ndropped);
  for (int k = 0, j = 0; k < nc; ++k)
    if (dropped[k]) data.dropped.col(j++) = V.col(k);
  data.damped.resize(nc, ndamped);
  data.damped_sigma.resize(ndamped);
  data.damped_lambda.resize(ndamped);
  for (int k = 0, j = 0; k < nc; ++k) {
    if (!damped[k]) continue;
    data.damped.col(j) = V.col(k);
    data.damped_sigma[j] = sigma[k];
    data.damped_lambda[j++] = damping[k];
  }
}

// variable_damping measures the singular region on K with its columns scaled by kind:
// K' = S K S, S_i = (max K_jj over the columns j of column i's kind)^-1/2, the kinds being
// columns with a force part (positions: K_ii in 1/kg) and pure moments (angles: 1/kg m^2).
// K's own eigenvalues mix the two (at a wrist a held angle's K_ii is 1e3 times a held
// position's), so a region relative to its sigma_max would call a regular position
// column singular; in K' both kinds have their largest diagonal 1, and a column whose
// mobility falls (K_ii -> 0) or that becomes dependent on others has a small eigenvalue.
// (A column that is the only one of its kind is measured against itself: only its
// dependence on the other kind is seen, not its own loss.) The solve is K' nu' = S rhs,
// nu = S nu': without damping, nu = K^-1 rhs as before. The damped directions are
// reported in the scaled columns.
// The variable-damping gain of a singular value sigma (region eps, damping lambda_max).
double variable_damping_gain(double sigma, double eps, double lambda_max) {
  if (sigma > eps) return 1.0 / sigma;
  const double ratio = sigma / eps, lambda2 = lambda_max * lambda_max * (1 - ratio * ratio);
  const double den = sigma * sigma + lambda2;
  return den > 0 ? sigma / den : 0.0;
}

// After solve_by_eigen_decomposition has damped some eigen-directions of K (data.K,
// data.workspace.rhs: the scaled K' and rhs): the columns L those directions belong to
// (each one's largest component) give way, and the others H are solved exactly, so that
// a lost direction does not take the accuracy of the held ones with it. With K in
// blocks, nu_H = K_HH^-1 (rhs_H - K_HL nu_L), and nu_L solves the Schur complement
// S = K_LL - K_LH K_HH^-1 K_HL (the coupling of L once H is enforced) with the same
// variable damping. False (nothing written) when every column gives way, when two
// damped directions fall on one column, or when K_HH has an eigenvalue in the singular
// region itself: then the plain variable damping stands.
bool solve_held_first(Data& data, const Options& options) {
  const int nc = static_cast<int>(data.K.rows()), ndamped = static_cast<int>(data.damped.cols());
  bool gives_way[kMaxConstraintColumns] = {false};
  int nl = 0;
  for (int j = 0; j < ndamped; ++j) {
    Eigen::Index column = 0;
    data.damped.col(j).cwiseAbs().maxCoeff(&column);
    nl += !gives_way[column];
    gives_way[column] = true;
  }
  const int nh = nc - nl;
  if (nl != ndamped || nh == 0) return false;
  int h[kMaxConstraintColumns], l[kMaxConstraintColumns];
  for (int i = 0, a = 0, b = 0; i < nc; ++i) (gives_way[i] ? l[b++] : h[a++]) = i;
  const CouplingMatrix& K = data.K;
  const ConstraintVector& rhs = data.workspace.rhs;
  CouplingMatrix Khh(nh, nh), Khl(nh, nl), S(nl, nl);
  ConstraintVector rh(nh), b(nl);
  for (int i = 0; i < nh; ++i) {
    rh[i] = rhs[h[i]];
    for (int j = 0; j < nh; ++j) Khh(i, j) = K(h[i], h[j]);
    for (int j = 0; j < nl; ++j) Khl(i, j) = K(h[i], l[j]);
  }
  const double sigma_max = Eigen::SelfAdjointEigenSolver<CouplingMatrix>(K, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  const double eps = options.singular_region * sigma_max, lambda_max = options.max_damping * sigma_max;
  // H must itself be clear of the singular region, or its exact solve is unbounded.
  const double khh_min = Eigen::SelfAdjointEigenSolver<CouplingMatrix>(Khh, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
  if (!(khh_min > eps)) return false;
  const Eigen::LLT<CouplingMatrix> llt(Khh);
  if (llt.info() != Eigen::Success) return false;
  const CouplingMatrix X = llt.solve(Khl);  // K_HH^-1 K_HL
  const ConstraintVector y = llt.solve(rh);  // K_HH^-1 rhs_H
  for (int i = 0; i < nl; ++i) {
    b[i] = rhs[l[i]] - Khl.col(i).dot(y);
    for (int j = 0; j < nl; ++j) S(i, j) = K(l[i], l[j]) - Khl.col(i).dot(X.col(j));
  }
  S = (S + S.transpose()) / 2;  // symmetric to round-off
  const Eigen::SelfAdjointEigenSolver<CouplingMatrix> eig(S);
  ConstraintVector nu_l = ConstraintVector::Zero(nl);
  for (int k = 0; k < nl; ++k) {
    const double w = variable_damping_gain(std::max(eig.eigenvalues()[k], 0.0), eps, lambda_max);
    if (w != 0.0) nu_l.noalias() += eig.eigenvectors().col(k) * (w * eig.eigenvectors().col(k).dot(b));
  }
  const ConstraintVector nu_h = y - X * nu_l;
  for (int i = 0; i < nh; ++i) data.nu[h[i]] = nu_h[i];
  for (int i = 0; i < nl; ++i) data.nu[l[i]] = nu_l[i];
  return true;
}

void solve_variable_damping(Data& data, const Options& options) {
  const int nc = static_cast<int>(data.K.rows());
  const CouplingMatrix K = data.K;
  const ConstraintVector rhs = data.workspace.rhs;
  double largest[2] = {0, 0};  // per kind: 0 force, 1 pure moment
  int kind[kMaxConstraintColumns];
  for (int i = 0; i < nc; ++i) {
    kind[i] = !data.workspace.has_force[i];
    largest[kind[i]] = std::max(largest[kind[i]], K(i, i));
  }
  ConstraintVector scale(nc);
  for (int i = 0; i < nc; ++i) scale[i] = largest[kind[i]] > 0 ? 1 / std::sqrt(largest[kind[i]]) : 1.0;
  for (int i = 0; i < nc; ++i) {
    for (int j = 0; j < nc; ++j) data.K(i, j) = K(i, j) * scale[i] * scale[j];
    data.workspace.rhs[i] = rhs[i] * scale[i];
  }
  if (!solve_by_ldlt(data, options)) {
    solve_by_eigen_decomposition(data, options);
    if (data.damped.cols()) solve_held_first(data, options);
  }
  for (int i = 0; i < nc; ++i) data.nu[i] *= scale[i];
  data.K = K;  // sigma_min() and the caller read K as it was
  data.workspace.rhs = rhs;
}

}  // namespace

void solve_coupling(Data& data, const Options& options) {
  if (options.policy == SingularityPolicy::VariableDamping) return solve_variable_damping(data, options);
  if (options.policy == SingularityPolicy::Truncate && solve_by_ldlt(data, options)) return;
  solve_by_eigen_decomposition(data, options);
}

double sigma_min(const Data& data) {
  const int nc = static_cast<int>(data.K.rows());
  if (nc == 0) return 0;
  // The coupling of the columns as given, K = S^-1 K_s S^-1 from K_s (data.K) of the
  // scaled columns alpha_k s_k: exact, as the s_k are powers of two, unless K itself is
  // beyond the range of a double.
  CouplingMatrix K = data.K;
  const ConstraintVector& scale = data.workspace.alpha_scale;
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j < nc; ++j) K(i, j) = K(i, j) / scale[i] / scale[j];
  if (!K.allFinite())
    throw Error("sigma_min: the coupling matrix K = A M^-1 A^T of these alpha columns overflows a "
                "double; scale the columns down (a column's scale does not change the solve)");
  // K's largest entry is on its diagonal (K is positive semi-definite). The reduction
  // squares K's entries, which would overflow for entries near 1e155 (a robot whose links
  // weigh 1e-300 kg) or underflow near 1e-155, so it runs on K 2^-e, 2^e <= max K_ii:
  // exact, undone on the result, and a no-op (e = 0) for K_ii of order one.
  const double largest = K.diagonal().maxCoeff();
  if (!(largest > 0)) return 0;  // K = 0: every constraint is singular
  const int e = std::min(std::max(std::ilogb(largest), -1022), 1022);
  K *= std::ldexp(1.0, -e);
  const double smallest =
      with_coupling_size(nc, [&](auto n) { return smallest_eigenvalue_of<decltype(n)::value>(K); });
  return std::ldexp(smallest, e);
}

}  // namespace achd
