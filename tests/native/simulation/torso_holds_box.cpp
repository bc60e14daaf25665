// The dual-arm torso holding a box with both hands (robots/dual_arm_torso_box.urdf: the
// box hangs from the root by a 6-DoF path of massless frames, and two fixed loop joints,
// robots/dual_arm_torso_box.loops.json, close it to the hands; the scene
// robots/scenes/dual_arm_torso_box.json holds the closed default pose and a joint PD):
// the default pose closes both loops (the simulator's closure error, forward kinematics
// on grip frames written here from the box's dimensions, and a Newton solve over the box's
// six joints that finds that pose again), the simulator with its defaults keeps the hands
// on the box while the PD moves the torso and arms, and at rest the loop wrenches carry
// the box's weight through its centre of mass, shared by both hands.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "achd/achd.hpp"
#include "achd/loops.hpp"
#include "scene_json.hpp"

namespace {

constexpr double kBoxMass = 2.0;          // kg (the URDF's box link)
constexpr double kBoxHalfWidth = 0.15;    // m: the box is 0.3 m along its y, hand to hand
constexpr double kGripReach = 0.12;       // m: the grip point along each hand's z
constexpr double kG = 9.81;
const char* const kBoxJoints[6] = {"box_x", "box_y", "box_z", "box_yaw", "box_pitch", "box_roll"};

achd::cli::Scene scene() {
  return achd::cli::load_scene(std::string(ACHD_SOURCE_DIR) + "/robots/scenes/dual_arm_torso_box.json");
}

std::vector<int> box_joints(const achd::Model& m) {
  std::vector<int> out;
  for (const char* name : kBoxJoints) out.push_back(m.joint_index(name));
  return out;
}

bool is_box_joint(const achd::Model& m, int i) {
  for (int j : box_joints(m))
    if (i == j) return true;
  return false;
}

// The grip frames as the box's geometry gives them, independently of the loops file:
// on each hand at (0, 0, kGripReach) with the hand's axes; on the box at the centre of the
// side face the hand presses, (0, +-kBoxHalfWidth, 0), its z pointing into the box (-+y)
// and its x along the box's x: Rx(+pi/2) for the left face, Rx(-pi/2) for the right.
achd::Transform hand_grip() {
  achd::Transform t;
  t.p = achd::Vector3(0, 0, kGripReach);
  return t;
}

achd::Transform box_grip(bool left) {
  achd::Transform t;
  t.p = achd::Vector3(0, left ? kBoxHalfWidth : -kBoxHalfWidth, 0);
  t.R = Eigen::AngleAxisd(left ? M_PI / 2 : -M_PI / 2, achd::Vector3::UnitX()).toRotationMatrix();
  return t;
}

// The loop error of loop `l` in base axes, e = [p_A - p_B; theta(R_A R_B^T)] (theta: the
// rotation vector), and its derivative over q when the loop is nearly closed,
// de/dq = J_a(at frame a's origin) - J_b(at frame b's origin) (rows [v; w], base axes).
void loop_residual(const achd::Model& m, const Eigen::VectorXd& q, int l, achd::Vector6& e, Eigen::MatrixXd& J) {
  const achd::LoopJoint& loop = m.loops[l];
  const std::vector<achd::Transform> X = achd::forward_kinematics(m, q);
  const achd::Transform A = X[loop.link_a] * loop.frame_a, B = X[loop.link_b] * loop.frame_b;
  const Eigen::AngleAxisd turn(A.R * B.R.transpose());
  e << A.p - B.p, turn.angle() * turn.axis();
  J = achd::link_jacobian(m, q, loop.link_a, loop.frame_a.p) - achd::link_jacobian(m, q, loop.link_b, loop.frame_b.p);
}

// Gauss-Newton over the joints `free`, the others as q gives them: the 12 errors of both
// loops against their 12 x |free| Jacobian, dq = -pinv(J) e, until |e| stops falling.
// Returns the last |e|.
double close_loops(const achd::Model& m, const std::vector<int>& free, Eigen::VectorXd& q) {
  double last = 1e300;
  for (int it = 0; it < 50; ++it) {
    Eigen::VectorXd e(12);
    Eigen::MatrixXd J(12, free.size());
    for (int l = 0; l < 2; ++l) {
      achd::Vector6 el;
      Eigen::MatrixXd Jl;
      loop_residual(m, q, l, el, Jl);
      e.segment<6>(6 * l) = el;
      for (size_t k = 0; k < free.size(); ++k) J.block<6, 1>(6 * l, k) = Jl.col(free[k]);
    }
    const double norm = e.norm();
    if (!(norm < last)) break;
    last = norm;
    const Eigen::VectorXd dq = J.completeOrthogonalDecomposition().solve(e);
    for (size_t k = 0; k < free.size(); ++k) q[free[k]] -= dq[k];
  }
  return last;
}

}  // namespace

