// The variable_damping policy on its own (solver level): bounded where truncate's
// constraint forces grow without bound, and the exact solve where nothing is near
// singular.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "achd/achd.hpp"

#include "hard_stretched_arm.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

Options policy(SingularityPolicy p) {
  Options o;
  o.policy = p;
  return o;
}

double largest_eigenvalue(const CouplingMatrix& K) {
  return Eigen::SelfAdjointEigenSolver<CouplingMatrix>(K, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
}

// The stretched arm (hard_stretched_arm.hpp) pushed radially (x) while z is held: both
// columns are positions, so K is scaled by one number and the gain of every direction is
// at most 1 / eps = 1 / (singular_region sigma_max): |nu| <= |rhs| / (singular_region
// sigma_max) at every theta, while truncate's nu grows like 1/theta^2 until its
// tolerance (1e-12 sigma_max) drops the direction near theta = 1e-6.
TEST(VariableDamping, ConstraintForcesStayBoundedWhereTruncatesGrow) {
  const Model model = stretched_arm();
  const Options vd = policy(SingularityPolicy::VariableDamping), tr = policy(SingularityPolicy::Truncate);
  for (double theta : sweep_angles()) {
    const Case c = stretched_arm_case(model, theta);
    Data d(model);
    hybrid_dynamics(model, d, c, vd);
    ASSERT_TRUE(d.nu.allFinite() && d.qdd.allFinite()) << theta;
    const double bound = d.workspace.rhs.norm() / (vd.singular_region * largest_eigenvalue(d.K));
    EXPECT_LE(d.nu.norm(), bound * (1 + 1e-12)) << "theta " << theta;
    if (theta <= 1e-3) {
      EXPECT_GE(d.damped.cols(), 1) << theta;  // the radial direction is in the region
      Data t(model);
      hybrid_dynamics(model, t, c, tr);
      if (theta == 1e-4) EXPECT_GT(t.nu.norm(), 100 * bound) << "truncate's nu at theta 1e-4";
    }
  }
}

// Away from the region variable_damping is truncate's exact solve: every robot of
// robots/index.json at its q0 holding z and rx, and x y z, with nonzero velocities
// (where the robot can move in every held direction: not the planar arm): nu and qdd
// agree to 1e-15 (relative), and no direction is reported damped.
TEST(VariableDamping, EqualsTruncateAwayFromTheRegion) {
  for (const IndexedRobot& r : load_robot_index(ACHD_SOURCE_DIR)) {
    const Model& m = r.model;
    for (const std::vector<int>& held : {std::vector<int>{2, 3}, std::vector<int>{0, 1, 2}}) {
      Case c = Case::zeros(m);
      c.q = r.q0;
      c.qd = Eigen::VectorXd::Constant(m.num_rates(), 0.3);
      c.alpha.setZero(6, static_cast<int>(held.size()));
      c.beta.resize(static_cast<int>(held.size()));
      for (std::size_t j = 0; j < held.size(); ++j) {
        c.alpha(held[j], static_cast<int>(j)) = 1;
        c.beta[static_cast<int>(j)] = 0.1 * (j + 1);
      }
      Data a(m), b(m);
      hybrid_dynamics(m, a, c, policy(SingularityPolicy::Truncate));
      hybrid_dynamics(m, b, c, policy(SingularityPolicy::VariableDamping));
      if (a.rank < static_cast<int>(held.size())) continue;  // a held direction the robot cannot move in
      EXPECT_EQ(b.damped.cols(), 0) << r.name;
      EXPECT_LE((a.nu - b.nu).norm(), 1e-15 * a.nu.norm()) << r.name << " nu " << a.nu.transpose() << " / "
                                                            << b.nu.transpose();
      EXPECT_LE((a.qdd - b.qdd).norm(), 1e-15 * a.qdd.norm()) << r.name;
    }
  }
}

}  // namespace
}  // namespace achd::test
