#include "coupling_solve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"  // sigma_min
#include "constraint_count.hpp"
#include "ldlt.hpp"
#include "smallest_eigenvalue.hpp"

namespace achd {
namespace {

// K is solved by its LDL^T factor when its smallest eigenvalue is provably at least this
// fraction of trace(K) >= sigma_max and above the truncation threshold: then no direction
// is truncated, and the factorisation, backward stable for any positive definite K, keeps
// its pivots well away from round-off (the eigen-decomposition is as accurate there, not
// more).
constexpr double kFactorMinRatio = 1e-11;

// sigma_max(K) <= (sum sigma_k^4)^(1/4) = ||K^2||_F^(1/2) for the symmetric n x n K, within
// n^(1/4) of it (||K||_F = (sum sigma_k^2)^(1/2) is within n^(1/2)), rounded up: each
// computed entry of K^2 is within n u ||K_i|| ||K_j|| of the exact one, so ||K^2||_F is
// within n u ||K||_F^2 of the computed one's norm. O(n^3 / 2), no allocation.
[[gnu::noinline]] double sigma_max_bound(const CouplingMatrix& K) {
  const int n = static_cast<int>(K.rows());
  const double u = std::numeric_limits<double>::epsilon();
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i <= j; ++i) {
      const double c = K.col(i).dot(K.col(j));  // (K^2)_ij, K symmetric
      sum += (i == j ? 1 : 2) * c * c;
    }
  const double fro2 = K.squaredNorm();
  const double norm2 = std::sqrt(sum) * (1 + (n * n + 2) * u) + (n + 2) * u * fro2 * (1 + (n * n + 2) * u);
  return std::sqrt(norm2) * (1 + 4 * u);
}

// True when every eigenvalue of the n x n K (factored as f) is provably above the truncation
// threshold `truncation`, above kFactorMinRatio * trace(K) and above variable_damping's
// singular region eps = singular_region * sigma_max: then the eigen-decomposition would
// truncate and damp nothing. The region is taken at an upper bound of sigma_max, first
// ||K||_F = (sum sigma_k^2)^(1/2) (within n^(1/2) of it; trace(K) = sum sigma_k can be n
// sigma_max), then, if the lower bounds of lambda_min do not clear that, sigma_max_bound's
// tighter one, and raised by a margin of many times the round-off of both this proof and
// the eigen-decomposition's eigenvalues. The last test, K - threshold 1 positive definite
// (its LDL^T has positive pivots; the factor's backward error, below n (n + 1) u ||K||, is
// within the margin), proves every eigenvalue above the threshold in two O(n^3) passes
// (sigma_max_bound, the factor) where the eigen-decomposition takes many. Not inlined:
// its frame (a copy of K and a factor) would otherwise be truncate's too.
template <int N>
[[gnu::noinline]] bool outside_singular_region(const Ldlt<N>& f, const CouplingMatrix& K, double truncation,
                                               const Options& options) {
  const int n = f.size();
  const double u = std::numeric_limits<double>::epsilon();
  const double trace = K.trace();
  const auto threshold = [&](double sigma_max) {
    return std::max({truncation, options.singular_region * sigma_max + 16 * (n * n + n) * u * trace,
                     kFactorMinRatio * trace});
  };
  const double frobenius = threshold(K.norm() * (1 + (n * n + 2) * u));
  const double room = 1 - 64 * n * u;
  if (room * determinant_bound_of_lambda_min(f, trace) > frobenius ||
      room * row_sum_bound_of_lambda_min(f) > frobenius)
    return true;
  CouplingMatrix shifted = K;
  shifted.diagonal().array() -= threshold(sigma_max_bound(K));
  Ldlt<N> g;
  return g.factor(shifted);
}

// The fast path of truncate and variable_damping for an n x n K: when the lower bound of
// its smallest eigenvalue is above the truncation threshold and above
// kFactorMinRatio * trace(K) >= kFactorMinRatio * sigma_max (and, variable_damping,
// outside_singular_region), nothing is truncated or damped, and nu = K^-1 rhs is accurate
// by LDL^T. False (nothing written) when K needs the eigen-decomposition.
template <int N>
bool solve_by_ldlt_n(Data& data, const Options& options) {
  const CouplingMatrix& K = data.K;
  Ldlt<N> f;
  if (!f.factor(K)) return false;
  const int n = f.size();
  const double trace = K.trace();
  const double threshold = options.absolute_tolerance ? options.tolerance : options.tolerance * trace;
  if (options.policy == SingularityPolicy::VariableDamping) {
    if (!outside_singular_region(f, K, threshold, options)) return false;
  } else {
    auto clears = [&](double below) { return below > threshold && below >= kFactorMinRatio * trace; };
    // The test is lower_bound_of_lambda_min's, O(n^3). A cheaper bound b <= lambda_min
    // settles it first when it can: 1 / trace(K^-1) >= lambda_min / n >= b / n, so b / n
    // clearing (less 64 n ulps for the round-off of both) means the trace bound clears too,
    // and the path taken, and so every result, is the same to the bit.
    const double room = (1 - 64 * n * std::numeric_limits<double>::epsilon()) / n;
    if (!clears(room * determinant_bound_of_lambda_min(f, trace)) && !clears(room * row_sum_bound_of_lambda_min(f)) &&
        !clears(lower_bound_of_lambda_min(f)))
      return false;
  }
  f.solve(data.workspace.rhs, data.nu);
  data.rank = n;
  data.dropped.resize(n, 0);
  data.damped.resize(n, 0);
  data.damped_sigma.resize(0);
  data.damped_lambda.resize(0);
  return true;
}

// m = 12 (four points held in 3D, two poses in 6D) and m = 15 (five points held in 3D: the
// Delta robot's loops) have their own unrolled factor when K is dense (a floating base, or
// blocks sharing joints): every row's envelope starts at column
// 0, so Ldlt<0> would do the same operations in the same order, with loop bounds read at
// run time. A K of separate blocks (legs on a fixed base) keeps Ldlt<0>'s envelope.
bool solve_by_ldlt(Data& data, const Options& options) {
  const int m = static_cast<int>(data.K.rows());
  if (m == 12 || m == 15) {
    bool dense = true;
    for (int i = 1; i < m; ++i) dense = dense && data.K(i, 0) != 0;
    if (dense) return m == 12 ? solve_by_ldlt_n<12>(data, options) : solve_by_ldlt_n<15>(data, options);
  }
  return with_coupling_size(m, [&](auto n) { return solve_by_ldlt_n<decltype(n)::value>(data, options); });
}

// The eigen-decomposition of the symmetric n x n K: eigenvalues ascending and, when
// asked, the unit eigenvectors as columns. Eigen's SelfAdjointEigenSolver on a fixed-size
// copy for n <= kMaxConstraints (its loops unrolled: a 6 x 6 decomposition at run-time
// size took most of a damped solve), at run-time size above.
struct SymmetricEigen {
  ConstraintVector values;
  CouplingMatrix vectors;
  SymmetricEigen(const CouplingMatrix& K, bool with_vectors) {
    const int n = static_cast<int>(K.rows());
    const int what = with_vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly;
    if (n == 0) return;
    with_coupling_size(n, [&](auto size) {
      constexpr int N = decltype(size)::value;
      if constexpr (N == 0) {
        const Eigen::SelfAdjointEigenSolver<CouplingMatrix> eig(K, what);
        values = eig.eigenvalues();
        if (with_vectors) vectors = eig.eigenvectors();
      } else {
        const Eigen::Matrix<double, N, N> A = K;
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(A, what);
        values = eig.eigenvalues();
        if (with_vectors) vectors = eig.eigenvectors();
      }
    });
  }
};

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
  return SymmetricEigen(K, false).values.cwiseMax(0.0).minCoeff();
}

