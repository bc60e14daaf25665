// Closed-form cases against formulas derived by hand: a pendulum (free and with its tip
// height constrained) and the 2-link planar arm of robots/planar2.urdf (M, C, g and a
// 1-constraint case).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "random_chain.hpp"

namespace achd::test {
namespace {

constexpr double kG = 9.81;
constexpr double kTol = 1e-12;

// Pendulum: joint about +y at the root origin, mass m at (L, 0, 0) of the arm with
// inertia Ic about its COM, and a tip link fixed at (L, 0, 0). The tip is at
// p = (L cos q, 0, -L sin q), so with gravity -z: V = -m g L sin q, and
//   (m L^2 + Ic) qdd = tau + m g L cos q.
struct Pendulum {
  double m = 2, L = 0.7, Ic = 1e-3;
  Model model;
  Pendulum() {
    std::ostringstream x;
    x.precision(17);
    x << "<robot name=\"pendulum\"><link name=\"base\"/>"
      << "<joint name=\"hinge\" type=\"continuous\"><parent link=\"base\"/><child link=\"arm\"/>"
      << "<axis xyz=\"0 1 0\"/></joint>"
      << "<link name=\"arm\"><inertial><origin xyz=\"" << L << " 0 0\"/><mass value=\"" << m
      << "\"/><inertia ixx=\"" << Ic << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << Ic
      << "\" iyz=\"0\" izz=\"" << Ic << "\"/></inertial></link>"
      << "<joint name=\"tool\" type=\"fixed\"><parent link=\"arm\"/><child link=\"tip\"/>"
      << "<origin xyz=\"" << L << " 0 0\"/></joint><link name=\"tip\"/></robot>";
    model = load_urdf_string(x.str(), "base", "tip");
  }
  Case make(double q, double qd, double tau) const {
    Case c = Case::zeros(model);
    c.q[0] = q;
    c.qd = Eigen::VectorXd::Constant(1, qd);
    c.ff_torques = Eigen::VectorXd::Constant(1, tau);
    return c;
  }
};

TEST(ClosedForm, PendulumFree) {
  const Pendulum p;
  Data d(p.model);
  for (const double q : {-2.0, -0.4, 0.0, 0.3, 1.2}) {
    const double tau = 0.4;
    hybrid_dynamics(p.model, d, p.make(q, 1.5, tau));
    const double expected = (tau + p.m * kG * p.L * std::cos(q)) / (p.m * p.L * p.L + p.Ic);
    EXPECT_NEAR(d.qdd[0], expected, kTol * std::max(1.0, std::abs(expected))) << "q " << q;
  }
}

// Constraint: the tip's z acceleration equals beta. The spatial acceleration of a point on
// a body turning about a fixed axis has no centripetal part, so with J_z = -L cos q:
//   -L cos q qdd = beta,   (m L^2 + Ic) qdd = tau + m g L cos q + nu L cos q
// (the robot receives -alpha nu = -nu e_z at the tip, torque -J_z nu = nu L cos q).
TEST(ClosedForm, PendulumWithTipHeightConstrained) {
  const Pendulum p;
  Data d(p.model);
  for (const double beta : {0.0, 0.8, -1.5}) {
    const double q = 0.5, qd = -1.1, tau = 0.3;
    Case c = p.make(q, qd, tau);
    c.alpha.resize(6, 1);
    c.alpha.col(0) << 0, 0, 1, 0, 0, 0;
    c.beta = ConstraintVector::Constant(1, beta);
    hybrid_dynamics(p.model, d, c);
    const double cq = std::cos(q), I = p.m * p.L * p.L + p.Ic;
    const double qdd = -beta / (p.L * cq);
    const double nu = (I * qdd - tau - p.m * kG * p.L * cq) / (p.L * cq);
    EXPECT_NEAR(d.qdd[0], qdd, kTol * std::max(1.0, std::abs(qdd)));
    EXPECT_NEAR(d.nu[0], nu, kTol * std::max(1.0, std::abs(nu)));
    EXPECT_NEAR(d.joint_torques[0], tau + nu * p.L * cq, kTol * std::max(1.0, std::abs(nu)));
    EXPECT_NEAR(d.link_accelerations.back()[2], beta, kTol);
  }
  // Held at rest (beta = 0, qd = 0, tau = 0): the constraint carries the weight, the tip
  // pushes down on it with m g.
  Case c = p.make(0.5, 0, 0);
  c.alpha.resize(6, 1);
  c.alpha.col(0) << 0, 0, 1, 0, 0, 0;
  c.beta = ConstraintVector::Zero(1);
  hybrid_dynamics(p.model, d, c);
  EXPECT_NEAR(d.qdd[0], 0, kTol);
  EXPECT_NEAR(d.constraint_wrench[2], -p.m * kG, kTol * p.m * kG);
}

// robots/planar2.urdf: l1 = l2 = 1, m1 = m2 = 1 at the far link ends, Ic = 1e-3 about y,
// both joints about +y with q turning +x towards -z. In the plane (x, y' = -z) it is the
// textbook arm with gravity along +y':
//   M11 = 2 Ic + m1 l1^2 + m2 (l1^2 + l2^2 + 2 l1 l2 c2),  M12 = Ic + m2 (l2^2 + l1 l2 c2),
//   M22 = Ic + m2 l2^2;  h = m2 l1 l2 s2;  C = [-h (2 qd1 qd2 + qd2^2); h qd1^2];
//   G = [-(m1 + m2) g l1 c1 - m2 g l2 c12; -m2 g l2 c12].
struct Planar2 {
  Model model = load_urdf_file(ACHD_SOURCE_DIR "/robots/planar2.urdf", "base_link", "link2");
  static Eigen::Matrix2d M(const Eigen::Vector2d& q) {
    const double c2 = std::cos(q[1]), Ic = 1e-3;
    Eigen::Matrix2d m;
    m << 2 * Ic + 1 + 2 + 2 * c2, Ic + 1 + c2, Ic + 1 + c2, Ic + 1;
    return m;
  }
  static Eigen::Vector2d CG(const Eigen::Vector2d& q, const Eigen::Vector2d& qd) {
    const double h = std::sin(q[1]), c1 = std::cos(q[0]), c12 = std::cos(q[0] + q[1]);
    return Eigen::Vector2d(-h * (2 * qd[0] * qd[1] + qd[1] * qd[1]) - 2 * kG * c1 - kG * c12,
                           h * qd[0] * qd[0] - kG * c12);
  }
};

TEST(ClosedForm, Planar2MassMatrixRneaAndForwardDynamics) {
  const Planar2 p;
  std::mt19937 rng(808);
  std::uniform_real_distribution<double> u(-2, 2);
  Data d(p.model);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector2d q(u(rng), u(rng)), qd(u(rng), u(rng)), qdd(u(rng), u(rng));
    const Eigen::Vector2d tau(u(rng), u(rng));
    const Eigen::Matrix2d M = Planar2::M(q);
    const Eigen::Vector2d cg = Planar2::CG(q, qd);
    EXPECT_LE((crba(p.model, q) - M).cwiseAbs().maxCoeff(), kTol * 5);
    EXPECT_LE(rel_error(rnea(p.model, q, qd, qdd, Vector3(0, 0, -kG)), M * qdd + cg), kTol);
    Case c = Case::zeros(p.model);
    c.q = q;
    c.qd = qd;
    c.ff_torques = tau;
    hybrid_dynamics(p.model, d, c);
    EXPECT_LE(rel_error(d.qdd, M.inverse() * (tau - cg)), kTol);
  }
}

// One constraint by hand: the tip (link2's origin, the elbow, p = (c1, 0, -s1)) has
// spatial z acceleration -c1 qdd1 - qd1 qd2 s1 (classical -c1 qdd1 + s1 qd1^2 minus
// (w x v)_z = s1 qd1 (qd1 + qd2)) and J_z = [-c1, 0]. So
//   qdd1 = -(beta + qd1 qd2 s1) / c1,   qdd2 = (tau2 - CG2 - M21 qdd1) / M22,
//   nu = (M11 qdd1 + M12 qdd2 + CG1 - tau1) / c1   (row 1: M qdd + CG = tau + [c1 nu, 0]).
TEST(ClosedForm, Planar2ElbowHeightConstrainedByHand) {
  const Planar2 p;
  const Eigen::Vector2d q(0.4, 0.9), qd(0.7, -1.3), tau(0.5, -0.2);
  const double beta = 0.6, c1 = std::cos(q[0]), s1 = std::sin(q[0]);
  const Eigen::Matrix2d M = Planar2::M(q);
  const Eigen::Vector2d cg = Planar2::CG(q, qd);
  const double qdd1 = -(beta + qd[0] * qd[1] * s1) / c1;
  const double qdd2 = (tau[1] - cg[1] - M(1, 0) * qdd1) / M(1, 1);
  const double nu = (M(0, 0) * qdd1 + M(0, 1) * qdd2 + cg[0] - tau[0]) / c1;
  Case c = Case::zeros(p.model);
  c.q = q;
  c.qd = qd;
  c.ff_torques = tau;
  c.alpha.resize(6, 1);
  c.alpha.col(0) << 0, 0, 1, 0, 0, 0;
  c.beta = ConstraintVector::Constant(1, beta);
  Data d(p.model);
  hybrid_dynamics(p.model, d, c);
  EXPECT_LE(rel_error(d.qdd, Eigen::Vector2d(qdd1, qdd2)), kTol);
  EXPECT_NEAR(d.nu[0], nu, kTol * std::max(1.0, std::abs(nu)));
}

}  // namespace
}  // namespace achd::test
