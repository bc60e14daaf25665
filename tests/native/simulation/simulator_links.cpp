// The simulator's directions on any links (each link its own set, at a point of it) and
// its joint PD controller, checked against what does not depend on the simulator:
//   - the floating quadruped stands 10 s on its four feet held in 3D under the PD
//     controller: every foot stays where it was (residuals <= 1e-9, and the feet's
//     positions from forward kinematics), the trunk's height within 1 cm;
//   - both hands of the dual-arm torso held in 6D under gravity: each hand's pose from
//     forward kinematics stays put, and each link's residuals are its own;
//   - a point off a link's origin held in 3D stays where it was (forward kinematics of the
//     link times the point), while the link turns about it;
//   - PD alone under gravity settles where kp (target - q) = g(q), the gravity torques of
//     RNEA (a static equilibrium the controller does not know);
//   - direction events name the link whose direction is damped;
//   - named errors: the tip API on a tree, a link index out of range, a 37th column,
//     gains on a floating base's free joint, wrong sizes, negative gains.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "achd/achd.hpp"
#include "achd/dynamics.hpp"
#include "achd/kinematics.hpp"
#include "achd/simulator.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

const std::string kSource = ACHD_SOURCE_DIR;

IndexedRobot tree_robot(const std::string& name) {
  for (IndexedRobot& r : load_tree_index(kSource))
    if (r.name == name) return r;
  throw std::runtime_error("no tree robot " + name + " in robots/index.json");
}

