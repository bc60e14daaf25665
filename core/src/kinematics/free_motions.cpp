// A joint moves nothing when D_i = S_i^T IA_i S_i = 0. 2 D_i is the least kinetic
// energy of the bodies after joint i when it turns (or slides) at unit rate and the
// later joints move as they like, so D_i = 0 exactly when some rates of the later joints
// leave every body moving in a way its inertia does not resist. Those motions of body i
// ("free motions", F_i, a subspace of its spatial velocities) follow from the leaves:
//   F_leaf = N_leaf,   F_i = N_i ∩ (∩ over the children c of i of X_c^-1 (F_c + span S_c)),
//   joint i moves nothing  <=>  S_i ∈ F_i,
// N_i being the null space of body i's spatial inertia: every motion for a massless body,
// the rotations about its centre of mass for a point mass, the spin about its axis for a
// rod, none for a body with mass and a positive definite rotational inertia (almost every
// real link), where F_i = {0} and the tree before it depends on nothing after it.
//
// Why not the size of D: an exact zero comes out of the sweeps as round-off, so "D = 0"
// needs a bound on D's round-off. The bound n eps M_ii used before (M_ii, the composite
// inertia, grows like n^3 on a long chain while D does not) refused valid robots: 10000
// links of 1 kg, 5 cm apart. Here nothing depends on the chain's length or on the ratio of
// its masses. Motions are compared in coordinates [v / L; w] (L, the model's largest
// length), where the vectors that span the subspaces have length 1, and each decision
// compares a quantity with kMargin times its tracked round-off bound: for a body's null
// space, a few tens of eps of that body's own inertia; for the subspaces, a few tens of
// eps per joint transform (times 1 + |p| / L) since the last body with no free motion,
// where F restarts exactly from {0}.
#include "free_motions.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "achd/kinematics.hpp"
#include "joint.hpp"