// Two fixed loops, all six directions of each held: with the arms still, the box's six
// joints can open either loop in every direction, so the tree holds none of them already.
TEST(TorsoHoldsBox, BothGripsHoldAllSixDirections) {
  const achd::cli::Scene s = scene();
  const achd::Model& m = s.model;
  ASSERT_EQ(m.loops.size(), 2u);
  EXPECT_EQ(m.loops[0].name, "left_grip");
  EXPECT_EQ(m.loops[1].name, "right_grip");
  for (const achd::LoopJoint& loop : m.loops) {
    EXPECT_EQ(achd::loop_direction_names(loop.directions),
              (std::vector<std::string>{"x", "y", "z", "rx", "ry", "rz"}))
        << loop.name;
    EXPECT_EQ(loop.dropped, 0u) << loop.name;
  }
  EXPECT_EQ(m.num_loop_columns(), 12);
  EXPECT_EQ(m.num_rates(), 21);
}

// The scene's q0 closes both loops: the simulator's closure error after reset, the grip
// frames of this file by forward kinematics (positions and axes), and a Newton solve over
// the box's six joints alone, started 3 cm and 0.1 rad away with the arms at q0, returns
// to q0's box joints with both loops closed.
TEST(TorsoHoldsBox, DefaultPoseClosesBothLoops) {
  const achd::cli::Scene s = scene();
  const achd::Model& m = s.model;
  const Eigen::VectorXd q0 = s.q0;

  achd::Simulator sim(m);
  sim.reset(q0, Eigen::VectorXd::Zero(m.num_rates()));
  for (int l = 0; l < 2; ++l) EXPECT_LT(sim.loop_error(l), 1e-12) << m.loops[l].name;

  const std::vector<achd::Transform> X = achd::forward_kinematics(m, q0);
  const int box = m.link_index("box");
  for (bool left : {true, false}) {
    const int hand = m.link_index(left ? "left_hand" : "right_hand");
    const achd::Transform H = X[hand] * hand_grip(), B = X[box] * box_grip(left);
    EXPECT_LT((H.p - B.p).norm(), 1e-12) << (left ? "left" : "right");
    EXPECT_LT((H.R - B.R).norm(), 1e-12) << (left ? "left" : "right");
    // the loops file says the same frames
    const achd::LoopJoint& loop = m.loops[left ? 0 : 1];
    EXPECT_EQ(loop.link_a, hand);
    EXPECT_EQ(loop.link_b, box);
    EXPECT_LT((loop.frame_a.p - hand_grip().p).norm() + (loop.frame_a.R - hand_grip().R).norm(), 1e-15);
    EXPECT_LT((loop.frame_b.p - box_grip(left).p).norm() + (loop.frame_b.R - box_grip(left).R).norm(), 1e-15);
  }
  // The box's centre sits halfway between the grip points, and the hands 0.3 m apart.
  const achd::Vector3 left_point = (X[box] * box_grip(true)).p, right_point = (X[box] * box_grip(false)).p;
  EXPECT_NEAR((left_point - right_point).norm(), 2 * kBoxHalfWidth, 1e-14);

  Eigen::VectorXd q = q0;
  const std::vector<int> free = box_joints(m);
  const double start[6] = {0.03, -0.03, 0.03, 0.1, -0.1, 0.1};
  for (int k = 0; k < 6; ++k) q[free[k]] += start[k];
  const double residual = close_loops(m, free, q);
  EXPECT_LT(residual, 1e-13);
  EXPECT_LT((q - q0).norm(), 1e-12);
  std::printf("torso box: Newton over the box's joints: |e| %.3g, |q - q0| %.3g\n", residual, (q - q0).norm());
}