void expect_error(const std::function<void()>& f, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one containing: " << part;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

// The floating quadruped at its index pose, the trunk 0.3 m up and upright.
struct StandingQuadruped {
  Model model;
  Eigen::VectorXd q0;
  std::vector<int> feet;
};

StandingQuadruped standing_quadruped() {
  const IndexedRobot r = tree_robot("quadruped");
  UrdfOptions o = r.options;
  o.floating = true;
  StandingQuadruped s{load_urdf_file(r.urdf_path, r.root, "", o), {}, {}};
  s.q0 = Case::zeros(s.model).q;
  s.q0[2] = 0.3;
  s.q0.tail(r.q0.size()) = r.q0;
  for (const std::string& foot : r.constraints) s.feet.push_back(s.model.link_index(foot));
  return s;
}

TEST(SimulatorLinks, FloatingQuadrupedStandsTenSecondsOnHeldFeet) {
  const StandingQuadruped s = standing_quadruped();
  const Model& m = s.model;
  SimulatorOptions o;
  o.integrator = Integrator::RK4;
  Simulator sim(m, o);
  sim.reset(s.q0, {});
  JointControl pd;
  pd.target = s.q0;
  pd.kp = Eigen::VectorXd::Constant(m.num_rates(), 30.0);
  pd.kd = Eigen::VectorXd::Constant(m.num_rates(), 0.5);
  pd.kp.head(6).setZero();  // the free joint is not actuated
  pd.kd.head(6).setZero();
  sim.set_joint_control(pd);
  for (int foot : s.feet)
    for (int k = 0; k < 3; ++k) sim.set_direction(foot, k, DirectionMode::Hold);
  const std::vector<Transform> feet0 = forward_kinematics(m, s.q0);
  double worst_residual = 0, worst_height = 0;
  for (int step = 0; step < 10000; ++step) {
    sim.step(1e-3);
    for (int foot : s.feet)
      for (double r : sim.residuals(foot)) worst_residual = std::max(worst_residual, std::abs(r));
    worst_height = std::max(worst_height, std::abs(sim.q[2] - s.q0[2]));
  }
  EXPECT_NEAR(sim.t, 10.0, 1e-12);
  EXPECT_LE(worst_residual, 1e-9);
  EXPECT_LE(worst_height, 0.01);
  const std::vector<Transform> feet = forward_kinematics(m, sim.q);
  for (int foot : s.feet) EXPECT_LE((feet[foot].p - feet0[foot].p).norm(), 1e-9) << m.links[foot].name;
  // It came to rest: the PD's damping took out the start's transient.
  EXPECT_LE(sim.qd.lpNorm<Eigen::Infinity>(), 1e-6);
  // The feet carry the weight: at rest they push down on their holds with m g in all
  // (constraint_wrenches: what each link exerts on its constraint).
  double mass = 0;
  for (const Body& b : m.bodies) mass += b.inertia(0, 0);
  double push = 0;
  for (const Vector6& w : sim.data().constraint_wrenches) push += w[2];
  EXPECT_NEAR(push, -mass * 9.81, 1e-6 * mass * 9.81);
  std::printf("# quadruped on held feet, 10 s RK4 at 1 ms: feet residual %.3g m, trunk height change %.3g m\n",
              worst_residual, worst_height);
}

TEST(SimulatorLinks, BothHandsOfTheTorsoHeldIn6D) {
  const IndexedRobot r = tree_robot("dual_arm_torso");
  const Model& m = r.model;
  Simulator sim(m);  // Dormand-Prince, all effects
  sim.reset(r.q0, Eigen::VectorXd::Constant(m.num_rates(), 0.3));
  const int left = m.link_index("left_hand"), right = m.link_index("right_hand");
  for (int k = 0; k < kNumDirections; ++k) sim.set_direction(left, k, DirectionMode::Hold);
  for (int k = 0; k < 3; ++k) sim.set_direction(right, k, DirectionMode::Hold);  // right: position only
  const std::vector<Transform> start = forward_kinematics(m, sim.q);
  sim.run(1000, 1e-3);
  const std::vector<Transform> end = forward_kinematics(m, sim.q);
  // The moving start decays under the stabilisation: both hands back within 1e-6.
  EXPECT_LE((end[left].p - start[left].p).norm(), 1e-6);
  EXPECT_LE(Eigen::AngleAxisd(start[left].R.transpose() * end[left].R).angle(), 1e-6);
  EXPECT_LE((end[right].p - start[right].p).norm(), 1e-6);
  // The right hand's orientation is free: the start's velocities turned it.
  EXPECT_GE(Eigen::AngleAxisd(start[right].R.transpose() * end[right].R).angle(), 1e-3);
  const auto rl = sim.max_residuals(left), rr = sim.max_residuals(right);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(sim.residuals(right)[3 + k], 0.0);  // not held
  EXPECT_GT(rl[3] + rl[4] + rl[5], 0.0);  // the start moved them: recorded per link
  ASSERT_EQ(sim.direction_sets().size(), 2u);
  EXPECT_EQ(sim.direction_sets()[0].link, left);  // nu: the left hand's six, then the right's three
  EXPECT_EQ(sim.data().nu.size(), 9);
  EXPECT_GT(rr[0] + rr[1] + rr[2], 0.0);
}

TEST(SimulatorLinks, APointOffTheLinkOriginStaysWhereItWas) {
  const IndexedRobot r = tree_robot("dual_arm_torso");
  const Model& m = r.model;
  Simulator sim(m);
  sim.reset(r.q0, Eigen::VectorXd::Constant(m.num_rates(), 0.5));
  const int hand = m.link_index("left_hand");
  const Vector3 point(0.05, -0.02, 0.1);
  sim.set_direction_point(hand, point);
  for (int k = 0; k < 3; ++k) sim.set_direction(hand, k, DirectionMode::Hold);
  const Transform start = forward_kinematics(m, sim.q)[hand];
  sim.run(1000, 1e-3);
  const Transform end = forward_kinematics(m, sim.q)[hand];
  EXPECT_LE(((end.p + end.R * point) - (start.p + start.R * point)).norm(), 1e-6);
  EXPECT_LE((sim.link_pose(hand).p - (end.p + end.R * point)).norm(), 1e-15);
  // The link's origin is not held: it turned about the point.
  EXPECT_GE((end.p - start.p).norm(), 1e-3);
}

TEST(SimulatorLinks, JointControlSettlesAtTheGravityEquilibrium) {
  const Model m = load_urdf_file(kSource + "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  SimulatorOptions o;
  o.effects = kGravity | kVelocityProducts;
  o.integrator = Integrator::ImplicitEuler;  // the wrist's kd / I is stiff: implicit in kd
  Simulator sim(m, o);
  Eigen::VectorXd q0(7), target(7);
  q0 << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  target << -0.2, 0.9, 0.3, -1.0, 0.1, 0.5, -0.3;
  sim.reset(q0, {});
  JointControl pd{target, Eigen::VectorXd::Constant(7, 400.0), Eigen::VectorXd::Constant(7, 40.0)};
  sim.set_joint_control(pd);
  sim.run(5000, 1e-3);
  // At rest, kp (target - q) = g(q): RNEA's torque holding q still under gravity.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(7);
  const Eigen::VectorXd g = rnea(m, sim.q, zero, zero, o.gravity, {}, with_effects(kGravity));
  EXPECT_LE(sim.qd.lpNorm<Eigen::Infinity>(), 1e-8);
  EXPECT_LE((pd.kp.cwiseProduct(target - sim.q) - g).lpNorm<Eigen::Infinity>(), 1e-6 * g.norm());
  EXPECT_GE((sim.q - target).norm(), 1e-3);  // gravity holds it off the target
  // Without gravity it reaches the target.
  sim.options().effects = kVelocityProducts;
  sim.run(5000, 1e-3);
  EXPECT_LE((sim.q - target).lpNorm<Eigen::Infinity>(), 1e-8);
  sim.clear_joint_control();
  EXPECT_FALSE(sim.joint_control_on());
}

TEST(SimulatorLinks, EventsNameTheLink) {
  const IndexedRobot r = tree_robot("dual_arm_torso");
  const Model& m = r.model;
  Simulator sim(m);
  sim.options().effects = kAllEffects & ~kGravity;
  sim.reset(r.q0, {});
  const int left = m.link_index("left_hand"), right = m.link_index("right_hand");
  for (int k = 0; k < 3; ++k) sim.set_direction(right, k, DirectionMode::Hold);
  // Pulled sideways faster and faster: the arm stretches to its reach, where x is damped.
  sim.set_direction(left, 1, DirectionMode::Accelerate, 8.0);
  for (int s = 0; s < 3000 && sim.events().empty(); ++s) sim.step(1e-3);
  ASSERT_FALSE(sim.events().empty());
  for (const DirectionEvent& e : sim.events()) {
    EXPECT_EQ(e.link, left) << direction_name(e.direction);
    EXPECT_EQ(e.direction, 1);
  }
  for (double res : sim.max_residuals(right)) EXPECT_LE(res, 1e-6);
}

TEST(SimulatorLinks, ErrorsNameTheLinkAndJoint) {
  const StandingQuadruped s = standing_quadruped();
  Simulator sim(s.model);
  expect_error([&] { sim.set_direction(2, DirectionMode::Hold); }, "the model is a tree (loaded without a tip)");
  expect_error([&] { sim.set_direction(99, 2, DirectionMode::Hold); }, "direction link index 99 is not in 0..");
  expect_error([&] { sim.set_direction(s.feet[0], 7, DirectionMode::Hold); }, "direction index 7 is not in 0..5");
  expect_error([&] { sim.set_direction(s.feet[0], 0, DirectionMode::Accelerate, NAN); },
               "direction x of link 'lf_foot': setpoint is not finite");
  expect_error([&] { sim.set_direction_weights(s.feet[1], 2, 1.5, 1); },
               "direction z of link 'rf_foot': w_fext must be in [0, 1], got 1.5");
  expect_error([&] { sim.set_direction_point(s.feet[0], Vector3(0, NAN, 0)); },
               "the direction point of link 'lf_foot' is not finite");
  // 36 columns on six links, then one more
  for (int l = 0, columns = 0; columns < kMaxConstraintColumns; ++l)
    for (int k = 0; k < kNumDirections; ++k, ++columns) sim.set_direction(l, k, DirectionMode::Hold);
  expect_error([&] { sim.set_direction(6, 0, DirectionMode::Hold); }, "36 directions are already active");
  JointControl pd{s.q0, Eigen::VectorXd::Zero(18), Eigen::VectorXd::Zero(18)};
  pd.kp[3] = 1;
  expect_error([&] { sim.set_joint_control(pd); }, "kp[3] of joint 'trunk' (the floating base's free joint");
  pd.kp[3] = 0;
  pd.kd[10] = -1;
  expect_error([&] { sim.set_joint_control(pd); },
               "kd of joint '" + s.model.bodies[10].joint_name + "' must be finite and >= 0, got -1");
  pd.kd[10] = 0;
  pd.target.resize(18);
  expect_error([&] { sim.set_joint_control(pd); }, "target: expected 19 values (a pose as q), got 18");
  EXPECT_FALSE(sim.joint_control_on());
}

}  // namespace
}  // namespace achd::test
