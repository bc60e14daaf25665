// Coupled joints (URDF <mimic>, loaded coupled by default): the solve holds
// qdd_f = k qdd_l, equals the dense solve of Gauss's principle with the coupling as a
// joint-space constraint (the KKT system of M, the coupling rows and a constraint block),
// RNEA at the solved qdd reproduces joint_torques = ff - J^T alpha nu - C^T nu_c, a
// simulation keeps q_f = k q_l + c, and solves allocate nothing. Robots: the Panda of
// example-robot-data (its second finger mimics the first) and Talos (its grippers), and a
// seeded random tree given couplings between random joints.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <regex>
#include <string>

#include <Eigen/Dense>

#include "achd/achd.hpp"
#include "counted_new.hpp"
#include "reference_dynamics.hpp"

namespace achd::test {
namespace {

const std::string kRobots = std::string(ACHD_SOURCE_DIR) + "/robots/example-robot-data/";

Model panda() { return load_urdf_file(kRobots + "panda_description/urdf/panda.urdf", "", ""); }

// A state within the limits, seeded.
void random_state(const Model& model, std::mt19937& rng, Case& c) {
  std::uniform_real_distribution<double> u(0, 1), v(-1, 1);
  c.q = default_pose(model);
  c.qd = Eigen::VectorXd::Zero(model.num_rates());
  c.ff_torques = Eigen::VectorXd::Zero(model.num_rates());
  for (int i = model.floating ? 6 : 0; i < model.num_rates(); ++i) {
    const JointLimits& l = model.bodies[i].limits;
    const double lo = std::max(l.lower, -2.0), hi = std::min(l.upper, 2.0);
    c.q[model.position_index(i)] = lo + u(rng) * (hi - lo);
    c.qd[i] = v(rng);
    c.ff_torques[i] = 5 * v(rng);
  }
  // coupled joints start on their coupling (position and rate)
  for (const JointCoupling& j : model.couplings) {
    c.q[model.position_index(j.follower)] = j.multiplier * c.q[model.position_index(j.leader)] + j.offset;
    c.qd[j.follower] = j.multiplier * c.qd[j.leader];
  }
}

// The coupling rows C (p x n).
Eigen::MatrixXd coupling_rows(const Model& model) {
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(model.couplings.size(), model.num_rates());
  for (size_t j = 0; j < model.couplings.size(); ++j) {
    C(j, model.couplings[j].follower) += 1;
    C(j, model.couplings[j].leader) -= model.couplings[j].multiplier;
  }
  return C;
}

TEST(JointCouplings, PandaLoadsWithItsFingersCoupled) {
  const Model m = panda();
  ASSERT_EQ(m.couplings.size(), 1u);
  EXPECT_EQ(m.bodies[m.couplings[0].follower].joint_name, "panda_finger_joint2");
  EXPECT_EQ(m.bodies[m.couplings[0].leader].joint_name, "panda_finger_joint1");
  EXPECT_EQ(m.couplings[0].multiplier, 1.0);
  // Talos' grippers load without an option.
  const Model talos = load_urdf_file(kRobots + "talos_data/robots/talos_full_v2.urdf", "", "");
  EXPECT_GT(talos.couplings.size(), 0u);
  // KDL's way stays an option; and refusing them.
  UrdfOptions independent;
  independent.mimic = MimicJoints::Independent;
  EXPECT_TRUE(load_urdf_file(kRobots + "panda_description/urdf/panda.urdf", "", "", independent).couplings.empty());
}

// A <mimic> naming a joint the file does not have couples to nothing: its joint loads as
// a joint of its own, with a warning naming both (a leader the file has but the model
// holds fixed stays an error: tests/native/cli/bad_input_cli.cpp).
TEST(JointCouplings, AMimicOfAJointTheFileDoesNotHaveLoadsWithAWarning) {
  const std::string link = R"(<link name="NAME"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>)";
  const auto named = [&](const std::string& name) { return std::regex_replace(link, std::regex("NAME"), name); };
  const std::string urdf = "<robot name=\"r\">" + named("base") + named("a") + named("b") +
                           R"(<joint name="ja" type="revolute"><parent link="base"/><child link="a"/>
                                <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
                              <joint name="jb" type="revolute"><parent link="a"/><child link="b"/>
                                <origin xyz="0.1 0 0"/><axis xyz="0 1 0"/>
                                <limit lower="-1" upper="1" effort="1" velocity="1"/>
                                <mimic joint="gone" multiplier="2"/></joint></robot>)";
  const Model m = load_urdf_string(urdf, "", "");
  EXPECT_TRUE(m.couplings.empty());
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("joint 'jb': <mimic> of joint 'gone', which the file does not have"), std::string::npos)
      << m.warnings[0];
}