// The scene's PD moves the waist and both arms towards targets away from q0 (and from the
// closure: the arms push against each other through the box) while the box's joints have
// no gain; for 5 s with the simulator's defaults (Dormand-Prince, rtol 1e-9, loops held
// at 100 rad/s) both loops stay closed within 1e-9, and the torso and the box did move.
TEST(TorsoHoldsBox, HandsHoldTheBoxWhileTheArmsMove) {
  const achd::cli::Scene s = scene();
  const achd::Model& m = s.model;
  ASSERT_TRUE(s.joint_control);
  const achd::JointControl& pd = s.control;
  int moved_targets = 0;
  for (int i = 0; i < m.num_rates(); ++i) {
    if (is_box_joint(m, i)) {
      EXPECT_EQ(pd.kp[i], 0) << m.bodies[i].joint_name;
      EXPECT_EQ(pd.kd[i], 0) << m.bodies[i].joint_name;
    } else {
      EXPECT_GT(pd.kp[i], 0) << m.bodies[i].joint_name;
      if (std::abs(pd.target[i] - s.q0[i]) > 0.1) ++moved_targets;
    }
  }
  EXPECT_GE(moved_targets, 5);

  achd::Simulator sim(m);  // the defaults, as the scene (it sets no integrator)
  sim.reset(s.q0, Eigen::VectorXd::Zero(m.num_rates()));
  sim.set_joint_control(pd);
  const int box = m.link_index("box");
  const achd::Vector3 box_start = achd::forward_kinematics(m, s.q0)[box].p;
  const int waist = m.joint_index("waist");
  double waist_max = 0;
  for (int k = 0; k < 50; ++k) {
    sim.run(100, 1e-3);
    waist_max = std::max(waist_max, std::abs(sim.q[waist]));
  }
  ASSERT_NEAR(sim.t, 5.0, 1e-9);
  const achd::Vector3 box_end = achd::forward_kinematics(m, sim.q)[box].p;
  for (int l = 0; l < 2; ++l) EXPECT_LE(sim.loop_drift(l), 1e-9) << m.loops[l].name;
  EXPECT_GT(waist_max, 0.2);                   // towards its 0.3 rad target
  EXPECT_GT((box_end - box_start).norm(), 0.05);  // the hands carried the box along
  std::printf("torso box, 5 s: loop drift %.3g m|rad (left), %.3g (right); waist %.4f rad; box moved %.4f m; "
              "substeps %lld\n",
              sim.loop_drift(0), sim.loop_drift(1), sim.q[waist], (box_end - box_start).norm(),
              static_cast<long long>(sim.substeps()));
}

// A second closed pose, away from q0's left-right symmetry: the box's joints set to
// (0.04, -0.03, 0.05) m and (0.25, 0.15, -0.1) rad, the waist at 0.2 rad, and the arms'
// 14 joints from a Newton solve (minimum-norm steps) that closes both loops from q0's arms.
Eigen::VectorXd tilted_pose(const achd::Model& m, const Eigen::VectorXd& q0) {
  Eigen::VectorXd q = q0;
  const std::vector<int> box = box_joints(m);
  const double values[6] = {0.04, -0.03, 0.05, 0.25, 0.15, -0.1};
  for (int k = 0; k < 6; ++k) q[box[k]] = values[k];
  q[m.joint_index("waist")] = 0.2;
  std::vector<int> arms;
  for (const char* side : {"left", "right"})
    for (int k = 1; k <= 7; ++k) arms.push_back(m.joint_index(std::string(side) + "_joint_" + std::to_string(k)));
  const double residual = close_loops(m, arms, q);
  EXPECT_LT(residual, 1e-13);
  return q;
}

