#include "coupling_solve.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace achd {
namespace {

// A well-conditioned K is solved by Cholesky when its smallest eigenvalue is at least
// this fraction of trace(K) >= sigma_max (and above the truncation threshold).
constexpr double kCholeskyMinRatio = 1e-8;

// The smallest eigenvalue of the symmetric K (nc <= 6), without eigenvectors:
// Householder reduction to a tridiagonal T = Q^T K Q, then Laguerre's iteration on
// p(x) = det(T - x 1) started below every eigenvalue (Gershgorin), which for a
// polynomial with real roots rises monotonically and cubically to the smallest one.
double smallest_eigenvalue(const CouplingMatrix& K) {
  const int n = static_cast<int>(K.rows());
  CouplingMatrix A = K;
  double d[kMaxConstraints] = {0}, e[kMaxConstraints] = {0};
  ConstraintVector v, p;
  for (int k = 0; k + 2 < n; ++k) {
    // H = 1 - 2 v v^T maps x = A(k+1:, k) to [alpha; 0]; A(k+1:, k+1:) <- H A H
    //   = A - 2 (v w^T + w v^T),  w = A v - (v^T A v) v.
    const int m = n - k - 1;
    const double norm = A.col(k).tail(m).norm();
    const double alpha = A(k + 1, k) > 0 ? -norm : norm;
    e[k] = alpha;
    v = A.col(k).tail(m);
    v[0] -= alpha;
    const double vn = v.norm();
    if (vn == 0) continue;  // already tridiagonal in this column
    v /= vn;
    p.noalias() = A.bottomRightCorner(m, m) * v;
    p -= v.dot(p) * v;
    A.bottomRightCorner(m, m) -= 2 * (v * p.transpose() + p * v.transpose());
  }
  for (int k = 0; k < n; ++k) d[k] = A(k, k);
  if (n >= 2) e[n - 2] = A(n - 1, n - 2);
  double x = d[0], scale = 0;
  for (int k = 0; k < n; ++k) {
    const double r = (k ? std::abs(e[k - 1]) : 0.0) + (k + 1 < n ? std::abs(e[k]) : 0.0);
    x = std::min(x, d[k] - r);
    scale = std::max(scale, std::abs(d[k]) + r);
  }
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

// nu = K^-1 rhs by the eigen-decomposition K = V diag(sigma) V^T with the singularity
// policy (K is symmetric positive semi-definite, so its eigenvalues are its singular
// values; round-off negatives count as zero).
void solve_by_eigen_decomposition(Data& data, const Options& options) {
  const int nc = static_cast<int>(data.M0.rows());
  Eigen::SelfAdjointEigenSolver<CouplingMatrix> eig(data.M0);
  const ConstraintVector sigma = eig.eigenvalues().cwiseMax(0.0);
  const CouplingMatrix& V = eig.eigenvectors();
  const double sigma_max = sigma.size() ? sigma.maxCoeff() : 0.0;
  const double threshold =
      options.absolute_tolerance ? options.tolerance : options.tolerance * sigma_max;
  const double lambda = options.damping * sigma_max;

  // nu = sum_k v_k w_k (v_k^T rhs) with w_k = 1/sigma_k above the threshold and 0 below
  // it (truncate), or w_k = sigma_k / (sigma_k^2 + lambda^2) (damped least squares).
  data.nu.setZero(nc);
  data.rank = 0;
  bool dropped[kMaxConstraints];
  int ndropped = 0;
  for (int k = 0; k < nc; ++k) {
    const bool kept = sigma[k] > threshold;
    data.rank += kept;
    double w;
    if (options.policy == SingularityPolicy::Truncate) {
      w = kept ? 1.0 / sigma[k] : 0.0;
      dropped[k] = !kept;
    } else {
      w = sigma[k] / (sigma[k] * sigma[k] + lambda * lambda);
      dropped[k] = sigma[k] <= lambda;  // damping dominates this direction
    }
    if (w != 0.0) data.nu.noalias() += V.col(k) * (w * V.col(k).dot(data.rhs));
    ndropped += dropped[k];
  }
  data.sigma_min = nc ? sigma.minCoeff() : 0.0;
  data.dropped.resize(nc, ndropped);
  for (int k = 0, j = 0; k < nc; ++k)
    if (dropped[k]) data.dropped.col(j++) = V.col(k);
}

}  // namespace

void solve_coupling(Data& data, const Options& options) {
  const CouplingMatrix& K = data.M0;
  const int nc = static_cast<int>(K.rows());
  if (options.policy == SingularityPolicy::Truncate) {
    // sigma_max <= trace(K): a smallest eigenvalue above both the truncation threshold and
    // kCholeskyMinRatio * trace(K) means full rank, nothing truncated, and nu = K^-1 rhs
    // is accurate by Cholesky.
    const double trace = K.trace();
    const double lambda_min = smallest_eigenvalue(K);
    const double threshold = options.absolute_tolerance ? options.tolerance : options.tolerance * trace;
    if (lambda_min > threshold && lambda_min >= kCholeskyMinRatio * trace) {
      Eigen::LLT<CouplingMatrix> llt(K);
      if (llt.info() == Eigen::Success) {
        data.nu = llt.solve(data.rhs);
        data.rank = nc;
        data.sigma_min = lambda_min;
        data.dropped.resize(nc, 0);
        return;
      }
    }
  }
  solve_by_eigen_decomposition(data, options);
}

}  // namespace achd
