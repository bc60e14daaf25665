// The URDF loader on trees: whole trees below a root (depth-first bodies, every link), and
// chains whose side branches are merged into the bodies they hang from (fixed links, locked
// joints) or ignored as KDL does; the tree robots of robots/index.json.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "achd/achd.hpp"
#include "robot_index.hpp"

namespace achd {
namespace {

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string v3(const Vector3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

struct Inertial {
  double mass = 0;
  Vector3 com = Vector3::Zero();
  Matrix3 I = Matrix3::Zero();  // at the centre of mass, link axes
};

std::string link(const std::string& name, const Inertial& in) {
  const Matrix3& I = in.I;
  return "<link name='" + name + "'><inertial><origin xyz='" + v3(in.com) + "'/><mass value='" + num(in.mass) +
         "'/><inertia ixx='" + num(I(0, 0)) + "' ixy='" + num(I(0, 1)) + "' ixz='" + num(I(0, 2)) + "' iyy='" +
         num(I(1, 1)) + "' iyz='" + num(I(1, 2)) + "' izz='" + num(I(2, 2)) + "'/></inertial></link>";
}

std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const Vector3& xyz, const Vector3& rpy, const Vector3& axis = Vector3::UnitZ(),
                  const std::string& extra = "") {
  return "<joint name='" + name + "' type='" + type + "'><parent link='" + parent + "'/><child link='" + child +
         "'/><origin xyz='" + v3(xyz) + "' rpy='" + v3(rpy) + "'/><axis xyz='" + v3(axis) +
         "'/><limit lower='-2' upper='2' effort='10' velocity='3'/>" + extra + "</joint>";
}

Inertial box(double m, double a, double b, double c, const Vector3& com) {
  Inertial in{m, com, Matrix3::Zero()};
  in.I.diagonal() << m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b);
  return in;
}

// Two inertials rigidly combined in the first one's frame; `X` places the second's frame.
Inertial combine(const Inertial& a, const Inertial& b_local, const Matrix3& R, const Vector3& p) {
  Inertial b{b_local.mass, R * b_local.com + p, R * b_local.I * R.transpose()};
  Inertial out;
  out.mass = a.mass + b.mass;
  out.com = (a.mass * a.com + b.mass * b.com) / out.mass;
  const Inertial& b_ref = b;
  for (const Inertial* x : {&a, &b_ref}) {
    const Vector3 d = x->com - out.com;
    out.I += x->I + x->mass * (d.squaredNorm() * Matrix3::Identity() - d * d.transpose());
  }
  return out;
}

// URDF's fixed-axis roll, pitch, yaw.
Matrix3 rpy_matrix(const Vector3& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Vector3::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Vector3::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Vector3::UnitX()))
      .toRotationMatrix();
}

const Inertial kLink1 = box(2.0, 0.3, 0.06, 0.06, Vector3(0.15, 0, 0));
const Inertial kLink2 = box(1.2, 0.25, 0.05, 0.05, Vector3(0.12, 0.01, 0));
const Inertial kCamera = box(0.4, 0.08, 0.1, 0.05, Vector3(0.01, 0.02, 0.015));
const Vector3 kJ2(0.3, 0, 0), kJ2Rpy(0.4, 0, 0), kTip(0.25, 0, 0);

// base -> j1 -> link1 -> j2 -> link2 -> tool (fixed), and `side` (more links and joints
// below link1 or link2) inserted after link1.
std::string arm(const std::string& side, const Inertial& link1 = kLink1) {
  return "<robot name='arm'><link name='base'/>" + joint("j1", "revolute", "base", "link1", Vector3(0, 0, 0.2), Vector3::Zero(), Vector3::UnitY()) +
         link("link1", link1) + side +
         joint("j2", "revolute", "link1", "link2", kJ2, kJ2Rpy, Vector3::UnitZ()) + link("link2", kLink2) +
         joint("tool_joint", "fixed", "link2", "tool", kTip, Vector3::Zero()) + "<link name='tool'/></robot>";
}

