#include "coupling_solve.hpp"

#include <Eigen/Eigenvalues>

namespace achd {

void solve_coupling(Data& data, const Options& options) {
  const int nc = static_cast<int>(data.M0.rows());
  // K = V diag(sigma) V^T (K is symmetric positive semi-definite, so its eigenvalues are
  // its singular values; round-off negatives count as zero).
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

}  // namespace achd
