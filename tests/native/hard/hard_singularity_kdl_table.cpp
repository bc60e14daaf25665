// docs/guide/hard-cases.md's singularity table: for the stretched-arm sweep (hard_stretched_arm.hpp),
// |nu| and the largest |joint torque| of KDL's Vereshchagin solver (Debian KDL, the
// parity reference) and of achd's two policies, printed as markdown. Run:
//   build-hard/tests/native/hard_singularity_kdl_table --gtest_filter='*PrintsTable*'
// KDL gets the same arm built segment by segment (joint at the segment root, tip at
// the next joint, the last tip at the tool point), so no fixed joint is involved.
#include <gtest/gtest.h>

#include <cstdio>

#include <kdl/chain.hpp>
#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include "hard_stretched_arm.hpp"

namespace achd::test {
namespace {

struct Row {
  double nu = 0, tau = 0;  // |nu|, max |joint torque|
  bool ok = true;          // KDL: CartToJnt returned 0
};

KDL::Chain kdl_stretched_arm() {
  const double length[3] = {1.0, 1.0, 0.5}, mass[3] = {2.0, 1.5, 0.5}, r = 0.03;
  KDL::Chain chain;
  for (int i = 0; i < 3; ++i) {
    const double t = mass[i] * (3 * r * r + length[i] * length[i]) / 12;
    // KDL expresses the inertia in the segment's tip frame: the COM is at -l/2 there.
    const KDL::RigidBodyInertia I(mass[i], KDL::Vector(-length[i] / 2, 0, 0),
                                  KDL::RotationalInertia(mass[i] * r * r / 2, t, t, 0, 0, 0));
    chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::RotY),
                                  KDL::Frame(KDL::Vector(length[i], 0, 0)), I));
  }
  return chain;
}

// KDL's solve in its own convention: root acceleration -g, beta_kdl = beta - alpha_lin^T g.
// Its joint torques -J^T alpha nu use KDL's own tip Jacobian (tip origin, base axes).
Row kdl_row(const Case& c) {
  const KDL::Chain chain = kdl_stretched_arm();
  const int nc = c.num_constraints(), n = 3;
  KDL::ChainHdSolver_Vereshchagin solver(
      chain, KDL::Twist(KDL::Vector(-c.gravity.x(), -c.gravity.y(), -c.gravity.z()), KDL::Vector::Zero()),
      nc);
  KDL::JntArray q(n), qd(n), qdd(n), ff(n), ct(n), beta(nc);
  KDL::Jacobian alpha(nc);
  for (int i = 0; i < n; ++i) q(i) = c.q[i];
  for (int k = 0; k < nc; ++k) {
    for (int r = 0; r < 6; ++r) alpha(r, k) = c.alpha(r, k);
    beta(k) = c.beta[k] - c.alpha.col(k).head<3>().dot(c.gravity);
  }
  KDL::Wrenches f_ext(n, KDL::Wrench::Zero());
  Row row;
  row.ok = solver.CartToJnt(q, qd, qdd, alpha, beta, f_ext, ff, ct) == 0;
  Eigen::VectorXd nu(nc);
  solver.getContraintForceMagnitude(nu);
  KDL::Jacobian J(n);
  KDL::ChainJntToJacSolver(chain).JntToJac(q, J);
  const Eigen::VectorXd tau = -J.data.transpose() * (c.alpha * nu);
  row.nu = nu.norm();
  row.tau = tau.cwiseAbs().maxCoeff();
  return row;
}

Row achd_row(const Model& model, const Case& c, const Options& o) {
  Data d(model);
  hybrid_dynamics(model, d, c, o);
  return {d.nu.norm(), d.joint_torques.cwiseAbs().maxCoeff(), true};
}

Options damped() {
  Options o;
  o.policy = SingularityPolicy::Damped;
  return o;
}

// The hand-built KDL chain is the same robot: away from the singularity KDL and achd
// agree (relative 1e-9: K's condition number is ~1e3 at theta = 0.1, times eps).
TEST(HardSingularityKdl, KdlChainIsTheSameArmAwayFromTheSingularity) {
  const Model model = stretched_arm();
  const Case c = stretched_arm_case(model, 0.1);
  const Row k = kdl_row(c), a = achd_row(model, c, Options());
  ASSERT_TRUE(k.ok);
  EXPECT_NEAR(k.nu, a.nu, 1e-9 * a.nu);
  EXPECT_NEAR(k.tau, a.tau, 1e-9 * a.tau);
}

Options kdl_like() {
  Options o;
  o.absolute_tolerance = true;
  o.tolerance = 1e-14;
  return o;
}

// What the table shows, asserted: KDL's constraint force passes 1e13 before its
// absolute 1e-14 threshold silently drops the constraint; achd with the same absolute
// threshold drops at the same angles (the parity option), with its default relative
// threshold drops earlier and says so (rank), and damped stays below |rhs| / (2 lambda)
// = 1e7 (hard_singularity.cpp) and varies smoothly.
TEST(HardSingularityKdl, PrintsTableKdlBlowsUpWhereDampedStaysBounded) {
  const Model model = stretched_arm();
  std::printf("\n| theta | KDL: nu | KDL: max tau | achd abs. 1e-14: nu | rank | achd truncate: nu |"
              " max tau | rank | achd damped: nu | max tau |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n");
  double kdl_nu_max = 0, damped_nu_max = 0;
  for (double theta : sweep_angles()) {
    const Case c = stretched_arm_case(model, theta);
    const Row k = kdl_row(c), t = achd_row(model, c, Options()), d = achd_row(model, c, damped());
    Data da(model), dt(model);
    hybrid_dynamics(model, da, c, kdl_like());
    hybrid_dynamics(model, dt, c, Options());
    std::printf("| %.0e | %.3e%s | %.3e | %.3e | %d | %.3e | %.3e | %d | %.3e | %.3e |\n", theta,
                k.nu, k.ok ? "" : " (error)", k.tau, da.nu.norm(), da.rank, t.nu, t.tau, dt.rank,
                d.nu, d.tau);
    // Same threshold, same decision and the same nu: above the threshold cond(K) <=
    // sigma_max / 1e-14 ~ 5e13, so the two solves may differ by eps cond ~ 1e-2 relative.
    EXPECT_NEAR(k.nu, da.nu.norm(), 1e-2 * k.nu) << theta;
    kdl_nu_max = std::max(kdl_nu_max, k.nu);
    damped_nu_max = std::max(damped_nu_max, d.nu);
  }
  std::printf("\n");
  EXPECT_GT(kdl_nu_max, 1e13);
  EXPECT_LT(damped_nu_max, 1e7);
}

}  // namespace
}  // namespace achd::test