// Without other constraints: the KKT system [M C^T; C 0] [qdd; nu_c] = [tau - h; 0] of
// Gauss's principle (M and h from the reference dynamics).
TEST(JointCouplings, SolveEqualsTheDenseKktSolve) {
  const Model m = panda();
  std::mt19937 rng(7);
  Data d(m);
  const Eigen::MatrixXd C = coupling_rows(m);
  const int n = m.num_rates(), p = static_cast<int>(C.rows());
  double worst = 0, worst_rnea = 0, worst_row = 0;
  for (int trial = 0; trial < 50; ++trial) {
    Case c = Case::zeros(m);
    random_state(m, rng, c);
    hybrid_dynamics(m, d, c);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    const Eigen::MatrixXd M = reference_crba(m, c.q);
    const Eigen::VectorXd h = reference_rnea(m, c.q, c.qd, zero, c.gravity);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + p, n + p);
    K.topLeftCorner(n, n) = M;
    K.topRightCorner(n, p) = C.transpose();
    K.bottomLeftCorner(p, n) = C;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + p);
    rhs.head(n) = c.ff_torques - h;
    const Eigen::VectorXd x = K.fullPivLu().solve(rhs);
    const double scale = std::max(1.0, x.head(n).cwiseAbs().maxCoeff());
    worst = std::max(worst, (d.qdd - x.head(n)).cwiseAbs().maxCoeff() / scale);
    worst = std::max(worst, std::abs(d.coupling_forces[0] - x[n]) / std::max(1.0, std::abs(x[n])));
    worst_row = std::max(worst_row, (C * d.qdd).cwiseAbs().maxCoeff() / scale);
    const Eigen::VectorXd tau = reference_rnea(m, c.q, c.qd, d.qdd, c.gravity);
    worst_rnea = std::max(worst_rnea, (tau - d.joint_torques).cwiseAbs().maxCoeff() / std::max(1.0, tau.cwiseAbs().maxCoeff()));
    const Eigen::VectorXd expected = c.ff_torques - C.transpose() * d.coupling_forces;
    worst_rnea = std::max(worst_rnea, (expected - d.joint_torques).cwiseAbs().maxCoeff() / std::max(1.0, tau.cwiseAbs().maxCoeff()));
  }
  std::printf("Panda, 50 states: |qdd - KKT| %.3g, |C qdd| %.3g, |RNEA - joint_torques| %.3g\n", worst, worst_row,
              worst_rnea);
  EXPECT_LE(worst, 1e-8);
  EXPECT_LE(worst_row, 1e-12);
  EXPECT_LE(worst_rnea, 1e-10);
}

