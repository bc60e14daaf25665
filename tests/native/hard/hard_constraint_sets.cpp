// Degenerate constraint sets: duplicated, parallel and zero alpha columns, more
// constraints than joints. Each gets a defined result: rank and dropped report the
// redundancy, the consistent constraints hold, the identities hold. (Seven or more
// constraints cannot be stored in a Case; the parsers refuse them: bad_input_case.cpp.)
#include <gtest/gtest.h>

#include <limits>

#include "achd/achd.hpp"
#include "hard_chain_urdf.hpp"
#include "reference_dynamics.hpp"

namespace achd::test {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A spatial 3R arm (axes z, y, y), tip 0.4 m beyond the last joint.
Model arm3() {
  std::vector<LinkSpec> l(4);
  l[0].axis = {0, 0, 1};
  l[1].axis = {0, 1, 0};
  l[1].joint_xyz = {0, 0, 0.3};
  l[2].axis = {0, 1, 0};
  l[2].joint_xyz = {0.5, 0, 0};
  for (int i = 0; i < 3; ++i) l[i].com = {0.2, 0, 0};
  l[3].joint_type = "fixed";
  l[3].joint_xyz = {0.4, 0, 0};
  l[3].has_inertial = false;
  l[3].name = "tip";
  return load_urdf_string(chain_urdf(l), "link0", "tip");
}

Case base_case(const Model& m) {
  Case c = Case::zeros(m);
  c.q << 0.3, -0.4, 0.9;
  c.qd.setConstant(3, 0.7);
  return c;
}

void set_alpha(Case& c, const std::vector<Vector6>& cols, const std::vector<double>& beta) {
  c.alpha.resize(6, static_cast<Eigen::Index>(cols.size()));
  c.beta.resize(static_cast<Eigen::Index>(beta.size()));
  for (size_t k = 0; k < cols.size(); ++k) c.alpha.col(k) = cols[k];
  for (size_t k = 0; k < beta.size(); ++k) c.beta[k] = beta[k];
}

Vector6 unit(int r, double s = 1) {
  Vector6 v = Vector6::Zero();
  v[r] = s;
  return v;
}

struct Result {
  Data data;
  Eigen::VectorXd residual;  // alpha^T a_tip - beta
  double rnea_error = 0;     // max |RNEA(q, qd, qdd) - joint_torques| / max(1, |tau|)
};

Result solve(const Model& m, const Case& c, const Options& o = {}) {
  Result r{Data(m), {}, 0};
  hybrid_dynamics(m, r.data, c, o);
  r.residual = c.alpha.transpose() * r.data.link_accelerations.back() - c.beta;
  const Eigen::VectorXd tau = reference_rnea(m, c.q, c.qd, r.data.qdd, c.gravity);
  r.rnea_error = (tau - r.data.joint_torques).cwiseAbs().maxCoeff() /
                 std::max(1.0, r.data.joint_torques.cwiseAbs().maxCoeff());
  return r;
}

// The bound for the constraint residuals and identities on this well-conditioned arm
// (cond(K) < 1e3 for the independent constraints): 1e2 eps per unit of |rhs| <= 30 m/s^2
// (gravity, velocity products at 0.7 rad/s, beta), times cond.
constexpr double kResidualBound = 1e2 * kEps * 1e3 * 30;

// alpha = [x, x]: the same constraint twice with the same beta is consistent; K has
// rank 1, the dropped direction is (1, -1)/sqrt2 and the result equals the solve with
// the constraint once.
TEST(HardConstraintSets, DuplicatedColumnIsDroppedOnceAndTheResultMatchesTheSingleColumn) {
  const Model m = arm3();
  Case once = base_case(m), twice = base_case(m);
  set_alpha(once, {unit(0)}, {0.5});
  set_alpha(twice, {unit(0), unit(0)}, {0.5, 0.5});
  const Result a = solve(m, once), b = solve(m, twice);
  EXPECT_EQ(b.data.rank, 1);
  ASSERT_EQ(b.data.dropped.cols(), 1);
  EXPECT_NEAR(std::abs(b.data.dropped(0, 0) - b.data.dropped(1, 0)), std::sqrt(2.0), 1e-12);
  // The pseudo-inverse splits the force evenly: nu_1 = nu_2 = nu_once / 2.
  EXPECT_NEAR(b.data.nu[0], a.data.nu[0] / 2, 1e-12 * std::abs(a.data.nu[0]));
  EXPECT_NEAR(b.data.nu[1], a.data.nu[0] / 2, 1e-12 * std::abs(a.data.nu[0]));
  EXPECT_LE((b.data.qdd - a.data.qdd).cwiseAbs().maxCoeff(), kResidualBound);
  EXPECT_LE(b.residual.cwiseAbs().maxCoeff(), kResidualBound);
  EXPECT_LE(b.rnea_error, 1e2 * kEps);
}

// alpha = [x, -2x] with beta = (b, -2b): parallel and consistent; same motion as x alone.
// With an inconsistent beta (b, 0) the least-squares compromise holds neither exactly
// but stays finite and reports the rank.
TEST(HardConstraintSets, ParallelColumnsGiveTheSingleColumnMotionOrAFiniteCompromise) {
  const Model m = arm3();
  Case once = base_case(m), par = base_case(m), bad = base_case(m);
  set_alpha(once, {unit(2)}, {-1.0});
  set_alpha(par, {unit(2), unit(2, -2)}, {-1.0, 2.0});
  set_alpha(bad, {unit(2), unit(2, -2)}, {-1.0, 0.0});
  const Result a = solve(m, once), b = solve(m, par), c = solve(m, bad);
  EXPECT_EQ(b.data.rank, 1);
  EXPECT_LE((b.data.qdd - a.data.qdd).cwiseAbs().maxCoeff(), kResidualBound);
  EXPECT_LE(b.residual.cwiseAbs().maxCoeff(), kResidualBound);
  EXPECT_EQ(c.data.rank, 1);
  EXPECT_TRUE(c.data.qdd.allFinite() && c.data.nu.allFinite());
  EXPECT_LE(c.rnea_error, 1e2 * kEps);
  // Least squares over the columns at unit length (the solve scales each column by a
  // power of two to a length in [2^-1/2, 2^1/2): here 1 and 1/2), so that a column's
  // scale does not weigh it: the scaled residuals (r_1, r_2 / 2) are orthogonal to the
  // kept direction (1, -1)/sqrt2, i.e. 2 r_1 - r_2 = 0; the tip's z acceleration is
  // -0.5, halfway between the -1 and 0 the two columns ask for.
  EXPECT_LE(std::abs(2 * c.residual[0] - c.residual[1]), kResidualBound);
  EXPECT_NEAR(c.residual[0], 0.5, kResidualBound);  // alpha_1^T a = -0.5 = beta_1 + 0.5
}

// A zero column constrains nothing: rank drops by one, the direction is reported, its
// nu is zero, and the other constraints hold as if it were absent.
TEST(HardConstraintSets, ZeroColumnIsReportedAndIgnored) {
  const Model m = arm3();
  Case without = base_case(m), with = base_case(m);
  set_alpha(without, {unit(0), unit(2)}, {0.3, -0.2});
  set_alpha(with, {unit(0), Vector6::Zero(), unit(2)}, {0.3, 0.0, -0.2});
  for (const SingularityPolicy p : {SingularityPolicy::Truncate, SingularityPolicy::Damped}) {
    Options o;
    o.policy = p;
    const Result a = solve(m, without, o), b = solve(m, with, o);
    EXPECT_EQ(b.data.rank, 2);
    ASSERT_EQ(b.data.dropped.cols(), 1);
    EXPECT_NEAR(std::abs(b.data.dropped(1, 0)), 1.0, 1e-12);
    EXPECT_EQ(b.data.nu[1], 0.0);
    // Damping perturbs the kept directions by (lambda / sigma)^2 ~ 1e-12 relative.
    const double tol = p == SingularityPolicy::Damped ? 1e-9 : kResidualBound;
    EXPECT_LE((b.data.qdd - a.data.qdd).cwiseAbs().maxCoeff(), tol);
    EXPECT_LE(std::abs(b.residual[0]) + std::abs(b.residual[2]), tol);
  }
}

// Six constraints on a three-joint arm: K = A^T J M^-1 J^T A has rank 3 (the tip has
// three degrees of freedom). Three directions are dropped; with a beta that the arm can
// meet (the accelerations of a consistent motion), every constraint holds.
TEST(HardConstraintSets, MoreConstraintsThanJointsKeepsRankNjAndHoldsConsistentBeta) {
  const Model m = arm3();
  Case free = base_case(m);
  Data d(m);
  hybrid_dynamics(m, d, free);  // a motion the arm can do: the free one
  Case c = base_case(m);
  std::vector<Vector6> cols;
  std::vector<double> beta;
  for (int r = 0; r < 6; ++r) {
    cols.push_back(unit(r));
    beta.push_back(d.link_accelerations.back()[r]);
  }
  set_alpha(c, cols, beta);
  const Result r = solve(m, c);
  EXPECT_EQ(r.data.rank, 3);
  EXPECT_EQ(r.data.dropped.cols(), 3);
  // The constraints ask for the free motion: no force is needed and qdd is unchanged.
  EXPECT_LE(r.data.nu.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((r.data.qdd - d.qdd).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE(r.residual.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE(r.rnea_error, 1e2 * kEps);
}

}  // namespace
}  // namespace achd::test
