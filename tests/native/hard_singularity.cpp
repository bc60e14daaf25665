// The stretched-arm singularity sweep (hard_stretched_arm.hpp): theta from 1e-1 to
// 1e-12, the radial tip constraint along the direction the arm loses.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>

#include "achd/dynamics.hpp"

#include "hard_stretched_arm.hpp"

namespace achd::test {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Solve {
  Data data;
  Eigen::Vector2d residual;  // alpha^T a_tip - beta
  double sigma_max = 0;      // of K (data.M0 holds K after the solve)
};

Solve solve(const Model& model, double theta, const Options& options) {
  Solve s{Data(model), {}, 0};
  const Case c = stretched_arm_case(model, theta);
  hybrid_dynamics(model, s.data, c, options);
  s.residual = c.alpha.transpose() * s.data.link_accelerations.back() - c.beta;
  s.sigma_max = Eigen::SelfAdjointEigenSolver<CouplingMatrix>(s.data.M0).eigenvalues().maxCoeff();
  return s;
}

Options damped() {
  Options o;
  o.policy = SingularityPolicy::Damped;
  return o;
}

// Damped least squares: nu = sum_k v_k g(sigma_k) v_k^T rhs with the gain
// g(sigma) = sigma / (sigma^2 + lambda^2) <= 1 / (2 lambda), lambda = damping sigma_max.
// Through K = B^T B, B = M^-1/2 J^T A, each direction moves the joints by
// |J^T A v_k| <= sqrt(sigma_k |M|) and |M^-1 J^T A v_k| <= sqrt(sigma_k |M^-1|), and
// sigma^1.5 g(sigma) peaks at 3^0.75 / 4 / sqrt(lambda) < 0.57 / sqrt(lambda). So
//   |nu| <= |rhs| / (2 lambda),
//   |tau| <= 0.57 sqrt(nc) |rhs| sqrt(|M| / lambda),
//   |qdd - qdd_free| <= 0.57 sqrt(nc) |rhs| sqrt(|M^-1| / lambda),
// for every theta, where the undamped values grow like 1/theta^2 and 1/theta.
TEST(HardSingularity, DampedKeepsTorquesAndAccelerationsBounded) {
  const Model model = stretched_arm();
  const Options o = damped();
  for (double theta : sweep_angles()) {
    const Solve s = solve(model, theta, o);
    ASSERT_TRUE(s.data.joint_torques.allFinite() && s.data.qdd.allFinite()) << theta;
    Case free = stretched_arm_case(model, theta);
    free.alpha.resize(6, 0);
    free.beta.resize(0);
    Data d_free(model);
    hybrid_dynamics(model, d_free, free, o);
    const Eigen::MatrixXd M = crba(model, free.q);
    const Eigen::VectorXd m_eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    const double lambda = o.damping * s.sigma_max, rhs = s.data.rhs.norm();
    const double gain = 0.57 * std::sqrt(2.0) * rhs / std::sqrt(lambda);
    // 1 + 1e-9: the bounds evaluated in floating point
    EXPECT_LE(s.data.nu.norm(), rhs / (2 * lambda) * (1 + 1e-9)) << theta;
    EXPECT_LE(s.data.joint_torques.cwiseAbs().maxCoeff(),
              gain * std::sqrt(m_eig.maxCoeff()) * (1 + 1e-9)) << theta;
    EXPECT_LE((s.data.qdd - d_free.qdd).norm(), gain / std::sqrt(m_eig.minCoeff()) * (1 + 1e-9))
        << theta;
  }
}

// Continuity: a relative change of 1e-3 in theta changes the damped torques by a
// relative amount of the same order (the damped gain is smooth in sigma, and sigma is
// smooth in theta), measured against the largest torque of the sweep. Truncation, by
// contrast, jumps where sigma crosses the threshold.
TEST(HardSingularity, DampedTorquesVaryContinuouslyAcrossTheSweep) {
  const Model model = stretched_arm();
  const Options o = damped();
  std::vector<double> thetas;
  for (double theta : sweep_angles())
    for (double f : {1.0, 1.5, 2.0, 3.0, 5.0, 7.0}) thetas.push_back(theta * f);
  double scale = 0;
  for (double theta : thetas)
    scale = std::max(scale, solve(model, theta, o).data.joint_torques.cwiseAbs().maxCoeff());
  const double h = 1e-3;
  for (double theta : thetas) {
    const Solve a = solve(model, theta, o), b = solve(model, theta * (1 + h), o);
    // |d tau / d log theta| <= 4 scale: sigma ~ theta^2 gives a factor 2, the damped
    // gain's logarithmic slope is at most 1 in magnitude, and 2x margin.
    EXPECT_LE((a.data.joint_torques - b.data.joint_torques).cwiseAbs().maxCoeff(), 4 * h * scale)
        << "theta " << theta;
  }
}

// Truncation (relative tolerance 1e-12): once sigma_min < 1e-12 sigma_max the radial
// direction is dropped, reported in data.dropped and data.rank, and the remaining
// (vertical) constraint still holds.
TEST(HardSingularity, TruncateReportsTheDroppedDirectionAndHoldsTheOthers) {
  const Model model = stretched_arm();
  const Options o;  // truncate, relative tolerance 1e-12
  int dropped_seen = 0;
  for (double theta : sweep_angles()) {
    const Solve s = solve(model, theta, o);
    const double cond = s.sigma_max / std::max(s.data.sigma_min, 1e-300);
    ASSERT_TRUE(s.data.nu.allFinite() && s.data.qdd.allFinite()) << theta;
    if (s.data.sigma_min > o.tolerance * s.sigma_max) {
      EXPECT_EQ(s.data.rank, 2) << theta;
      EXPECT_EQ(s.data.dropped.cols(), 0) << theta;
      // Both constraints hold. The base solve is backward stable: its residual is
      // eps |K| |nu| ~ eps cond(K) |rhs|, |rhs| <= 20 m/s^2 (gravity, beta); 1e2 for the
      // O(n) sweeps that form K and rhs.
      EXPECT_LE(s.residual.cwiseAbs().maxCoeff(), 1e2 * kEps * cond * 20) << theta;
      continue;
    }
    ++dropped_seen;
    EXPECT_EQ(s.data.rank, 1) << theta;
    ASSERT_EQ(s.data.dropped.rows(), 2);
    ASSERT_EQ(s.data.dropped.cols(), 1);
    const Eigen::Vector2d d = s.data.dropped.col(0);
    // The dropped direction is the radial constraint: its coupling to the vertical one
    // is O(theta) (the tip Jacobian's off-diagonal terms), so |d_x| >= 1 - 1e-6 here.
    EXPECT_GT(std::abs(d[0]), 1 - 1e-6) << theta;
    // The kept direction holds: its block of K is well conditioned (cond_kept =
    // sigma_max / sigma_kept <= 10 for this arm), so the projected residual is a few eps
    // times |rhs| <= 20, times 1e2 for the sweeps.
    const Eigen::Vector2d kept_residual = s.residual - d * d.dot(s.residual);
    EXPECT_LE(kept_residual.norm(), 1e2 * kEps * 10 * 20) << theta;
    // Nothing is applied along the dropped direction.
    EXPECT_LE(std::abs(d.dot(s.data.nu)), 1e-9 * s.data.nu.norm() + 1e-300) << theta;
  }
  // sigma_min ~ theta^2 / 10: theta <= 1e-7 are below 1e-12 sigma_max.
  EXPECT_GE(dropped_seen, 5);
}

// The physics identity joint_torques = RNEA(q, qd, qdd) holds on both sides of the
// threshold and for both policies, relative to the torques' size.
TEST(HardSingularity, JointTorquesMatchInverseDynamicsAtEveryAngle) {
  const Model model = stretched_arm();
  for (const Options& o : {Options(), damped()}) {
    for (double theta : sweep_angles()) {
      const Solve s = solve(model, theta, o);
      const Case c = stretched_arm_case(model, theta);
      const Eigen::VectorXd tau = rnea(model, c.q, c.q * 0, s.data.qdd, c.gravity);
      const double scale = std::max(1.0, s.data.joint_torques.cwiseAbs().maxCoeff());
      // RNEA and the solver each round O(n) products of size |tau|: 1e2 eps relative.
      EXPECT_LE((tau - s.data.joint_torques).cwiseAbs().maxCoeff(), 1e2 * kEps * scale)
          << "theta " << theta;
    }
  }
}

}  // namespace
}  // namespace achd::test
