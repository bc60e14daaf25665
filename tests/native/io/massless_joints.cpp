// A joint whose link and every link after it carry no mass moves nothing: the default load
// holds it (at 0, or the middle of its limits when 0 is outside them), exactly as
// --lock does, with a warning naming it, why, and the value; --inertia strict refuses it
// and --inertia repair gives it a floor mass. The robot then solves and simulates with
// finite numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "achd/achd.hpp"

namespace achd::test {
namespace {

const char* kMass =
    "<inertial><mass value='2'/><origin xyz='0.3 0 0'/>"
    "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.02' iyz='0' izz='0.02'/></inertial>";

// An arm (revolute about y, its mass 0.3 m out along x) whose palm, fixed to it, carries
// two massless prismatic fingers: 'finger_a' with limits [0, 0.04] and a massless joint
// 'nail' after it, 'finger_b' with limits [0.01, 0.04] (0 outside them).
std::string gripper() {
  return "<robot name='gripper'><link name='base'/><link name='arm'>" + std::string(kMass) +
         "</link><link name='palm'/><link name='a'/><link name='a_nail'/><link name='b'/>"
         "<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><axis xyz='0 1 0'/>"
         "<limit lower='-3' upper='3' effort='10' velocity='1'/></joint>"
         "<joint name='wrist' type='fixed'><parent link='arm'/><child link='palm'/><origin xyz='0.6 0 0'/></joint>"
         "<joint name='finger_a' type='prismatic'><parent link='palm'/><child link='a'/><axis xyz='0 1 0'/>"
         "<limit lower='0' upper='0.04' effort='1' velocity='1'/></joint>"
         "<joint name='nail' type='revolute'><parent link='a'/><child link='a_nail'/><origin xyz='0.05 0 0'/>"
         "<axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint>"
         "<joint name='finger_b' type='prismatic'><parent link='palm'/><child link='b'/><axis xyz='0 -1 0'/>"
         "<limit lower='0.01' upper='0.04' effort='1' velocity='1'/></joint></robot>";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::map<std::string, double> locked_values(const Model& model) {
  std::map<std::string, double> out;
  for (const LockedJoint& l : model.locked_joints) out[l.name] = l.value;
  return out;
}

// Loaded with the defaults: the three massless joints held, each with its warning, and
// the model is the one --lock gives (same bodies, same link frames).
TEST(MasslessJoints, TheDefaultHoldsAJointThatMovesNoMassAndSaysSo) {
  const Model model = load_urdf_string(gripper(), "", "");
  ASSERT_EQ(model.num_rates(), 1);
  EXPECT_EQ(model.bodies[0].joint_name, "shoulder");
  const std::map<std::string, double> held = locked_values(model);
  ASSERT_EQ(held.size(), 3u);
  EXPECT_EQ(held.at("finger_a"), 0.0);
  EXPECT_EQ(held.at("nail"), 0.0);
  EXPECT_EQ(held.at("finger_b"), 0.025);  // the middle of [0.01, 0.04]
  // one warning per massless subtree: 'nail', after 'finger_a', is told in finger_a's
  ASSERT_EQ(model.warnings.size(), 2u);
  for (const char* name : {"finger_a", "finger_b"}) {
    SCOPED_TRACE(name);
    int said = 0;
    for (const std::string& w : model.warnings)
      if (w.rfind(std::string("joint '") + name + "' moves nothing: its link and every link after it carry no mass",
                  0) == 0) {
        ++said;
        EXPECT_TRUE(contains(w, "the inertia option 'repair' (CLI --inertia repair) gives it a floor mass")) << w;
        EXPECT_TRUE(contains(w, "'strict' refuses it")) << w;
      }
    EXPECT_EQ(said, 1);
  }
  for (const std::string& w : model.warnings) {
    if (contains(w, "'finger_b'")) EXPECT_TRUE(contains(w, "locked at 0.025 (as --lock finger_b=0.025 does)")) << w;
    if (contains(w, "'finger_a'"))
      EXPECT_TRUE(contains(w, "; the 1 joint after it ('nail') moves nothing either and is locked the same way")) << w;
  }

  UrdfOptions by_hand;
  by_hand.locked = {{"finger_a", 0}, {"nail", 0}, {"finger_b", 0.025}};
  const Model locked = load_urdf_string(gripper(), "", "", by_hand);
  EXPECT_TRUE(locked.warnings.empty());
  ASSERT_EQ(locked.num_links(), model.num_links());
  EXPECT_EQ(locked.bodies[0].inertia, model.bodies[0].inertia);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 0.4);
  const std::vector<Transform> a = forward_kinematics(model, q), b = forward_kinematics(locked, q);
  for (int l = 0; l < model.num_links(); ++l) {
    SCOPED_TRACE(model.links[l].name);
    EXPECT_EQ(a[l].p, b[l].p);
    EXPECT_EQ(a[l].R, b[l].R);
  }
  // finger_b's link stands 0.025 m along -y from the palm.
  const Transform palm = a[model.link_index("palm")], finger = a[model.link_index("b")];
  EXPECT_NEAR((palm.R.transpose() * (finger.p - palm.p)).y(), -0.025, 1e-15);
}

// The other inertia policies keep their meaning: strict refuses the joint, naming it and the
// ways out; repair gives floor masses until every joint moves something.
TEST(MasslessJoints, StrictRefusesItAndRepairGivesItMass) {
  UrdfOptions strict;
  strict.inertia = InertiaPolicy::Strict;
  try {
    load_urdf_string(gripper(), "", "", strict);
    ADD_FAILURE() << "strict loaded a joint that moves nothing";
  } catch (const Error& e) {
    const std::string why = e.what();
    EXPECT_TRUE(contains(why, "URDF: joint 'finger_b' moves nothing: the links after it have no mass")) << why;
    EXPECT_TRUE(contains(why, "--inertia repair")) << why;
    EXPECT_TRUE(contains(why, "--lock finger_b=VALUE")) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
  }
  UrdfOptions repair;
  repair.inertia = InertiaPolicy::Repair;
  const Model repaired = load_urdf_string(gripper(), "", "", repair);
  EXPECT_EQ(repaired.num_rates(), 4);
  EXPECT_TRUE(repaired.locked_joints.empty());
  // (nail's floor mass is what finger_a then moves: two floors)
  ASSERT_EQ(repaired.warnings.size(), 2u);
  EXPECT_EQ(repaired.warnings[0].rfind("joint 'finger_b' moved nothing", 0), 0u) << repaired.warnings[0];
  EXPECT_EQ(repaired.warnings[1].rfind("joint 'nail' moved nothing", 0), 0u) << repaired.warnings[1];
}

// Held by the default, the gripper swings under gravity for 1 s: every step finite, the arm
// falling from horizontal.
TEST(MasslessJoints, AGripperWithItsFingersHeldSimulatesFinite) {
  const Model model = load_urdf_string(gripper(), "", "");
  Simulator sim(model);
  sim.reset(default_pose(model), Eigen::VectorXd::Zero(model.num_rates()));
  for (int k = 0; k < 1000; ++k) {
    sim.step(1e-3);
    ASSERT_TRUE(sim.q.allFinite() && sim.qd.allFinite()) << "step " << k;
  }
  EXPECT_GT(std::abs(sim.q[0]), 0.1);  // it swung
  EXPECT_LE(std::abs(sim.q[0]), 3.0);
}

// A chain whose tip link moves no mass: the path's massless joints are held too, and the
// chain keeps its tip (finger_b, a side branch, held where it is told: 0 is outside its
// limits).
TEST(MasslessJoints, AChainToAMasslessTipHoldsItsMasslessJoints) {
  UrdfOptions options;
  options.locked = {{"finger_b", 0.02}};
  const Model chain = load_urdf_string(gripper(), "base", "a_nail", options);
  EXPECT_EQ(chain.num_rates(), 1);
  EXPECT_EQ(chain.tip_name, "a_nail");
  EXPECT_EQ(chain.links.back().name, "a_nail");
  const std::map<std::string, double> held = locked_values(chain);
  EXPECT_EQ(held.at("finger_a"), 0.0);
  EXPECT_EQ(held.at("nail"), 0.0);
  EXPECT_EQ(held.at("finger_b"), 0.02);
  EXPECT_EQ(chain.warnings.size(), 1u);  // finger_a's, telling nail's too
  // Not told: the side joint is held at the middle of its limits, 0 being outside them.
  const Model untold = load_urdf_string(gripper(), "base", "a_nail");
  EXPECT_EQ(locked_values(untold).at("finger_b"), 0.025);
}

// A long massless chain after a massive link: every joint locked, one warning for them
// all naming the first few, and the load stays linear in the joints (20000 of them load
// in well under a second here; a quadratic pass took minutes).
TEST(MasslessJoints, ALongMasslessChainIsOneWarning) {
  const int n = 20000;
  std::string urdf = "<robot name='long'><link name='base'/><link name='arm'>" + std::string(kMass) + "</link>"
                     "<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/>"
                     "<axis xyz='0 1 0'/><limit lower='-3' upper='3' effort='10' velocity='1'/></joint>";
  std::string parent = "arm";
  for (int i = 0; i < n; ++i) {
    const std::string link = "l" + std::to_string(i);
    urdf += "<link name='" + link + "'/><joint name='j" + std::to_string(i) + "' type='revolute'><parent link='" +
            parent + "'/><child link='" + link + "'/><axis xyz='0 0 1'/>"
            "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>";
    parent = link;
  }
  urdf += "</robot>";
  const Model model = load_urdf_string(urdf, "", "");
  EXPECT_EQ(model.num_rates(), 1);
  EXPECT_EQ(model.locked_joints.size(), static_cast<std::size_t>(n));
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_TRUE(contains(model.warnings[0], "joint 'j0' moves nothing")) << model.warnings[0].substr(0, 300);
  EXPECT_TRUE(contains(model.warnings[0], "the 19999 joints after it ('j1', 'j2', 'j3' and 19996 more) move nothing"))
      << model.warnings[0].substr(0, 400);
}

}  // namespace
}  // namespace achd::test