// nu = K^-1 rhs by the eigen-decomposition K = V diag(sigma) V^T with the singularity
// policy (K is symmetric positive semi-definite, so its eigenvalues are its singular
// values; round-off negatives count as zero). Returns K's largest eigenvalue.
double solve_by_eigen_decomposition(Data& data, const Options& options) {
  const int nc = static_cast<int>(data.K.rows());
  const SymmetricEigen eig(data.K, true);
  const ConstraintVector sigma = eig.values.cwiseMax(0.0);
  const CouplingMatrix& V = eig.vectors;
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
  // variable_damping: beside the damped solve, the exact one (w_k = 1/sigma_k for every k),
  // when every eigenvalue clears the truncation threshold, for hybrid_dynamics to keep if
  // the joints' efforts allow it (Options::exact_within_efforts).
  ConstraintVector& exact = data.workspace.exact_nu;
  if (options.policy == SingularityPolicy::VariableDamping && options.exact_within_efforts && ndamped &&
      data.rank == nc) {
    exact.setZero(nc);
    for (int k = 0; k < nc; ++k) exact.noalias() += V.col(k) * (V.col(k).dot(data.workspace.rhs) / sigma[k]);
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
  return sigma_max;
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

// x = sum_k v_k w_k (v_k^T b) over the eigen-directions of the symmetric M (round-off
// negatives count as zero), w_k the variable-damping gain with the region and damping
// relative to sigma_max (M's largest eigenvalue when sigma_max < 0).
ConstraintVector variably_damped_solve(const CouplingMatrix& M, const ConstraintVector& b, const Options& options,
                                       double sigma_max) {
  const SymmetricEigen eig(M, true);
  if (sigma_max < 0) sigma_max = std::max(eig.values.maxCoeff(), 0.0);
  const double eps = options.singular_region * sigma_max, lambda_max = options.max_damping * sigma_max;
  ConstraintVector x = ConstraintVector::Zero(M.rows());
  for (int k = 0; k < M.rows(); ++k) {
    const double w = variable_damping_gain(std::max(eig.values[k], 0.0), eps, lambda_max);
    if (w != 0.0) x.noalias() += eig.vectors.col(k) * (w * eig.vectors.col(k).dot(b));
  }
  return x;
}

// Column scales by kind (solve_variable_damping) of the n columns listed: column i's is
// (max K_jj over the listed columns j of its kind)^-1/2, 1 where that is 0.
ConstraintVector kind_scales(const Data& data, const int* columns, int n) {
  double largest[2] = {0, 0};  // per kind: 0 force, 1 pure moment
  for (int i = 0; i < n; ++i) {
    const int c = columns[i], kind = !data.workspace.has_force[c];
    largest[kind] = std::max(largest[kind], data.K(c, c));
  }
  ConstraintVector scale(n);
  for (int i = 0; i < n; ++i) {
    const double l = largest[!data.workspace.has_force[columns[i]]];
    scale[i] = l > 0 ? 1 / std::sqrt(l) : 1.0;
  }
  return scale;
}

// K_HH, the coupling of the columns h[0..nh) among themselves.
CouplingMatrix principal_block(const CouplingMatrix& K, const int* h, int nh) {
  CouplingMatrix Khh(nh, nh);
  for (int i = 0; i < nh; ++i)
    for (int j = 0; j < nh; ++j) Khh(i, j) = K(h[i], h[j]);
  return Khh;
}

// The smallest eigenvalue of K_HH, H the columns that do not give way (at least one), and
// in `lowest` the column of its eigen-direction's largest component.
double smallest_held_eigenvalue(const CouplingMatrix& K, const bool* gives_way, int& lowest) {
  int h[kMaxConstraintColumns], nh = 0;
  for (int i = 0; i < K.rows(); ++i)
    if (!gives_way[i]) h[nh++] = i;
  const SymmetricEigen eig(principal_block(K, h, nh), true);
  Eigen::Index k = 0;
  eig.vectors.col(0).cwiseAbs().maxCoeff(&k);
  lowest = h[k];
  return eig.values[0];
}

// The columns that give way (solve_held_first), as few as leave the held ones H clear of
// the singular region: first, for each damped eigen-direction, its largest component
// among the columns not yet giving way (a yielding column, one that asks for motion,
// where its component is at least kPushShare of that: a push into the boundary gives
// way before the holds beside it); then, while K_HH still has an eigenvalue within
// 4 eps, the largest component of K_HH's lowest eigen-direction. Below 2 eps the held
// ones' exact solve would blend into the plain damping, and every column would carry
// part of the lost motion without an event; choosing at twice that leaves room for the
// later stages of a step, which keep the columns its first solve chose. A lost
// combination spread over several columns (the LWR holding 6D on a driven base) so
// gives way in the columns that span it, and the others stay exact. Returns K_HH's
// smallest eigenvalue (every column giving way but one at most).
double choose_giving_columns(const Data& data, double eps, bool* gives_way) {
  const int nc = static_cast<int>(data.K.rows());
  int nl = 0;
  const auto largest = [&](Eigen::Index j, std::uint64_t among) {
    int column = -1;
    for (int i = 0; i < nc; ++i)
      if (!gives_way[i] && (among >> i & 1u) &&
          (column < 0 || std::abs(data.damped(i, j)) > std::abs(data.damped(column, j))))
        column = i;
    return column;
  };
  for (Eigen::Index j = 0; j < data.damped.cols() && nl < nc - 1; ++j) {
    int column = largest(j, ~std::uint64_t{0});
    const int yielding = largest(j, data.workspace.yielding);
    if (yielding >= 0 && std::abs(data.damped(yielding, j)) >= kPushShare * std::abs(data.damped(column, j)))
      column = yielding;
    gives_way[column] = true;
    ++nl;
  }
  int lowest = 0;
  double khh_min = smallest_held_eigenvalue(data.K, gives_way, lowest);
  while (nl < nc - 1 && !(khh_min > 4 * eps)) {
    gives_way[lowest] = true;
    ++nl;
    khh_min = smallest_held_eigenvalue(data.K, gives_way, lowest);
  }
  return khh_min;
}

// After solve_by_eigen_decomposition has damped some eigen-directions of K (data.K,
// data.workspace.rhs: the scaled K' and rhs): the columns L of choose_giving_columns (or
// Options::gives_way) give way, and the others H are solved exactly, so that a lost
// direction does not take the accuracy of the held ones with it. With K in blocks,
// nu_H = K_HH^-1 (rhs_H - K_HL nu_L), and nu_L solves the Schur complement
// S = K_LL - K_LH K_HH^-1 K_HL (the coupling of L once H is enforced) with the same
// variable damping: within L only the lost combination is damped. Where K_HH itself nears
// the singular region (with the columns given, which a simulator fixes for a step), its
// smallest eigenvalue k from 2 eps down to eps, the solve moves to the plain variable
// damping (data.nu on entry) by nu = nu_vd + s (nu_hf - nu_vd), s = x^2 (3 - 2x),
// x = k / eps - 1, so that the right-hand side of a simulation stays continuous there.
// False (data.nu left as the plain variable damping) when every column gives way or
// k <= eps.
bool solve_held_first(Data& data, const Options& options, double sigma_max) {
  const int nc = static_cast<int>(data.K.rows());
  const CouplingMatrix& K = data.K;
  const double eps = options.singular_region * sigma_max;
  bool gives_way[kMaxConstraintColumns] = {false};
  double khh_min = 0;  // K_HH's smallest eigenvalue, as choose_giving_columns found it
  if (options.gives_way) {
    for (int i = 0; i < nc; ++i) gives_way[i] = options.gives_way >> i & 1u;
  } else {
    khh_min = choose_giving_columns(data, eps, gives_way);
  }
  int h[kMaxConstraintColumns], l[kMaxConstraintColumns], nh = 0, nl = 0;
  for (int i = 0; i < nc; ++i) (gives_way[i] ? l[nl++] : h[nh++]) = i;
  if (nl == 0 || nh == 0) return false;
  for (int i = 0; i < nc; ++i) data.workspace.gave_way |= static_cast<std::uint64_t>(gives_way[i]) << i;
  const ConstraintVector& rhs = data.workspace.rhs;
  const CouplingMatrix Khh = principal_block(K, h, nh);
  if (options.gives_way) khh_min = SymmetricEigen(Khh, false).values[0];
  CouplingMatrix Khl(nh, nl), S(nl, nl);
  ConstraintVector rh(nh), b(nl);
  for (int i = 0; i < nh; ++i) {
    rh[i] = rhs[h[i]];
    for (int j = 0; j < nl; ++j) Khl(i, j) = K(h[i], l[j]);
  }
  // H must itself be clear of the singular region, or its exact solve is unbounded.
  if (!(khh_min > eps)) return false;
  const double x = std::min(khh_min / eps - 1, 1.0), blend = x * x * (3 - 2 * x);
  const Eigen::LLT<CouplingMatrix> llt(Khh);
  if (llt.info() != Eigen::Success) return false;
  const CouplingMatrix X = llt.solve(Khl);  // K_HH^-1 K_HL
  const ConstraintVector y = llt.solve(rh);  // K_HH^-1 rhs_H
  for (int i = 0; i < nl; ++i) {
    b[i] = rhs[l[i]] - Khl.col(i).dot(y);
    for (int j = 0; j < nl; ++j) S(i, j) = K(l[i], l[j]) - Khl.col(i).dot(X.col(j));
  }
  S = (S + S.transpose()) / 2;  // symmetric to round-off
  const ConstraintVector nu_l = variably_damped_solve(S, b, options, sigma_max);
  const ConstraintVector nu_h = y - X * nu_l;
  const auto mix = [blend](double vd, double hf) { return blend == 1 ? hf : vd + blend * (hf - vd); };
  for (int i = 0; i < nh; ++i) data.nu[h[i]] = mix(data.nu[h[i]], nu_h[i]);
  for (int i = 0; i < nl; ++i) data.nu[l[i]] = mix(data.nu[l[i]], nu_l[i]);
  return true;
}

void solve_variable_damping(Data& data, const Options& options) {
  const int nc = static_cast<int>(data.K.rows());
  const CouplingMatrix K = data.K;
  const ConstraintVector rhs = data.workspace.rhs;
  int all[kMaxConstraintColumns];
  for (int i = 0; i < nc; ++i) all[i] = i;
  const ConstraintVector scale = kind_scales(data, all, nc);
  for (int i = 0; i < nc; ++i) {
    for (int j = 0; j < nc; ++j) data.K(i, j) = K(i, j) * scale[i] * scale[j];
    data.workspace.rhs[i] = rhs[i] * scale[i];
  }
  if (!solve_by_ldlt(data, options)) {
    const double sigma_max = solve_by_eigen_decomposition(data, options);
    if (data.damped.cols()) solve_held_first(data, options, sigma_max);
  }
  for (int i = 0; i < nc; ++i) data.nu[i] *= scale[i];
  for (int i = 0; i < data.workspace.exact_nu.size(); ++i) data.workspace.exact_nu[i] *= scale[i];
  data.K = K;  // sigma_min() and the caller read K as it was
  data.workspace.rhs = rhs;
}

}  // namespace

void solve_coupling(Data& data, const Options& options) {
  data.workspace.exact_nu.resize(0);
  data.workspace.gave_way = 0;
  if (options.policy == SingularityPolicy::VariableDamping) return solve_variable_damping(data, options);
  if (options.policy == SingularityPolicy::Truncate && solve_by_ldlt(data, options)) return;
  solve_by_eigen_decomposition(data, options);
}

void solve_coupling_without(const Data& data, const Options& options, const bool* given_up, ConstraintVector& nu) {
  const int nc = static_cast<int>(data.K.rows());
  int h[kMaxConstraintColumns], nh = 0;
  for (int i = 0; i < nc; ++i)
    if (!given_up[i]) h[nh++] = i;
  nu.setZero(nc);
  if (nh == 0) return;
  // K_HH and rhs_H scaled by kind, as solve_variable_damping scales K
  const ConstraintVector scale = kind_scales(data, h, nh);
  ConstraintVector rhs(nh);
  CouplingMatrix K(nh, nh);
  for (int i = 0; i < nh; ++i) {
    rhs[i] = data.workspace.rhs[h[i]] * scale[i];
    for (int j = 0; j < nh; ++j) K(i, j) = data.K(h[i], h[j]) * scale[i] * scale[j];
  }
  const ConstraintVector nu_h = variably_damped_solve(K, rhs, options, -1);
  for (int i = 0; i < nh; ++i) nu[h[i]] = nu_h[i] * scale[i];
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