namespace achd {
namespace {

// The round-off of one step (a 3x3 eigen decomposition, a transform, an orthonormal
// basis), relative to the size of its inputs, and the margin kept above it.
constexpr double kStepRoundOff = 64 * std::numeric_limits<double>::epsilon();
constexpr double kMargin = 100;

// Orthonormal columns spanning a subspace of scaled motions [v / L; w] (at most 6).
using Basis = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, 6>;

// Appends to B the part of v orthogonal to it, unless that part is at most `zero` |v|.
// (Gram-Schmidt twice: once leaves round-off of the size of v along B.)
void add_direction(Basis& B, Vector6 v, double zero) {
  const double length = v.norm();
  for (int pass = 0; pass < 2; ++pass) v -= B * (B.transpose() * v);
  const double rest = v.norm();
  if (!(rest > zero * length)) return;
  B.conservativeResize(Eigen::NoChange, B.cols() + 1);
  B.col(B.cols() - 1) = v / rest;
}

// The eigenvectors of a symmetric positive semi-definite 3x3 whose eigenvalues are
// round-off of zero for a matrix computed from numbers of size `scale`.
std::vector<Vector3> null_directions(const Matrix3& M, double scale) {
  if (scale == 0) return {Vector3::UnitX(), Vector3::UnitY(), Vector3::UnitZ()};
  const Eigen::SelfAdjointEigenSolver<Matrix3> eig(M);
  std::vector<Vector3> out;
  for (int k = 0; k < 3; ++k)
    if (eig.eigenvalues()[k] <= kMargin * kStepRoundOff * scale) out.push_back(eig.eigenvectors().col(k));
  return out;
}

// The centre of mass of a spatial inertia [m 1, -m [c]x; m [c]x, Io] with m > 0.
Vector3 centre_of_mass(const Matrix6& I, double m) {
  const Matrix3 mc = I.bottomLeftCorner<3, 3>();
  return Vector3(mc(2, 1) - mc(1, 2), mc(0, 2) - mc(2, 0), mc(1, 0) - mc(0, 1)) / (2 * m);
}

double mass(const Matrix6& I) { return I.topLeftCorner<3, 3>().trace() / 3; }

// N: the motions the inertia I does not resist. Massless: every translation, and the
// rotations its rotational inertia does not resist. Otherwise the rotations about the
// centre of mass c (velocity of the origin c x w) about axes w of zero inertia there;
// Ic = Io + m [c]x [c]x is computed from numbers of size |Io| + m |c|^2.
Basis null_space(const Matrix6& I, double L) {
  const double m = mass(I);
  const Matrix3 Io = I.bottomRightCorner<3, 3>();
  Basis N(6, 0);
  const double zero = kMargin * kStepRoundOff;
  if (!(m > 0)) {
    for (int k = 0; k < 3; ++k) add_direction(N, Vector6::Unit(k), zero);
    for (const Vector3& w : null_directions(Io, Io.cwiseAbs().maxCoeff()))
      add_direction(N, (Vector6() << Vector3::Zero(), w).finished(), zero);
    return N;
  }
  const Vector3 c = centre_of_mass(I, m);
  const Matrix3 Ic = Io + m * skew(c) * skew(c);
  for (const Vector3& w : null_directions(Ic, Io.cwiseAbs().maxCoeff() + m * c.squaredNorm()))
    add_direction(N, (Vector6() << c.cross(w) / L, w).finished(), zero);
  return N;
}

// A ∩ B for orthonormal bases: the combinations A x whose part outside B, |(1 - B B^T) A x|,
// is at most `zero` (the right singular vectors of (1 - B B^T) A with such singular values).
Basis intersect(const Basis& A, const Basis& B, double zero) {
  Basis out(6, 0);
  if (A.cols() == 0 || B.cols() == 0) return out;
  const Basis outside = A - B * (B.transpose() * A);
  const Eigen::JacobiSVD<Basis> svd(outside, Eigen::ComputeFullV);
  for (int j = 0; j < A.cols(); ++j)
    if (svd.singularValues()[j] <= zero) add_direction(out, A * svd.matrixV().col(j), zero);
  return out;
}

// The direction of joint b's motion subspace S in scaled coordinates.
Vector6 joint_direction(const Body& b) { return subspace_times(b, 1.0); }

}  // namespace

int joint_moving_nothing(const Model& model, const Eigen::VectorXd& q) {
  const int n = model.num_rates();
  // The length scale: the largest joint offset or centre of mass.
  std::vector<Transform> X(n);
  double L = 0;
  for (int i = 0; i < n; ++i) {
    X[i] = joint_transform(model.bodies[i], q[i]);
    L = std::max(L, X[i].p.norm());
    const double m = mass(model.bodies[i].inertia);
    if (m > 0) L = std::max(L, centre_of_mass(model.bodies[i].inertia, m).norm());
  }
  if (!(L > 0)) L = 1;
  // Free motions of each body and their round-off bounds, relative; a body's are complete
  // when the loop reaches its parent (children come after their parents).
  std::vector<Basis> F(n, Basis(6, 0));
  std::vector<double> bound(n, 0);
  std::vector<std::vector<int>> children(n);
  for (int i = 0; i < n; ++i)
    if (model.bodies[i].parent >= 0) children[model.bodies[i].parent].push_back(i);
  for (int i = n - 1; i >= 0; --i) {
    const Basis N = null_space(model.bodies[i].inertia, L);
    if (N.cols() == 0) continue;  // no free motion: exact, its parent starts afresh
    // The motions of body i that the joints after it take up: the intersection over its
    // children c of X_c^-1 (F_c + span S_c); a leaf: every motion.
    F[i] = N;
    if (children[i].empty()) {
      bound[i] = kStepRoundOff;
      F[i] = intersect(N, Basis::Identity(6, 6), kMargin * bound[i]);
    }
    for (const int c : children[i]) {
      const Transform Xs{X[c].R, X[c].p / L};
      const double bound_c = bound[c] + kStepRoundOff * (2 + Xs.p.norm());
      bound[i] = std::max(bound[i], bound_c);
      Basis after = F[c];
      add_direction(after, joint_direction(model.bodies[c]), kMargin * bound_c);
      Basis G(6, 0);
      for (int k = 0; k < after.cols(); ++k) add_direction(G, Xs.motion_to_parent(after.col(k)), kMargin * bound_c);
      F[i] = intersect(F[i], G, kMargin * bound_c);
    }
    const Vector6 S = joint_direction(model.bodies[i]);
    if (F[i].cols() > 0 && (S - F[i] * (F[i].transpose() * S)).norm() <= kMargin * bound[i]) return i;
  }
  return -1;
}

std::array<Eigen::VectorXd, 2> check_configurations(const Model& model) {
  const int n = model.num_rates();
  Eigen::VectorXd zero = Eigen::VectorXd::Zero(n), generic(n);
  for (int i = 0; i < n; ++i) {
    const JointLimits& l = model.bodies[i].limits;
    const double lo = std::max(l.lower, -3.0), hi = std::min(l.upper, 3.0);
    generic[i] = lo + (0.3 + 0.37 * ((i * 7) % 5) / 4.0) * (hi - lo);
  }
  return {zero, generic};
}

int joint_moving_nothing_at_checks(const Model& model) {
  for (const Eigen::VectorXd& q : check_configurations(model)) {
    const int i = joint_moving_nothing(model, q);
    if (i >= 0) return i;
  }
  return -1;
}

}  // namespace achd
