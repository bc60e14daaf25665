// Driver priorities (Case::w_fext, w_ff and the blocks' own; driver_priorities.cpp): on
// the random trees of the tree suites, every column k satisfies
//   alpha_k^T a_k = beta_k + (1 - w_fext,k) (A M^-1 J^T f_ext)_k + (1 - w_ff,k) (A M^-1 ff)_k
// against a dense computation of A (alpha^T J at each point), M (CRBA) and J^T f_ext (link
// Jacobians), while weights of 1 give the solve without weights bit for bit.
#include <gtest/gtest.h>

#include <cstring>

#include "random_tree.hpp"
#include "tree_cases.hpp"

namespace achd::test {
namespace {

// The columns' own accelerations alpha_k^T a at their points (physical convention).
Eigen::VectorXd column_accelerations(const Model& m, const Data& d, const Case& c) {
  const std::vector<Transform> X = forward_kinematics(m, c.q);
  Eigen::VectorXd out(c.num_constraints());
  int row = 0;
  auto add = [&](int link, const Vector3& point, const ConstraintMatrix& alpha) {
    const Vector6 a = motion_shift(d.link_accelerations[link + 1], X[link].R * point);
    for (Eigen::Index k = 0; k < alpha.cols(); ++k) out[row++] = alpha.col(k).dot(a);
  };
  if (c.alpha.cols()) add(m.num_links() - 1, Vector3::Zero(), c.alpha);
  for (const ConstraintBlock& b : c.constraints) add(b.link, b.point, b.alpha);
  return out;
}

// Every column's weights, tip first, as one vector each (1 where none are given).
void stacked_weights(const Case& c, Eigen::VectorXd& wf, Eigen::VectorXd& wff) {
  wf.resize(c.num_constraints());
  wff.resize(c.num_constraints());
  int row = 0;
  auto add = [&](const ConstraintVector& f, const ConstraintVector& ff, Eigen::Index columns) {
    for (Eigen::Index k = 0; k < columns; ++k, ++row) {
      wf[row] = f.size() ? f[k] : 1.0;
      wff[row] = ff.size() ? ff[k] : 1.0;
    }
  };
  add(c.w_fext, c.w_ff, c.alpha.cols());
  for (const ConstraintBlock& b : c.constraints) add(b.w_fext, b.w_ff, b.alpha.cols());
}

// Random weights on every column: a third 0, a third 1, a third in between.
void random_weights(std::mt19937& rng, Case& c) {
  auto draw = [&](Eigen::Index columns) {
    ConstraintVector w(columns);
    for (Eigen::Index k = 0; k < columns; ++k) {
      const int kind = static_cast<int>(rng() % 3);
      w[k] = kind == 0 ? 0.0 : kind == 1 ? 1.0 : uniform(rng, 0, 1);
    }
    return w;
  };
  if (c.alpha.cols()) c.w_fext = draw(c.alpha.cols()), c.w_ff = draw(c.alpha.cols());
  for (ConstraintBlock& b : c.constraints) b.w_fext = draw(b.alpha.cols()), b.w_ff = draw(b.alpha.cols());
}

TEST(DriverPriorities, WeightsOfOneAreTheSolveWithoutWeightsBitForBit) {
  const int cases = for_tree_cases(61, [](const Model& m, const Case& c) {
    Case ones = c;
    const auto one = [](Eigen::Index n) { return ConstraintVector::Ones(n); };
    ones.w_fext = one(c.alpha.cols()), ones.w_ff = one(c.alpha.cols());
    for (ConstraintBlock& b : ones.constraints) b.w_fext = one(b.alpha.cols()), b.w_ff = one(b.alpha.cols());
    Data a(m), b(m);
    hybrid_dynamics(m, a, c, all_effects());
    hybrid_dynamics(m, b, ones, all_effects());
    ASSERT_EQ(std::memcmp(a.qdd.data(), b.qdd.data(), sizeof(double) * a.qdd.size()), 0);
    ASSERT_EQ(a.nu.size(), b.nu.size());
    ASSERT_EQ(std::memcmp(a.nu.data(), b.nu.data(), sizeof(double) * a.nu.size()), 0);
  });
  EXPECT_GT(cases, 60);
}

TEST(DriverPriorities, EachDriverPassesThroughInProportionOneMinusItsWeight) {
  std::mt19937 rng(62);
  double worst = 0;
  int checked = 0;
  for_tree_cases(62, [&](const Model& m, const Case& given) {
    if (given.num_constraints() == 0 || given.any_prescribed()) return;
    Case c = given;
    random_weights(rng, c);
    const Options o = all_effects();
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    ASSERT_EQ(d.rank, c.num_constraints());
    // Dense: A = alpha^T J at each point, M with rotor inertia, J^T f_ext over the links.
    const Eigen::MatrixXd A = stacked_constraint_jacobian(m, c);
    const Eigen::MatrixXd M = crba(m, c.q);
    Eigen::VectorXd JTf = Eigen::VectorXd::Zero(m.num_rates());
    for (int l = 0; l < m.num_links(); ++l)
      JTf += link_jacobian(m, c.q, l, Vector3::Zero()).transpose() * c.f_ext[l];
    const Eigen::LDLT<Eigen::MatrixXd> Minv(M);
    const Eigen::VectorXd yf = A * Minv.solve(JTf), yff = A * Minv.solve(c.ff_torques);
    Eigen::VectorXd wf, wff, beta(c.num_constraints());
    stacked_weights(c, wf, wff);
    int row = 0;
    for (Eigen::Index k = 0; k < c.alpha.cols(); ++k) beta[row++] = c.beta[k];
    for (const ConstraintBlock& b : c.constraints)
      for (Eigen::Index k = 0; k < b.alpha.cols(); ++k) beta[row++] = b.beta[k];
    const Eigen::VectorXd expected =
        beta + (Eigen::VectorXd::Ones(wf.size()) - wf).cwiseProduct(yf) +
        (Eigen::VectorXd::Ones(wff.size()) - wff).cwiseProduct(yff);
    const Eigen::VectorXd got = column_accelerations(m, d, c);
    const double scale = std::max({1.0, expected.cwiseAbs().maxCoeff(), yf.cwiseAbs().maxCoeff(),
                                   yff.cwiseAbs().maxCoeff()});
    const double error = (got - expected).cwiseAbs().maxCoeff() / scale;
    worst = std::max(worst, error);
    EXPECT_LE(error, 1e-8) << "weights f " << wf.transpose() << "\nweights ff " << wff.transpose();
    ++checked;
  });
  std::printf("  %d cases: max relative error of the identity %.3g\n", checked, worst);
  EXPECT_GE(checked, 25);
}

}  // namespace
}  // namespace achd::test
