// Why the URDFs of example-robot-data that once needed --inertia repair load as they do
// (real_robots.cpp checks the table): each is measured here, the option one still needs
// shown to be for a physical reason, not for a limit of the loader.
// - romeo.urdf: each hand is a <mimic> group (a leader and eleven followers) with no mass
//   anywhere, its leader's link included: coupling the fingers gives the group no mass,
//   so its motion is undefined; the default holds each hand by its leader, its followers at
//   their coupled positions, one warning per hand (strict refuses it, naming the group).
// - romeo_laas_small.urdf: LHipPitch_link's rotational inertia has a principal moment of
//   -0.0027 kg m^2, over ten thousand times the file's round-off: a genuine negative
//   moment, which still needs --inertia repair; its two massless grippers are held.
// - the three Bravo7 grippers: two massless fingers, independent joints (no <mimic>),
//   held by the default.
// And, on small trees, the cases of a coupled joint that moves nothing (a massless group
// held by its leader within every follower's limits, a massless follower of a leader that
// moves mass refused), a leader held with a cycle of <mimic>s, and a held leader whose
// follower's coupled position is outside the follower's limits.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <Eigen/Eigenvalues>

#include "achd/achd.hpp"

namespace achd::test {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(ACHD_SOURCE_DIR) / "robots" / "example-robot-data";

std::string path_of(const std::string& file) { return (kCorpus / file).string(); }

// The error of a load that must fail ("" if it loaded).
std::string load_error(const std::string& file, const UrdfOptions& options) {
  try {
    load_urdf_file(path_of(file), "", "", options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// At rest under gravity at its default pose: every output finite, gravity acting, and
// RNEA at the solved qdd gives back the joint torques (zero: no couplings, no constraints).
void expect_solves(const Model& model) {
  Case c = Case::zeros(model);
  c.q = default_pose(model);
  Data data(model);
  hybrid_dynamics(model, data, c);
  ASSERT_TRUE(data.qdd.allFinite());
  ASSERT_TRUE(data.joint_torques.allFinite());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.num_rates());
  const Eigen::VectorXd gravity_torques = rnea(model, c.q, zero, zero, c.gravity);
  ASSERT_GT(gravity_torques.cwiseAbs().maxCoeff(), 0.0);
  const Eigen::VectorXd tau = rnea(model, c.q, zero, data.qdd, c.gravity);
  EXPECT_LE(tau.cwiseAbs().maxCoeff(), 1e-8 * gravity_torques.cwiseAbs().maxCoeff());
  EXPECT_LE(data.joint_torques.cwiseAbs().maxCoeff(), 0.0);
}

int count_containing(const std::vector<std::string>& lines, const std::string& part) {
  int n = 0;
  for (const std::string& l : lines) n += contains(l, part);
  return n;
}

const char* kRomeo = "romeo_description/urdf/romeo.urdf";

// Romeo's hands: every link of a hand has mass 0, the leader's (RHand, LHand) too, and
// eleven <mimic> joints follow each leader. The default holds each hand by its leader at 0,
// one warning per hand naming the group, exactly as --lock RHand=0 --lock LHand=0 does.
TEST(RealRobotsOptions, RomeoHandsAreMasslessCoupledGroupsTheDefaultHolds) {
  const Model model = load_urdf_file(path_of(kRomeo), "", "");
  EXPECT_EQ(model.num_rates(), 55 - 24);  // the 24 hand joints held
  EXPECT_TRUE(model.couplings.empty());
  ASSERT_EQ(model.locked_joints.size(), 24u);
  for (const LockedJoint& l : model.locked_joints) EXPECT_EQ(l.value, 0.0) << l.name;
  for (const char* hand : {"RHand", "LHand"}) {
    SCOPED_TRACE(hand);
    const std::string h = hand;
    EXPECT_EQ(count_containing(model.warnings, "joint '" + h + "' and the 11 joints coupled to it (<mimic>) move "
                                               "nothing: their links and every link after them carry no mass"),
              1);
    EXPECT_EQ(count_containing(model.warnings, "'" + h + "' locked at 0 (as --lock " + h + "=0 does), each joint "
                                               "coupled to it at its multiplier times that plus its offset"),
              1);
  }
  UrdfOptions held;
  held.locked = {{"RHand", 0}, {"LHand", 0}};
  const Model by_hand = load_urdf_file(path_of(kRomeo), "", "", held);
  EXPECT_EQ(by_hand.warnings.size() + 2, model.warnings.size());
  ASSERT_EQ(by_hand.num_links(), model.num_links());
  const Eigen::VectorXd q = default_pose(model);
  const std::vector<Transform> a = forward_kinematics(model, q), b = forward_kinematics(by_hand, q);
  for (int l = 0; l < model.num_links(); ++l) {
    SCOPED_TRACE(model.links[l].name);
    EXPECT_EQ(a[l].p, b[l].p);
    EXPECT_EQ(a[l].R, b[l].R);
  }
  expect_solves(model);
}

// Held by their leaders, the hands stand where their couplings put them (each follower at
// multiplier * leader + offset, the thumbs' first joints at -1 times), exactly as when
// every hand joint is locked by name; the rest of Romeo then loads with the defaults, and
// solves.
TEST(RealRobotsOptions, RomeoLoadsWithItsHandsHeldByTheirLeaders) {
  UrdfOptions held;
  held.locked = {{"RHand", 0.5}, {"LHand", 0.25}};
  const Model model = load_urdf_file(path_of(kRomeo), "", "", held);
  EXPECT_EQ(model.num_rates(), 55 - 24);  // the 24 hand joints held
  EXPECT_TRUE(model.couplings.empty());
  EXPECT_EQ(count_containing(model.warnings, "moved nothing"), 0);
  ASSERT_EQ(model.locked_joints.size(), 24u);
  UrdfOptions named;
  named.mimic = MimicJoints::Independent;  // (the <mimic>s then say nothing)
  for (const LockedJoint& l : model.locked_joints) {
    SCOPED_TRACE(l.name);
    const double leader = l.name[0] == 'R' ? 0.5 : 0.25;
    const bool thumb1 = l.name == "RThumb1" || l.name == "LThumb1";
    EXPECT_EQ(l.value, thumb1 ? -leader : leader);
    named.locked[l.name] = l.value;
  }
  const Model by_name = load_urdf_file(path_of(kRomeo), "", "", named);
  ASSERT_EQ(by_name.num_links(), model.num_links());
  const Eigen::VectorXd q = default_pose(model);
  const std::vector<Transform> a = forward_kinematics(model, q), b = forward_kinematics(by_name, q);
  for (int l = 0; l < model.num_links(); ++l) {
    SCOPED_TRACE(model.links[l].name);
    ASSERT_EQ(model.links[l].name, by_name.links[l].name);
    EXPECT_LE((a[l].p - b[l].p).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LE((a[l].R - b[l].R).cwiseAbs().maxCoeff(), 1e-15);
  }
  expect_solves(model);
}

const char* kRomeoLaas = "romeo_description/urdf/romeo_laas_small.urdf";

// LHipPitch_link's <inertia> as the file writes it: one principal moment is -0.00272 kg
// m^2, far beyond what rounding the written digits can move an eigenvalue (Weyl: at most
// |E|_F, E the half units of the last digits), so it is a negative moment, not round-off
// of zero, and the default refuses the body it rides on; it is not the grippers' doing.
TEST(RealRobotsOptions, RomeoLaasSmallHipHasAGenuineNegativeMoment) {
  Matrix3 I;  // ixx="0.0390706" ixy="-2.41786e-05" ixz="0.0250104" iyy="0.0395116" iyz="0.000712271" izz="0.0122599"
  I << 0.0390706, -2.41786e-05, 0.0250104, -2.41786e-05, 0.0395116, 0.000712271, 0.0250104, 0.000712271, 0.0122599;
  const double least = Eigen::SelfAdjointEigenSolver<Matrix3>(I).eigenvalues()[0];
  EXPECT_NEAR(least, -0.00272042, 1e-8);
  const double r2 = 5e-8 * 5e-8, r11 = 5e-11 * 5e-11, r10 = 5e-10 * 5e-10;
  const double roundoff = std::sqrt(r2 + r2 + r2 + 2 * (r11 + r2 + r10));  // ixx iyy izz; 2 (ixy ixz iyz)
  EXPECT_LT(least, -1e4 * roundoff);
  // The default refuses the hip's body (the grippers, which it holds, are not why).
  const std::string why = load_error(kRomeoLaas, {});
  EXPECT_TRUE(contains(why, "link 'LHipPitch_link': spatial inertia is not positive semi-definite")) << why;
  EXPECT_TRUE(contains(why, "--inertia repair")) << why;
  // Repaired, each fix is a warning: the hips' moments and the grippers' floor masses.
  UrdfOptions repair;
  repair.inertia = InertiaPolicy::Repair;
  const Model model = load_urdf_file(path_of(kRomeoLaas), "", "", repair);
  // (the loader read the numbers above: the same moments)
  EXPECT_EQ(count_containing(model.warnings, "link 'LHipPitch_link': inertia repaired: principal moments "
                                             "-0.00272042, 0.0395126, 0.0540499 -> "),
            1);
  EXPECT_EQ(count_containing(model.warnings, "link 'RHipPitch_link': inertia repaired"), 1);
  EXPECT_EQ(count_containing(model.warnings, "joint 'l_gripper_joint' moved nothing"), 1);
  EXPECT_EQ(count_containing(model.warnings, "joint 'r_gripper_joint' moved nothing"), 1);
  expect_solves(model);
}

// The Bravo7 grippers: the two fingers are joints of their own (no <mimic>) whose links
// have no mass; the default holds both at 0, as --lock does, one warning each; strict
// refuses them and repair gives them floor masses.
TEST(RealRobotsOptions, Bravo7FingersAreIndependentMasslessJointsTheDefaultHolds) {
  for (const char* file : {"bravo7_description/urdf/bravo7_gripper.urdf",
                           "bluevolta_description/urdf/bluevolta_bravo7_gripper.urdf",
                           "falcon_description/urdf/falcon_bravo7_gripper.urdf"}) {
    SCOPED_TRACE(file);
    const Model model = load_urdf_file(path_of(file), "", "");
    EXPECT_EQ(model.num_rates(), 6);
    EXPECT_TRUE(model.couplings.empty());
    ASSERT_EQ(model.warnings.size(), 2u);
    for (const char* finger : {"bravo_finger1_joint", "bravo_finger2_joint"})
      EXPECT_EQ(count_containing(model.warnings, "joint '" + std::string(finger) +
                                                     "' moves nothing: its link and every link after it carry no "
                                                     "mass, so no torque moves it and its acceleration is undefined; "
                                                     "locked at 0 (as --lock " + finger + "=0 does)"),
                1);
    UrdfOptions held;
    held.locked = {{"bravo_finger1_joint", 0}, {"bravo_finger2_joint", 0}};
    const Model by_hand = load_urdf_file(path_of(file), "", "", held);
    EXPECT_TRUE(by_hand.warnings.empty());
    ASSERT_EQ(by_hand.num_rates(), model.num_rates());
    for (int i = 0; i < model.num_rates(); ++i) EXPECT_EQ(by_hand.bodies[i].inertia, model.bodies[i].inertia);
    expect_solves(model);
    UrdfOptions strict;
    strict.inertia = InertiaPolicy::Strict;
    const std::string why = load_error(file, strict);
    EXPECT_TRUE(contains(why, "joint 'bravo_finger2_joint' moves nothing: the links after it have no mass")) << why;
    EXPECT_FALSE(contains(why, "coupled")) << why;
    UrdfOptions repair;
    repair.inertia = InertiaPolicy::Repair;
    const Model repaired = load_urdf_file(path_of(file), "", "", repair);
    EXPECT_TRUE(repaired.couplings.empty());
    EXPECT_EQ(count_containing(repaired.warnings, "moved nothing"), 2);
  }
}

// A small tree: the leader 'lead' (link 'arm', mass `arm_mass`) and its follower 'follow'
// (q = 2 q_lead + 0.1, link 'finger' massless, limits [0, follow_upper]), and a joint
// 'other' of its own.
std::string coupled_tree(double arm_mass, double follow_upper) {
  const std::string inertial =
      "<inertial><mass value=\"" + std::to_string(arm_mass) +
      "\"/><origin xyz=\"0.2 0 0\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>";
  return R"(<robot name="r"><link name="base"/>
    <link name="arm">)" + (arm_mass > 0 ? inertial : std::string()) + R"(</link>
    <link name="finger"/>
    <link name="other_link"><inertial><mass value="1"/><origin xyz="0.2 0 0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
    <joint name="lead" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="follow" type="revolute"><parent link="arm"/><child link="finger"/><origin xyz="0.4 0 0"/>
      <axis xyz="0 0 1"/><limit lower="0" upper=")" + std::to_string(follow_upper) + R"(" effort="1" velocity="1"/>
      <mimic joint="lead" multiplier="2" offset="0.1"/></joint>
    <joint name="other" type="revolute"><parent link="base"/><child link="other_link"/><axis xyz="0 1 0"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </robot>)";
}

std::string string_error(const std::string& xml, const UrdfOptions& options) {
  try {
    load_urdf_string(xml, "", "", options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A massless follower of a leader with mass: the group moves something, but the coupled
// solve solves the uncoupled tree, where the follower moves nothing; said so, and the
// default does not hold it (holding it would break the coupling). A massless leader too:
// nothing defines the group's motion; strict says so, the default holds the group.
TEST(RealRobotsOptions, ACoupledJointThatMovesNothingNamesItsCase) {
  const std::string massive_leader = string_error(coupled_tree(1, 3), {});
  EXPECT_TRUE(contains(massive_leader, "joint 'follow' moves nothing: the links after it have no mass")) << massive_leader;
  EXPECT_TRUE(contains(massive_leader, "it is one of joint 'lead' and the 1 joint coupled to it (<mimic>), which move "
                                       "something, but the coupled solve still needs each coupled joint"))
      << massive_leader;
  UrdfOptions strict;
  strict.inertia = InertiaPolicy::Strict;
  const std::string massless = string_error(coupled_tree(0, 3), strict);
  EXPECT_TRUE(contains(massless, "joint 'follow' moves nothing, nor does any joint coupled with it: joint 'lead' and "
                                 "the 1 joint coupled to it (<mimic>) have no mass or inertia"))
      << massless;
  // An uncoupled massless joint keeps validate()'s message (strict), and is held by default.
  UrdfOptions independent = strict;
  independent.mimic = MimicJoints::Independent;
  const std::string alone = string_error(coupled_tree(1, 3), independent);
  EXPECT_TRUE(contains(alone, "joint 'follow' moves nothing")) << alone;
  EXPECT_FALSE(contains(alone, "coupled")) << alone;
  independent.inertia = InertiaPolicy::Accept;
  const Model held_alone = load_urdf_string(coupled_tree(1, 3), "", "", independent);
  ASSERT_EQ(held_alone.locked_joints.size(), 1u);
  EXPECT_EQ(held_alone.locked_joints[0].name, "follow");
  EXPECT_EQ(held_alone.locked_joints[0].value, 0.0);
}

// A massless group held by the default: its leader at 0 when that keeps the follower
// (2 lead + 0.1) within its limits; else at the middle of the leader values that do:
// follower limits [0, 0.05] allow lead in [-0.05, -0.025], so lead -0.0375, follow 0.025.
TEST(RealRobotsOptions, TheDefaultHoldsAMasslessGroupWithinEveryFollowersLimits) {
  const Model wide = load_urdf_string(coupled_tree(0, 3), "", "");
  ASSERT_EQ(wide.num_rates(), 1);
  EXPECT_EQ(wide.bodies[0].joint_name, "other");
  std::map<std::string, double> at;
  for (const LockedJoint& l : wide.locked_joints) at[l.name] = l.value;
  EXPECT_EQ(at.at("lead"), 0.0);
  EXPECT_EQ(at.at("follow"), 0.1);
  ASSERT_EQ(wide.warnings.size(), 1u);
  EXPECT_EQ(wide.warnings[0].rfind("joint 'lead' and the 1 joint coupled to it (<mimic>) move nothing", 0), 0u)
      << wide.warnings[0];
  const Model narrow = load_urdf_string(coupled_tree(0, 0.05), "", "");
  at.clear();
  for (const LockedJoint& l : narrow.locked_joints) at[l.name] = l.value;
  EXPECT_NEAR(at.at("lead"), -0.0375, 1e-15);
  EXPECT_NEAR(at.at("follow"), 0.025, 1e-15);
  EXPECT_TRUE(contains(narrow.warnings[0], "'lead' locked at -0.0375 (as --lock lead=-0.0375 does)"))
      << narrow.warnings[0];
  expect_solves(narrow);
}

// Holding a leader holds its follower at 2 * 0.3 + 0.1; a follower whose coupled position
// leaves its limits is refused, naming the leader and the coupling.
TEST(RealRobotsOptions, AHeldLeaderHoldsItsFollowerAtItsCoupledPosition) {
  UrdfOptions held;
  held.locked = {{"lead", 0.3}};
  const Model model = load_urdf_string(coupled_tree(0, 3), "", "", held);
  ASSERT_EQ(model.num_rates(), 1);
  EXPECT_EQ(model.bodies[0].joint_name, "other");
  ASSERT_EQ(model.locked_joints.size(), 2u);
  std::map<std::string, double> at;
  for (const LockedJoint& l : model.locked_joints) at[l.name] = l.value;
  EXPECT_EQ(at.at("lead"), 0.3);
  EXPECT_EQ(at.at("follow"), 2 * 0.3 + 0.1);
  const std::vector<Transform> poses = forward_kinematics(model, Eigen::VectorXd::Zero(1));
  const Transform finger = poses[model.link_index("finger")];
  const double angle = 0.3 + (2 * 0.3 + 0.1);  // both turn about base z
  EXPECT_NEAR(finger.R(0, 0), std::cos(angle), 1e-15);
  EXPECT_NEAR(finger.R(1, 0), std::sin(angle), 1e-15);
  EXPECT_NEAR(finger.p.x(), 0.4 * std::cos(0.3), 1e-15);
  expect_solves(model);
  // The follower's limits [0, 0.5] exclude 0.7.
  const std::string why = string_error(coupled_tree(0, 0.5), held);
  EXPECT_TRUE(contains(why, "locked joint 'follow': value 0.7 is outside its limits [0, 0.5] (it follows joint "
                            "'lead', which is held: 2 times its value plus 0.1)"))
      << why;
  // Named by the user, a follower's own value stands.
  held.locked["follow"] = 0.2;
  const Model named = load_urdf_string(coupled_tree(0, 3), "", "", held);
  int follows = 0;
  for (const LockedJoint& l : named.locked_joints)
    if (l.name == "follow") {
      ++follows;
      EXPECT_EQ(l.value, 0.2);
    }
  EXPECT_EQ(follows, 1);
}

// <mimic>s that follow each other round a cycle, or in a long chain: looking for a held
// leader ends.
TEST(RealRobotsOptions, ACycleOfMimicsEndsTheSearchForAHeldLeader) {
  const std::string link = R"(<inertial><mass value="1"/><origin xyz="0.2 0 0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>)";
  const std::string xml = R"(<robot name="r"><link name="base"/><link name="a">)" + link +
                          R"(</link><link name="b">)" + link + R"(</link>
    <joint name="ja" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="jb"/></joint>
    <joint name="jb" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.4 0 0"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="ja"/></joint></robot>)";
  UrdfOptions held;
  held.locked = {{"jb", 0.5}};  // ja follows jb: held with it, nothing is left to move
  const std::string why = string_error(xml, held);
  EXPECT_TRUE(contains(why, "has no movable joint")) << why;
  // A chain of 5000 joints, each following the one before it (q_k = q_(k-1) + 1e-4), the
  // first held at 0.25: all held, each where the chain of couplings puts it, and one
  // joint of its own left to move; the walk up the leaders neither recurses nor repeats.
  std::string chain = R"(<robot name="r"><link name="base"/>)" + std::string("<link name=\"l0\">") + link + "</link>";
  std::string joints;
  for (int k = 1; k <= 5000; ++k) {
    const std::string me = std::to_string(k), before = std::to_string(k - 1);
    chain += "<link name=\"l" + me + "\">" + link + "</link>";
    joints += "<joint name=\"j" + me + "\" type=\"continuous\"><parent link=\"l" + before + "\"/><child link=\"l" + me +
              "\"/><origin xyz=\"0.1 0 0\"/><axis xyz=\"0 0 1\"/>" +
              (k > 1 ? "<mimic joint=\"j" + before + "\" multiplier=\"1\" offset=\"0.0001\"/>" : std::string()) +
              "</joint>";
  }
  chain += R"(<link name="free">)" + link + R"(</link><joint name="free_joint" type="continuous"><parent link="base"/>
    <child link="free"/><axis xyz="0 1 0"/></joint><joint name="j0" type="fixed"><parent link="base"/><child link="l0"/></joint>)" +
           joints + "</robot>";
  UrdfOptions first_held;
  first_held.locked = {{"j1", 0.25}};
  const Model long_chain = load_urdf_string(chain, "", "", first_held);
  ASSERT_EQ(long_chain.num_rates(), 1);
  ASSERT_EQ(long_chain.locked_joints.size(), 5000u);
  double expected = 0.25;
  for (int k = 1; k <= 5000; ++k) {
    const LockedJoint& l = long_chain.locked_joints[k - 1];
    ASSERT_EQ(l.name, "j" + std::to_string(k));
    if (k > 1) expected = expected + 0.0001;
    ASSERT_EQ(l.value, expected) << l.name;
  }
  // Neither held: the search ends; the load ends (loaded or refused, not hung).
  try {
    load_urdf_string(xml, "", "", {});
  } catch (const Error&) {
  }
}

}  // namespace
}  // namespace achd::test