// At rest with the torso's and arms' joints prescribed at qdd = 0, the box (free on its
// joints) is held by the hands alone. Each loop's block is
// alpha^T (a_hand(Q) - a_box(Q)) = beta with link a the hand and link b the box, and the
// robot receives -alpha nu at the point on link a and +alpha nu at Q on link b
// (case.hpp): Data::constraint_wrenches[l] = alpha nu = [f_l; n_l] (base axes, at Q_l)
// is the wrench hand l exerts on the box. The box at rest: sum_l f_l + m g = 0 and
// sum_l (n_l + (Q_l - c) x f_l) = 0 about its centre of mass c, so the hands push up with
// m_box 9.81 N through c. The same torques with every joint free (ff = the prescribed
// torques) leave the whole robot at rest with the same loop wrenches. At q0 and at a
// tilted, turned pose (tilted_pose), where the grip points' arms about c do not cancel
// by symmetry.
TEST(TorsoHoldsBox, BoxWeightShowsInBothHands) {
  const achd::cli::Scene s = scene();
  const achd::Model& m = s.model;
  const int n = m.num_rates();
  const int box = m.link_index("box");
  for (const Eigen::VectorXd& pose : {Eigen::VectorXd(s.q0), tilted_pose(m, s.q0)}) {
    SCOPED_TRACE(pose[m.joint_index("waist")] == 0 ? "q0" : "tilted");
    achd::Simulator closure(m);
    closure.reset(pose, Eigen::VectorXd::Zero(n));
    for (int l = 0; l < 2; ++l) ASSERT_LT(closure.loop_error(l), 1e-12);

    achd::Case c = achd::Case::zeros(m);
    c.q = pose;
    c.gravity = achd::Vector3(0, 0, -kG);
    c.prescribed.assign(n, false);
    c.qdd_given = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) c.prescribed[i] = !is_box_joint(m, i);
    achd::Data d(m);
    achd::hybrid_dynamics(m, d, c);
    ASSERT_EQ(d.constraint_wrenches.size(), 2u);  // no blocks of the case: the two loops
    EXPECT_LT(d.qdd.norm(), 1e-9);
    // With the arms prescribed, the 12 loop columns act on the box's 6 free joints only:
    // K has rank 6, and the solver's truncation takes the nu of least norm, the one with
    // no squeeze between the hands; what statics fixes, the sum on the box, is checked.
    EXPECT_EQ(d.rank, 6);

    const std::vector<achd::Transform> X = achd::forward_kinematics(m, c.q);
    const achd::Vector3 centre = X[box].p;  // the box's centre of mass is its frame's origin
    const auto balance = [&](const std::vector<achd::Vector6>& w, achd::Vector3& force, achd::Vector3& moment) {
      force.setZero();
      moment.setZero();
      for (int l = 0; l < 2; ++l) {
        const achd::Vector3 Q = (X[box] * m.loops[l].frame_b).p;
        const achd::Vector3 f = w[l].head<3>(), torque = w[l].tail<3>();
        force += f;
        moment += torque + (Q - centre).cross(f);
      }
    };
    achd::Vector3 force, moment;
    balance(d.constraint_wrenches, force, moment);
    EXPECT_LT((force - achd::Vector3(0, 0, kBoxMass * kG)).norm(), 1e-6) << force.transpose();
    EXPECT_LT(moment.norm(), 1e-6) << moment.transpose();
    // Each hand carries part of the weight.
    const double left_up = d.constraint_wrenches[0][2], right_up = d.constraint_wrenches[1][2];
    EXPECT_GT(left_up, 0.1 * kBoxMass * kG);
    EXPECT_GT(right_up, 0.1 * kBoxMass * kG);
    std::printf("torso box at rest (%s): hands lift %.9f N (left %.6f N, right %.6f N; m g = %.9f N), moment "
                "about the centre %.3g N m\n",
                pose[m.joint_index("waist")] == 0 ? "q0" : "tilted", force.z(), left_up, right_up, kBoxMass * kG,
                moment.norm());

    // Every joint free, driven by the torques the prescribed solve found.
    achd::Case free = achd::Case::zeros(m);
    free.q = pose;
    free.gravity = c.gravity;
    free.ff_torques = d.prescribed_torques;
    achd::Data d_free(m);
    achd::hybrid_dynamics(m, d_free, free);
    EXPECT_EQ(d_free.rank, 12);  // 21 free joints: the loops' 12 columns are independent
    EXPECT_LT(d_free.qdd.norm(), 1e-9) << d_free.qdd.transpose();
    achd::Vector3 force_free, moment_free;
    balance(d_free.constraint_wrenches, force_free, moment_free);
    EXPECT_LT((force_free - achd::Vector3(0, 0, kBoxMass * kG)).norm(), 1e-6) << force_free.transpose();
    EXPECT_LT(moment_free.norm(), 1e-6) << moment_free.transpose();
    for (int l = 0; l < 2; ++l)
      EXPECT_LT((d_free.constraint_wrenches[l] - d.constraint_wrenches[l]).norm(), 1e-6) << m.loops[l].name;
  }
}