// A camera on link1 behind a fixed joint at (xyz, rpy).
std::string camera_on_link1(const Vector3& xyz, const Vector3& rpy) {
  return joint("camera_joint", "fixed", "link1", "camera", xyz, rpy) + link("camera", kCamera);
}

// The acceleration of the chain with every input nonzero and the tip held along two directions.
Eigen::VectorXd solve(const Model& m) {
  Case c = Case::zeros(m);
  c.q << 0.3, -0.7;
  c.qd = Eigen::Vector2d(0.5, -0.4);
  c.ff_torques = Eigen::Vector2d(1.5, -0.3);
  c.alpha = ConstraintMatrix::Zero(6, 1);
  c.alpha(2, 0) = 1;
  c.beta = ConstraintVector::Constant(1, 0.2);
  Data d(m);
  hybrid_dynamics(m, d, c, Options{});
  return d.qdd;
}

double rel(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

void expect_same_model(const Model& a, const Model& b) {  // bit for bit
  ASSERT_EQ(a.num_rates(), b.num_rates());
  ASSERT_EQ(a.num_links(), b.num_links());
  EXPECT_EQ(a.root_name, b.root_name);
  EXPECT_EQ(a.tip_name, b.tip_name);
  for (int i = 0; i < a.num_rates(); ++i) {
    const Body &x = a.bodies[i], &y = b.bodies[i];
    EXPECT_EQ(x.joint_name, y.joint_name);
    EXPECT_EQ(x.link_name, y.link_name);
    EXPECT_EQ(x.parent, y.parent);
    EXPECT_EQ(x.type, y.type);
    EXPECT_TRUE(x.X_tree.R == y.X_tree.R && x.X_tree.p == y.X_tree.p) << x.joint_name;
    EXPECT_TRUE(x.inertia == y.inertia) << x.joint_name;
    EXPECT_EQ(x.damping, y.damping);
    EXPECT_EQ(x.limits.lower, y.limits.lower);
    EXPECT_EQ(x.limits.upper, y.limits.upper);
  }
  for (int l = 0; l < a.num_links(); ++l) {
    EXPECT_EQ(a.links[l].name, b.links[l].name);
    EXPECT_EQ(a.links[l].body, b.links[l].body);
    EXPECT_TRUE(a.links[l].offset.R == b.links[l].offset.R && a.links[l].offset.p == b.links[l].offset.p)
        << a.links[l].name;
  }
}

// Bodies in depth-first order: each body's subtree (the bodies it is an ancestor of) is the
// range right after it; links after the root with parents before children.
void expect_depth_first(const Model& m) {
  const int n = m.num_rates();
  auto below = [&](int j, int i) {  // j in the subtree of i
    for (int k = j; k >= 0; k = m.bodies[k].parent)
      if (k == i) return true;
    return false;
  };
  for (int i = 0; i < n; ++i) {
    EXPECT_LT(m.bodies[i].parent, i);
    int end = i + 1;
    while (end < n && below(end, i)) ++end;
    for (int j = end; j < n; ++j) EXPECT_FALSE(below(j, i)) << m.bodies[j].joint_name << " below " << m.bodies[i].joint_name;
  }
  for (int l = 0; l < m.num_links(); ++l)
    if (m.links[l].body >= 0) EXPECT_GE(l, m.link_index(m.bodies[m.links[l].body].link_name));
}

std::vector<int> parents(const Model& m) {
  std::vector<int> p;
  for (const Body& b : m.bodies) p.push_back(b.parent);
  return p;
}

std::vector<std::string> joint_names(const Model& m) {
  std::vector<std::string> out;
  for (const Body& b : m.bodies) out.push_back(b.joint_name);
  return out;
}

std::string robot_path(const std::string& name) { return std::string(ACHD_SOURCE_DIR) + "/robots/" + name + ".urdf"; }

TEST(UrdfTrees, QuadrupedWholeTreeIsFourLegsInFileOrder) {
  const Model m = load_urdf_file(robot_path("quadruped"), "", "");
  EXPECT_EQ(m.root_name, "trunk");
  EXPECT_FALSE(m.has_tip());
  ASSERT_EQ(m.num_rates(), 12);
  EXPECT_EQ(parents(m), (std::vector<int>{-1, 0, 1, -1, 3, 4, -1, 6, 7, -1, 9, 10}));
  const std::vector<std::string> legs = {"lf", "rf", "lh", "rh"};
  for (int leg = 0; leg < 4; ++leg) {
    EXPECT_EQ(m.bodies[3 * leg].joint_name, legs[leg] + "_haa");
    EXPECT_EQ(m.bodies[3 * leg + 1].joint_name, legs[leg] + "_hfe");
    EXPECT_EQ(m.bodies[3 * leg + 2].joint_name, legs[leg] + "_kfe");
    // The foot rides on the knee's body: its mass is in the knee's inertia.
    const int foot = m.link_index(legs[leg] + "_foot");
    ASSERT_GE(foot, 0);
    EXPECT_EQ(m.links[foot].body, 3 * leg + 2);
    EXPECT_NEAR(m.bodies[3 * leg + 2].inertia(0, 0), 0.0376 + 0.01, 1e-15);
  }
  EXPECT_EQ(m.num_links(), 16);  // every link after the trunk
  EXPECT_TRUE(m.locked_joints.empty());
  expect_depth_first(m);
  // Root "" is the URDF's root link.
  expect_same_model(m, load_urdf_file(robot_path("quadruped"), "trunk", ""));
}

TEST(UrdfTrees, DualArmTorsoHasTwoArmsOnTheWaist) {
  const Model m = load_urdf_file(robot_path("dual_arm_torso"), "", "");
  EXPECT_EQ(m.root_name, "base_link");
  ASSERT_EQ(m.num_rates(), 15);
  EXPECT_EQ(parents(m), (std::vector<int>{-1, 0, 1, 2, 3, 4, 5, 6, 0, 8, 9, 10, 11, 12, 13}));
  EXPECT_EQ(m.bodies[1].joint_name, "left_joint_1");
  EXPECT_EQ(m.bodies[8].joint_name, "right_joint_1");
  EXPECT_EQ(m.links[m.link_index("left_hand")].body, 7);
  EXPECT_EQ(m.links[m.link_index("right_hand")].body, 14);
  EXPECT_EQ(m.links[m.link_index("left_arm_base")].body, 0);
  // The torso carries the arm bases (fixed): 12 + 2 x 1.697 kg.
  EXPECT_NEAR(m.bodies[0].inertia(0, 0), 12 + 2 * 1.697, 1e-13);
  EXPECT_EQ(m.num_links(), 19);
  expect_depth_first(m);
}

TEST(UrdfTrees, PandaFingersAreCoupledAsATreeAndLockedInAChain) {
  const Model coupled = load_urdf_file(robot_path("panda_fingers"), "", "");
  ASSERT_EQ(coupled.couplings.size(), 1u);
  EXPECT_EQ(coupled.bodies[coupled.couplings[0].follower].joint_name, "panda_finger_joint2");
  EXPECT_EQ(coupled.bodies[coupled.couplings[0].leader].joint_name, "panda_finger_joint1");
  UrdfOptions independent;
  independent.mimic = MimicJoints::Independent;
  const Model tree = load_urdf_file(robot_path("panda_fingers"), "", "", independent);
  ASSERT_EQ(tree.num_rates(), 9);
  EXPECT_EQ(parents(tree), (std::vector<int>{-1, 0, 1, 2, 3, 4, 5, 6, 6}));
  EXPECT_EQ(tree.bodies[7].joint_name, "panda_finger_joint1");
  EXPECT_EQ(tree.bodies[7].type, JointType::Prismatic);
  expect_depth_first(tree);
  // The chain to the hand: the fingers are side branches, locked at 0 (the mimic joint is
  // not a joint of the model, so no option is needed) and their mass rides on joint 7.
  const Model chain = load_urdf_file(robot_path("panda_fingers"), "panda_link0", "panda_hand");
  ASSERT_EQ(chain.num_rates(), 7);
  ASSERT_EQ(chain.locked_joints.size(), 2u);
  EXPECT_EQ(chain.locked_joints[0].name, "panda_finger_joint1");
  EXPECT_EQ(chain.locked_joints[1].name, "panda_finger_joint2");
  EXPECT_EQ(chain.locked_joints[0].value, 0);
  EXPECT_EQ(chain.tip().name, "panda_hand");
  EXPECT_NEAR(chain.bodies[6].inertia(0, 0), 0.735522 + 0.73 + 2 * 0.015, 1e-14);
}

TEST(UrdfTrees, SubtreeBelowAGivenRoot) {
  const Model m = load_urdf_file(robot_path("quadruped"), "rf_hip", "");
  EXPECT_EQ(joint_names(m), (std::vector<std::string>{"rf_hfe", "rf_kfe"}));
  EXPECT_EQ(parents(m), (std::vector<int>{-1, 0}));
  EXPECT_EQ(m.num_links(), 3);  // thigh, shank, foot
}

// A chain loaded as a tree (no tip) is the same model as the chain, but for the tip.
TEST(UrdfTrees, AChainLoadedAsATreeIsTheChain) {
  for (const test::IndexedRobot& r : test::load_robot_index(ACHD_SOURCE_DIR)) {
    SCOPED_TRACE(r.name);
    Model tree = load_urdf_string(r.urdf, r.root, "");
    EXPECT_FALSE(tree.has_tip());
    tree.tip_name = r.tip;
    expect_same_model(tree, r.model);
  }
}

// A fixed side link's mass moves the chain exactly as the same mass merged by hand into
// the link it hangs from: Body::inertia and the solve agree to 1e-12, at two places.
TEST(UrdfTrees, AFixedSideLinkCountsAsItsMassMergedByHand) {
  const Model plain = load_urdf_string(arm(""), "base", "tool");
  Eigen::VectorXd previous = solve(plain);
  for (const auto& [xyz, rpy] : {std::pair<Vector3, Vector3>{Vector3(0.1, 0.05, 0.02), Vector3(0.3, -0.2, 0.5)},
                                 std::pair<Vector3, Vector3>{Vector3(0.2, -0.04, 0.06), Vector3(0, 0.7, 0)}}) {
    const Model merged = load_urdf_string(arm(camera_on_link1(xyz, rpy)), "base", "tool");
    const Model by_hand =
        load_urdf_string(arm("", combine(kLink1, kCamera, rpy_matrix(rpy), xyz)), "base", "tool");
    ASSERT_EQ(merged.num_rates(), 2);
    EXPECT_EQ(merged.num_links(), plain.num_links());  // the chain's links: the path's
    EXPECT_TRUE(merged.locked_joints.empty());
    EXPECT_LE(rel(merged.bodies[0].inertia, by_hand.bodies[0].inertia), 1e-12);
    EXPECT_TRUE(merged.bodies[1].inertia == plain.bodies[1].inertia);
    const Eigen::VectorXd qdd = solve(merged);
    EXPECT_LE(rel(qdd, solve(by_hand)), 1e-12);
    EXPECT_GT(rel(qdd, previous), 1e-3);  // the camera (and where it sits) matters
    previous = qdd;
    // Ignored, as KDL does: the model of the path alone, bit for bit.
    UrdfOptions ignore;
    ignore.side_branches = SideBranches::Ignore;
    expect_same_model(load_urdf_string(arm(camera_on_link1(xyz, rpy)), "base", "tool", ignore), plain);
  }
}

// A side branch with a movable joint (a pan joint on link2 carrying the camera, and a
// prismatic slide on link1): locked at 0, or at the given value, it is the same as the
// fixed joint at that position.
TEST(UrdfTrees, LockedSideJointsAreFixedAtTheirValues) {
  const std::string side = joint("pan", "revolute", "link1", "camera", Vector3(0.1, 0.05, 0.02), Vector3(0.2, 0, 0),
                                 Vector3::UnitZ()) +
                           link("camera", kCamera) +
                           joint("slide", "prismatic", "camera", "weight", Vector3(0, 0, 0.05), Vector3::Zero(),
                                 Vector3::UnitX()) +
                           link("weight", box(0.3, 0.05, 0.05, 0.05, Vector3(0.01, 0, 0)));
  auto fixed_at = [](double pan, double slide) {
    // The pan joint about z after rpy (0.2, 0, 0): the rotation R(rpy) Rz(pan); the slide
    // moves the weight along x of the camera.
    const Matrix3 R = rpy_matrix(Vector3(0.2, 0, 0)) * Eigen::AngleAxisd(pan, Vector3::UnitZ()).toRotationMatrix();
    const Vector3 rpy = R.eulerAngles(2, 1, 0).reverse();
    return joint("pan", "fixed", "link1", "camera", Vector3(0.1, 0.05, 0.02), rpy) + link("camera", kCamera) +
           joint("slide", "fixed", "camera", "weight", Vector3(slide, 0, 0.05), Vector3::Zero()) +
           link("weight", box(0.3, 0.05, 0.05, 0.05, Vector3(0.01, 0, 0)));
  };
  const Model at_zero = load_urdf_string(arm(side), "base", "tool");
  ASSERT_EQ(at_zero.locked_joints.size(), 2u);
  EXPECT_EQ(at_zero.locked_joints[0].name, "pan");
  EXPECT_EQ(at_zero.locked_joints[0].value, 0);
  EXPECT_EQ(at_zero.locked_joints[1].name, "slide");
  const Model fixed_zero = load_urdf_string(arm(fixed_at(0, 0)), "base", "tool");
  EXPECT_LE(rel(at_zero.bodies[0].inertia, fixed_zero.bodies[0].inertia), 1e-12);
  EXPECT_LE(rel(solve(at_zero), solve(fixed_zero)), 1e-12);

  UrdfOptions options;
  options.locked = {{"pan", 0.9}, {"slide", -0.15}};
  const Model at_values = load_urdf_string(arm(side), "base", "tool", options);
  ASSERT_EQ(at_values.locked_joints.size(), 2u);
  EXPECT_EQ(at_values.locked_joints[0].value, 0.9);
  EXPECT_EQ(at_values.locked_joints[1].value, -0.15);
  const Model fixed_values = load_urdf_string(arm(fixed_at(0.9, -0.15)), "base", "tool");
  EXPECT_LE(rel(at_values.bodies[0].inertia, fixed_values.bodies[0].inertia), 1e-12);
  EXPECT_LE(rel(solve(at_values), solve(fixed_values)), 1e-12);
  EXPECT_GT(rel(solve(at_values), solve(at_zero)), 1e-4);
}

void expect_error(const std::function<void()>& load, const std::string& expected) {
  try {
    load();
    ADD_FAILURE() << "loaded; expected: " << expected;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(UrdfTrees, ErrorsNameTheLinkOrJoint) {
  const std::string side = joint("pan", "revolute", "link1", "camera", Vector3(0.1, 0, 0), Vector3::Zero()) +
                           link("camera", kCamera);
  auto with_locked = [&](std::map<std::string, double> locked, SideBranches branches = SideBranches::Merge,
                         const std::string& tip = "tool") {
    UrdfOptions o;
    o.locked = std::move(locked);
    o.side_branches = branches;
    return [=] { load_urdf_string(arm(side), "base", tip, o); };
  };
  expect_error(with_locked({{"nope", 1}}), "URDF: locked joint 'nope': not a movable joint of the loaded robot "
                                           "(there is no joint of that name)");
  expect_error(with_locked({{"tool_joint", 1}}), "locked joint 'tool_joint': not a movable joint of the loaded "
                                                 "robot (it is a fixed joint)");
  expect_error(with_locked({{"pan", 1}}, SideBranches::Ignore), "locked joint 'pan': not a movable joint of "
                                                                "the loaded robot (side branches are ignored");
  expect_error(with_locked({{"pan", 2.5}}), "URDF: locked joint 'pan': value 2.5 is outside its limits");
  expect_error(with_locked({{"pan", std::nan("")}}), "locked joint 'pan': value is not finite");
  expect_error([&] { load_urdf_string(arm(side), "nowhere", ""); }, "URDF: unknown root link 'nowhere'");
  expect_error([&] { load_urdf_string(arm(side), "nowhere", "tool"); }, "URDF: unknown root link 'nowhere'");
  expect_error([&] { load_urdf_string(arm(side), "camera", "tool"); },
               "URDF: tip link 'tool' is not below root link 'camera'");
  expect_error([&] { load_urdf_string(arm(side), "tool", ""); }, "the tree below 'tool' has no movable joint");
  // A side branch is loaded, so its faults are reported (ignored, it is not read).
  const std::string bad_side = joint("float", "floating", "link1", "drone", Vector3::Zero(), Vector3::Zero()) +
                               link("drone", kCamera);
  expect_error([&] { load_urdf_string(arm(bad_side), "base", "tool"); }, "joint 'float': unsupported joint type 'floating'");
  UrdfOptions ignore;
  ignore.side_branches = SideBranches::Ignore;
  EXPECT_EQ(load_urdf_string(arm(bad_side), "base", "tool", ignore).num_rates(), 2);
  Inertial negative = kCamera;
  negative.mass = -1;
  expect_error([&] { load_urdf_string(arm(joint("c", "fixed", "link2", "cam", Vector3::Zero(), Vector3::Zero()) +
                                          link("cam", negative)),
                                      "base", "tool"); },
               "URDF: link 'cam': negative mass");
}

// The tree robots of robots/index.json: each loads whole with its options, its q0 inside the
// limits, its default held links links of the model; the four-bar has no held links but
// its loop joint (its loops file's).
TEST(UrdfTrees, IndexTreesLoadWithTheirPosesAndHeldLinks) {
  const std::vector<test::IndexedRobot> trees = test::load_tree_index(ACHD_SOURCE_DIR);
  ASSERT_EQ(trees.size(), 5u);  // quadruped, dual-arm torso, Panda with fingers, humanoid, four-bar
  for (const test::IndexedRobot& r : trees) {
    SCOPED_TRACE(r.name);
    EXPECT_FALSE(r.model.has_tip());
    ASSERT_EQ(r.q0.size(), r.model.num_rates());
    for (int i = 0; i < r.model.num_rates(); ++i) {
      EXPECT_GT(r.q0[i], r.model.bodies[i].limits.lower) << r.model.bodies[i].joint_name;
      EXPECT_LT(r.q0[i], r.model.bodies[i].limits.upper) << r.model.bodies[i].joint_name;
    }
    EXPECT_NE(r.constraints.empty(), r.model.loops.empty()) << "held links, or loop joints";
    for (const std::string& link : r.constraints) EXPECT_GE(r.model.link_index(link), 0) << link;
    expect_depth_first(r.model);
  }
  EXPECT_EQ(trees[0].model.num_rates(), 12);
  EXPECT_GE(trees[1].model.num_rates(), 15);
  EXPECT_EQ(trees[2].model.num_rates(), 9);
  EXPECT_EQ(trees[4].name, "four_bar");
  ASSERT_EQ(trees[4].model.loops.size(), 1u);
  EXPECT_EQ(trees[4].model.loops[0].name, "coupler_rocker");
}

}  // namespace
}  // namespace achd
