// SRDF poses and the PD controller given by two numbers:
//   - read_srdf_poses / srdf_pose_q read a robot's group_states as q (ANYmal C's
//     "standing": its root_joint entry as the floating base's pose, joints by name, the
//     others at 0 or mid-limits), and name what is wrong in a malformed file;
//   - JointControl{frequency, damping_ratio} gives kp_i = M_ii (2 pi f)^2 and
//     kd_i = 2 zeta M_ii (2 pi f) on a fixed arm (M from CRBA), and larger gains where a
//     held foot makes a joint move the rest of the robot;
//   - the hold feed-forward keeps an arm exactly at its target under gravity, where the
//     same PD without it sags.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "achd/achd.hpp"

namespace achd::test {
namespace {

const std::string kSource = ACHD_SOURCE_DIR;
const std::string kAnymal = kSource + "/robots/example-robot-data/anymal_c_simple_description/";

std::string read(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  std::string s;
  char buf[4096];
  for (std::size_t n; f && (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, n);
  if (f) std::fclose(f);
  return s;
}

void expect_error(const std::function<void()>& f, const std::string& expected) {
  try {
    f();
    ADD_FAILURE() << "no error; expected " << expected;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

TEST(SrdfPoses, AnymalStandingPoseAsQ) {
  UrdfOptions floating;
  floating.floating = true;
  const Model m = load_urdf_file(kAnymal + "urdf/anymal.urdf", "", "", floating);
  const std::vector<SrdfPose> poses = read_srdf_poses(read(kAnymal + "srdf/anymal.srdf"), "anymal.srdf");
  const SrdfPose& standing = find_srdf_pose(poses, "standing", "anymal.srdf");
  const Eigen::VectorXd q = srdf_pose_q(m, standing);
  ASSERT_EQ(q.size(), m.num_positions());
  EXPECT_EQ(q[2], 0.528);
  EXPECT_EQ(q[6], 1.0);
  EXPECT_EQ(q[m.position_index(m.joint_index("LF_HAA"))], -0.1);
  EXPECT_EQ(q[m.position_index(m.joint_index("LF_HFE"))], 0.7);
  // On a fixed base the root_joint entry is not a joint of the model: skipped.
  const Model fixed = load_urdf_file(kAnymal + "urdf/anymal.urdf", "", "");
  EXPECT_EQ(srdf_pose_q(fixed, standing)[fixed.joint_index("LF_KFE")], -1.0);
  expect_error([&] { find_srdf_pose(poses, "sitting", "anymal.srdf"); },
               "anymal.srdf: no group_state 'sitting' (it has 'standing')");
}

TEST(SrdfPoses, MalformedFilesAreNamedErrors) {
  const Model m = load_urdf_file(kAnymal + "urdf/anymal.urdf", "", "", [] {
    UrdfOptions o;
    o.floating = true;
    return o;
  }());
  auto pose_of = [&](const std::string& body) {
    const auto poses = read_srdf_poses("<robot>" + body + "</robot>", "x.srdf");
    return srdf_pose_q(m, poses.at(0));
  };
  expect_error([&] { read_srdf_poses("<robot><group_state/></robot>", "x.srdf"); }, "x.srdf: a <group_state> has no name");
  expect_error([&] { read_srdf_poses("<robot><group_state name='a'/><group_state name='a'/></robot>", "x.srdf"); },
               "x.srdf: group_state 'a' is defined twice");
  expect_error([&] { pose_of("<group_state name='a'><joint name='LF_HAA' value='a b'/></group_state>"); },
               "x.srdf: group_state 'a', joint 'LF_HAA': value 'a b' is not a list of finite numbers");
  expect_error([&] { pose_of("<group_state name='a'><joint name='LF_HAA' value='nan'/></group_state>"); },
               "x.srdf: group_state 'a', joint 'LF_HAA': value 'nan' is not a list of finite numbers");
  expect_error([&] { pose_of("<group_state name='a'><joint name='LF_HAA' value='1 2'/></group_state>"); },
               "group_state 'a', joint 'LF_HAA': expected one number, got 2");
  expect_error([&] { pose_of("<group_state name='a'><joint name='root_joint' value='0 0 1'/></group_state>"); },
               "group_state 'a', joint 'root_joint': a floating base takes 7 numbers (x y z qx qy qz qw), got 3");
  expect_error([&] { pose_of("<group_state name='a'><joint name='root_joint' value='0 0 1 0 0 0 0'/></group_state>"); },
               "group_state 'a', joint 'root_joint': the quaternion (qx qy qz qw) is zero");
  expect_error([&] { read_srdf_poses("<robot><group_state", "x.srdf"); },
               "x.srdf: cannot parse SRDF: Failed to read Element name");
  std::string deep;
  for (int k = 0; k < 200; ++k) deep += "<a>";
  expect_error([&] { read_srdf_poses(deep, "x.srdf"); },
               "x.srdf: cannot parse SRDF: elements nested more than 100 deep");
  // A quaternion of any length is normalised.
  const Eigen::VectorXd q = pose_of("<group_state name='a'><joint name='root_joint' value='0 0 1 0 0 0 1e-200'/></group_state>");
  EXPECT_EQ(q[6], 1.0);
}

TEST(FrequencyControl, GainsFollowTheInertiaEachJointMoves) {
  const Model arm = load_urdf_file(kSource + "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  Simulator sim(arm);
  JointControl c;
  c.target = Eigen::VectorXd::Constant(7, 0.3);
  c.frequency = 5;
  c.damping_ratio = 0.7;
  sim.set_joint_control(c);
  const Eigen::VectorXd M = crba(arm, c.target).diagonal();
  const double w = 2 * M_PI * 5;
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(sim.joint_control().kp[i], M[i] * w * w, 1e-9 * M[i] * w * w);
    EXPECT_NEAR(sim.joint_control().kd[i], 2 * 0.7 * M[i] * w, 1e-9 * M[i] * w);
  }
  // A floating quadruped: with a foot held, that leg's knee moves the rest of the robot.
  UrdfOptions floating;
  floating.floating = true;
  const Model quad = load_urdf_file(kSource + "/robots/quadruped.urdf", "", "", floating);
  Simulator standing(quad);
  Eigen::VectorXd q0 = default_pose(quad);
  q0[2] = 0.3;
  standing.reset(q0, Eigen::VectorXd::Zero(quad.num_rates()));
  JointControl g;
  g.target = q0;
  g.frequency = 5;
  g.damping_ratio = 1;
  standing.set_joint_control(g);
  const int knee = quad.joint_index("lf_kfe");
  const double free_kp = standing.joint_control().kp[knee];
  for (int k = 0; k < 3; ++k) standing.set_direction(quad.link_index("lf_foot"), k, DirectionMode::Hold);
  EXPECT_GT(standing.joint_control().kp[knee], 20 * free_kp);
  EXPECT_EQ(standing.joint_control().kp[0], 0.0);  // the free joint takes none
  // Named errors.
  JointControl bad = c;
  bad.frequency = 0;
  expect_error([&] { sim.set_joint_control(bad); }, "joint control: frequency must be finite and > 0 (Hz), got 0");
  bad.frequency = 5;
  bad.damping_ratio = std::nan("");
  expect_error([&] { sim.set_joint_control(bad); }, "joint control: damping_ratio must be finite and >= 0, got NaN");
  bad.damping_ratio = 1;
  bad.frequency = 1e300;
  expect_error([&] { sim.set_joint_control(bad); },
               "joint control: the gains of joint 'lwr_joint_1' at frequency 1e+300 Hz are not finite");
  bad = c;
  bad.kp = bad.kd = Eigen::VectorXd::Constant(7, 1.0);
  expect_error([&] { sim.set_joint_control(bad); },
               "joint control: give kp and kd, or frequency and damping_ratio, not both");
}

// The LWR at a bent pose under gravity, 2 s of the default integrator: with the hold
// feed-forward the joints stay at the target (the PD sees no error); without it the same
// gains let the arm sag by the gravity torque over kp.
TEST(FrequencyControl, HoldFeedForwardKeepsTheTargetUnderGravity) {
  const Model arm = load_urdf_file(kSource + "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  const Eigen::VectorXd target = (Eigen::VectorXd(7) << 0.3, 0.9, -0.2, -1.2, 0.4, 0.8, 0.1).finished();
  double error[2];
  for (bool hold : {true, false}) {
    Simulator sim(arm);
    sim.reset(target, Eigen::VectorXd::Zero(7));
    JointControl c;
    c.target = target;
    c.frequency = 5;
    c.damping_ratio = 1;
    c.hold = hold;
    sim.set_joint_control(c);
    for (int k = 0; k < 2000; ++k) sim.step(1e-3);
    error[hold ? 0 : 1] = (sim.q - target).cwiseAbs().maxCoeff();
  }
  std::printf("LWR 2 s: |q - target| %.3g with the hold feed-forward, %.3g without\n", error[0], error[1]);
  EXPECT_LE(error[0], 1e-9);
  EXPECT_GE(error[1], 1e-3);
}

}  // namespace
}  // namespace achd::test
