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
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(m.num_joints());
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

}  // namespace
}  // namespace achd::test