// With a constraint block on the hand (6D): the KKT system gains the block's rows
// alpha^T J qdd = beta - alpha^T (Jdot qd) (read off the solver's own link acceleration at
// qdd = 0); the solve still equals it, and the block's and the coupling's constraints hold.
TEST(JointCouplings, WithAConstraintBlockTheSolveEqualsTheDenseKktSolve) {
  const Model m = panda();
  const int hand = m.link_index("panda_hand");
  ASSERT_GE(hand, 0);
  std::mt19937 rng(11);
  Data d(m), free_data(m);
  const Eigen::MatrixXd C = coupling_rows(m);
  const int n = m.num_rates(), p = static_cast<int>(C.rows());
  double worst = 0;
  for (int trial = 0; trial < 30; ++trial) {
    Case c = Case::zeros(m);
    random_state(m, rng, c);
    ConstraintBlock b;
    b.link = hand;
    b.alpha = ConstraintMatrix::Identity(6, 3);  // x, y, z of the hand
    b.beta = ConstraintVector::Constant(3, 0.3);
    c.constraints.push_back(b);
    hybrid_dynamics(m, d, c);
    // The hand's rows: J (its Jacobian, base axes, linear first) and its acceleration at
    // qdd = 0 (velocity products and gravity's shift: the prescribed-zero solve).
    const Eigen::MatrixXd J = link_jacobian(m, c.q, hand);
    Case still = c;
    still.constraints.clear();
    still.prescribed.assign(n, true);
    still.qdd_given = Eigen::VectorXd::Zero(n);
    hybrid_dynamics(m, free_data, still);
    const Vector6 a_bias = free_data.link_accelerations[hand + 1];
    const Eigen::MatrixXd A = b.alpha.transpose() * J;
    const Eigen::MatrixXd M = reference_crba(m, c.q);
    const Eigen::VectorXd h = reference_rnea(m, c.q, c.qd, Eigen::VectorXd::Zero(n), c.gravity);
    const int r = p + 3;
    Eigen::MatrixXd G(r, n);
    G << C, A;
    Eigen::VectorXd g(r);
    g << Eigen::VectorXd::Zero(p), b.beta - b.alpha.transpose() * a_bias;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + r, n + r);
    K.topLeftCorner(n, n) = M;
    K.topRightCorner(n, r) = G.transpose();
    K.bottomLeftCorner(r, n) = G;
    Eigen::VectorXd rhs(n + r);
    rhs << c.ff_torques - h, g;
    const Eigen::VectorXd x = K.fullPivLu().solve(rhs);
    worst = std::max(worst, (d.qdd - x.head(n)).cwiseAbs().maxCoeff() / std::max(1.0, x.head(n).cwiseAbs().maxCoeff()));
    // and the hand's acceleration is beta
    const Vector6& a = d.link_accelerations[hand + 1];
    EXPECT_LE((b.alpha.transpose() * a - b.beta).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LE((C * d.qdd).cwiseAbs().maxCoeff(), 1e-9);
  }
  std::printf("Panda with the hand held in x, y, z, 30 states: |qdd - KKT| %.3g\n", worst);
  EXPECT_LE(worst, 1e-8);
}

// 10 s of the default simulator (adaptive Dormand-Prince) under gravity: the fingers move
// together, q_f - k q_l - c within 1e-9 at every step.
TEST(JointCouplings, SimulatedFingersMoveTogether) {
  const Model m = panda();
  Simulator sim(m);
  std::mt19937 rng(3);
  Case c = Case::zeros(m);
  random_state(m, rng, c);
  sim.q = c.q;
  sim.qd = c.qd;
  const JointCoupling& j = m.couplings[0];
  double worst = 0;
  for (int step = 0; step < 10000; ++step) {
    sim.step(1e-3);
    worst = std::max(worst, std::abs(sim.q[m.position_index(j.follower)] - j.multiplier * sim.q[m.position_index(j.leader)] - j.offset));
  }
  std::printf("Panda 10 s: worst |q_f - k q_l - c| %.3g\n", worst);
  EXPECT_LE(worst, 1e-9);
}

TEST(JointCouplings, SolvesAllocateNothing) {
  const Model m = panda();
  Data d(m);
  std::mt19937 rng(5);
  Case c = Case::zeros(m);
  random_state(m, rng, c);
  ConstraintBlock b;
  b.link = m.link_index("panda_hand");
  b.alpha = ConstraintMatrix::Identity(6, 6);
  b.beta = ConstraintVector::Zero(6);
  c.constraints.push_back(b);
  hybrid_dynamics(m, d, c);  // warm
  const long before = g_allocations;
  for (int k = 0; k < 10; ++k) hybrid_dynamics(m, d, c);
  EXPECT_EQ(g_allocations - before, 0);
}

}  // namespace
}  // namespace achd::test
