// The stretched-arm singularity sweep (hard_stretched_arm.hpp): theta from 1e-1 to
// 1e-12, the radial tip constraint along the direction the arm loses.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>

#include "achd/dynamics.hpp"
#include "achd/kinematics.hpp"

#include "hard_stretched_arm.hpp"
#include "reference_dynamics.hpp"

namespace achd::test {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Solve {
  Data data;
  Eigen::Vector2d residual;  // alpha^T a_tip - beta
  double sigma_max = 0;      // of K (data.K holds K after the solve)
};

Solve solve(const Model& model, double theta, const Options& options) {
  Solve s{Data(model), {}, 0};
  const Case c = stretched_arm_case(model, theta);
  hybrid_dynamics(model, s.data, c, options);
  s.residual = c.alpha.transpose() * s.data.link_accelerations.back() - c.beta;
  s.sigma_max = Eigen::SelfAdjointEigenSolver<CouplingMatrix>(s.data.K).eigenvalues().maxCoeff();
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
    const Eigen::MatrixXd M = reference_crba(model, free.q);
    const Eigen::VectorXd m_eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    const double lambda = o.damping * s.sigma_max, rhs = s.data.workspace.rhs.norm();
    const double gain = 0.57 * std::sqrt(2.0) * rhs / std::sqrt(lambda);
    // 1 + 1e-9: the bounds evaluated in floating point
    EXPECT_LE(s.data.nu.norm(), rhs / (2 * lambda) * (1 + 1e-9)) << theta;
    EXPECT_LE(s.data.joint_torques.cwiseAbs().maxCoeff(),
              gain * std::sqrt(m_eig.maxCoeff()) * (1 + 1e-9)) << theta;
    EXPECT_LE((s.data.qdd - d_free.qdd).norm(), gain / std::sqrt(m_eig.minCoeff()) * (1 + 1e-9))
        << theta;
  }
}

// Continuity, on a log grid of theta with ratio r = 10^(1/4) from 1e-1 to 1e-12. Split
// the torques along the eigenvectors of K: tau_lost = -J^T A v (v^T nu) for the
// smallest eigenvalue's v (the radial direction) and tau_kept for the other. Each part
// is a product of |J^T A v| ~ theta^(0..1) and a gain ~ theta^(-2..2) (1/sigma above
// lambda, sigma/lambda^2 below, sigma ~ theta^2), so its logarithmic slope is at most
// 3 in magnitude and neighbours differ by at most a factor r^3 = 5.6 in each part
// (the sum may cancel, so the parts are checked, not the sum). Truncation breaks this
// where sigma crosses its threshold: tau_lost jumps from 1e6 to 0.
double largest_jump(const Model& model, const Options& o) {
  const double r = std::pow(10.0, 0.25);
  double jump = 1;
  Eigen::Vector2d previous = Eigen::Vector2d::Zero();
  for (double theta = 0.1; theta >= 1e-12; theta /= r) {
    const Solve s = solve(model, theta, o);
    const Case c = stretched_arm_case(model, theta);
    const Eigen::SelfAdjointEigenSolver<CouplingMatrix> eig(s.data.K);
    const Eigen::MatrixXd JA = tip_jacobian(model, c.q).transpose() * c.alpha;
    Eigen::Vector2d parts;  // |tau_lost|, |tau_kept|; eigenvalues ascending
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d v = eig.eigenvectors().col(k);
      parts[k] = (JA * v * v.dot(s.data.nu)).cwiseAbs().maxCoeff() + 1e-300;
    }
    if (previous[0] > 0)
      for (int k = 0; k < 2; ++k)
        jump = std::max(jump, std::max(parts[k] / previous[k], previous[k] / parts[k]));
    previous = parts;
  }
  return jump;
}

TEST(HardSingularity, DampedTorquesVaryContinuouslyAcrossTheSweep) {
  const Model model = stretched_arm();
  EXPECT_LE(largest_jump(model, damped()), std::pow(10.0, 0.75));
  EXPECT_GT(largest_jump(model, Options()), 1e4);  // truncate: the jump the table shows
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
    const double cond = s.sigma_max / std::max(sigma_min(s.data), 1e-300);
    ASSERT_TRUE(s.data.nu.allFinite() && s.data.qdd.allFinite()) << theta;
    if (sigma_min(s.data) > o.tolerance * s.sigma_max) {
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
      const Eigen::VectorXd tau = reference_rnea(model, c.q, c.q * 0, s.data.qdd, c.gravity);
      const double scale = std::max(1.0, s.data.joint_torques.cwiseAbs().maxCoeff());
      // RNEA and the solver each round O(n) products of size |tau|: 1e2 eps relative.
      EXPECT_LE((tau - s.data.joint_torques).cwiseAbs().maxCoeff(), 1e2 * kEps * scale)
          << "theta " << theta;
    }
  }
}

}  // namespace
}  // namespace achd::test
