// Model validation on trees: a joint moves nothing (D = S^T IA S = 0) exactly when every
// branch after it can take its motion up; a branch that cannot makes the joint move
// something, wherever the branches sit in the body order.
#include <string>

#include <gtest/gtest.h>

#include "achd/achd.hpp"

namespace achd {
namespace {

const char* kMass =
    "<inertial><mass value='1.5'/><origin xyz='0.05 0.02 0.1'/>"
    "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.012' iyz='0' izz='0.008'/></inertial>";

std::string joint(const std::string& name, const std::string& parent, const std::string& child,
                  const std::string& xyz, const std::string& axis) {
  return "<joint name='" + name + "' type='revolute'><parent link='" + parent + "'/><child link='" + child +
         "'/><origin xyz='" + xyz + "'/><axis xyz='" + axis + "'/><limit lower='-2' upper='2' effort='1' velocity='1'/></joint>";
}

std::string link(const std::string& name, bool mass) {
  return "<link name='" + name + "'>" + (mass ? std::string(kMass) : std::string()) + "</link>";
}

// j1 about z carries a massless link `hub`, from which two branches start: j2 about z on
// j1's axis (it turns its body as j1 would), and j3 about `axis3` at `xyz3`.
std::string hub(const std::string& xyz3, const std::string& axis3) {
  return "<robot name='hub'>" + link("base", false) + joint("j1", "base", "hub", "0 0 0.1", "0 0 1") +
         link("hub", false) + joint("j2", "hub", "a", "0 0 0.1", "0 0 1") + link("a", true) +
         joint("j3", "hub", "b", xyz3, axis3) + link("b", true) + "</robot>";
}

std::string load_error(const std::string& urdf, const UrdfOptions& options = {}) {
  try {
    load_urdf_string(urdf, "base", "", options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Both branches take j1's turn up (each has a joint on its axis): j1 moves nothing, though
// mass follows it, so the default does not hold it either.
TEST(TreeValidation, AJointWhoseEveryBranchTakesItsMotionUpMovesNothing) {
  const std::string why = load_error(hub("0 0 0.2", "0 0 1"));
  EXPECT_NE(why.find("URDF: joint 'j1' moves nothing"), std::string::npos) << why;
}

// The second branch turns about x, 0.2 m away: it cannot take j1's turn up, so j1 moves
// its body (the chain-only check looked at the first branch alone and refused j1).
TEST(TreeValidation, OneBranchThatCannotTakeTheMotionUpIsEnough) {
  EXPECT_EQ(load_error(hub("0.2 0 0", "1 0 0")), "");
  const Model m = load_urdf_string(hub("0.2 0 0", "1 0 0"), "base", "");
  ASSERT_EQ(m.num_rates(), 3);
  EXPECT_EQ(m.bodies[1].parent, 0);
  EXPECT_EQ(m.bodies[2].parent, 0);
}

// A massless leaf on one branch, a massive body on a sibling branch after it: the leaf's
// joint moves nothing (the chain-only check took the sibling for its child and let it
// pass); strict refuses it, the default holds it and the sibling moves.
TEST(TreeValidation, AMasslessLeafBeforeASiblingMovesNothing) {
  const std::string urdf = "<robot name='leaf'>" + link("base", false) + joint("empty", "base", "nothing", "0 0 0.1", "0 0 1") +
                           link("nothing", false) + joint("arm", "base", "mass", "0.3 0 0", "1 0 0") + link("mass", true) +
                           "</robot>";
  UrdfOptions strict;
  strict.inertia = InertiaPolicy::Strict;
  const std::string why = load_error(urdf, strict);
  EXPECT_NE(why.find("URDF: joint 'empty' moves nothing"), std::string::npos) << why;
  const Model m = load_urdf_string(urdf, "base", "");
  ASSERT_EQ(m.num_rates(), 1);
  EXPECT_EQ(m.bodies[0].joint_name, "arm");
  ASSERT_EQ(m.locked_joints.size(), 1u);
  EXPECT_EQ(m.locked_joints[0].name, "empty");
}

}  // namespace
}  // namespace achd
