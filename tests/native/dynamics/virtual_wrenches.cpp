// Virtual wrenches (Case::f_virtual): on the random trees of the tree suites,
// virtual_torques = J^T f_virtual against each link's Jacobian computed on its own
// (link_jacobian), and a solve with f_virtual is the solve with those torques added to
// ff_torques.
#include <gtest/gtest.h>

#include "random_tree.hpp"
#include "tree_cases.hpp"

namespace achd::test {
namespace {

std::vector<Vector6> random_wrenches(std::mt19937& rng, const Model& m) {
  std::vector<Vector6> f(m.num_links());
  for (Vector6& w : f) w = Vector6::NullaryExpr([&] { return uniform(rng, -5, 5); });
  return f;
}

TEST(VirtualWrenches, VirtualTorquesAreTheJacobiansTransposedTimesTheWrenches) {
  std::mt19937 rng(71);
  double worst = 0;
  const int cases = for_tree_cases(71, [&](const Model& m, const Case& given) {
    Case c = given;
    c.f_virtual = random_wrenches(rng, m);
    Data d(m);
    hybrid_dynamics(m, d, c, all_effects());
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(m.num_rates());
    for (int l = 0; l < m.num_links(); ++l)
      expected += link_jacobian(m, c.q, l, Vector3::Zero()).transpose() * c.f_virtual[l];
    const double error = rel_error(d.virtual_torques, expected);
    worst = std::max(worst, error);
    EXPECT_LE(error, 1e-12);
  });
  std::printf("  %d cases: max relative error of J^T f_virtual %.3g\n", cases, worst);
  EXPECT_GT(cases, 60);
}

TEST(VirtualWrenches, ASolveWithThemIsTheSolveWithTheirTorquesAsFeedForward) {
  std::mt19937 rng(72);
  double worst = 0;
  for_tree_cases(72, [&](const Model& m, const Case& given) {
    Case c = given;
    c.f_virtual = random_wrenches(rng, m);
    Data d(m), e(m);
    hybrid_dynamics(m, d, c, all_effects());
    Case plain = given;
    plain.ff_torques = given.ff_torques + d.virtual_torques;
    hybrid_dynamics(m, e, plain, all_effects());
    const double error = std::max({rel_error(d.qdd, e.qdd), rel_error(d.nu, e.nu),
                                   rel_error(d.joint_torques, e.joint_torques),
                                   rel_error(d.prescribed_torques, e.prescribed_torques)});
    worst = std::max(worst, error);
    EXPECT_LE(error, 1e-12);
  });
  std::printf("  max relative difference from the feed-forward solve %.3g\n", worst);
}

// The reference solver (pv_reference.hpp) does not implement virtual wrenches or driver
// weights below 1: it names them instead of solving a different problem.
TEST(VirtualWrenches, TheReferenceRefusesWhatItDoesNotSolve) {
  std::mt19937 rng(73);
  int checked = 0;
  for_tree_cases(73, [&](const Model& m, const Case& given) {
    if (checked++ >= 5) return;
    EXPECT_NO_THROW(pv_reference(m, given, {}));
    Case c = given;
    c.f_virtual = random_wrenches(rng, m);
    try {
      pv_reference(m, c, {});
      ADD_FAILURE() << "pv_reference solved a case with virtual wrenches";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("f_virtual"), std::string::npos) << e.what();
    }
    Case w = given;
    w.constraints.assign(1, ConstraintBlock{});
    w.constraints.back().link = m.num_links() - 1;
    w.constraints.back().alpha = ConstraintMatrix::Zero(6, 1);
    w.constraints.back().alpha(2, 0) = 1;
    w.constraints.back().beta = ConstraintVector::Zero(1);
    w.constraints.back().w_fext = ConstraintVector::Constant(1, 0.5);
    try {
      pv_reference(m, w, {});
      ADD_FAILURE() << "pv_reference solved a case with a driver weight of 0.5";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("w_fext"), std::string::npos) << e.what();
    }
  });
  EXPECT_GE(checked, 5);
}

}  // namespace
}  // namespace achd::test
