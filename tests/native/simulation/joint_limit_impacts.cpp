// Joint limits with LimitPolicy::Clamp (joint_limits.cpp): a joint that reaches
// its limit while the tip holds z and rx stops by an inelastic impact that keeps the held
// directions, rests on the limit with its acceleration prescribed as 0 while the other
// joints hold the directions, and leaves the limit when the solve pulls it away. The
// robots' limits are narrowed in code so that gravity drives a joint into one within the
// first second. Before this (clamping q and zeroing qd), the held residual after the
// impact reached 0.128 (UR5) and 0.013 (LWR). The last test runs a scene through the CLI.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"
#include "cli_run.hpp"

namespace achd::test {
namespace {

constexpr int kZ = 2, kRx = 3;

struct Scene {
  std::string name;
  Model model;
  Eigen::VectorXd q0;
  int joint;  // the joint that reaches a limit
  int side;   // -1 lower, +1 upper
};

Scene ur5_elbow() {
  Scene s{"ur5", load_urdf_file(ACHD_SOURCE_DIR "/robots/ur5.urdf", "base_link", "wrist_3_link"),
          Eigen::VectorXd(6), 2, -1};
  s.q0 << 0.2, -1.0, 1.2, -1.5, -1.4, 0.3;
  s.model.bodies[2].limits.lower = 0.6;  // the elbow falls from 1.2 to 0.6 in 0.32 s
  return s;
}

Scene lwr_shoulder() {
  Scene s{"kuka_lwr4", load_urdf_file(ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7"),
          Eigen::VectorXd(7), 1, +1};
  s.q0 << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  s.model.bodies[1].limits.upper = 1.2;  // joint 2 rises from 0.6 to 1.2 in 0.34 s
  return s;
}

// The simulator's defaults with limits clamp, holding z and rx from q0 at rest.
Simulator holding_z_rx(const Scene& s) {
  SimulatorOptions o;
  o.limits = LimitPolicy::Clamp;
  Simulator sim(s.model, o);
  sim.reset(s.q0, {});
  sim.set_direction(kZ, DirectionMode::Hold);
  sim.set_direction(kRx, DirectionMode::Hold);
  return sim;
}

double limit_of(const Scene& s) {
  const JointLimits& l = s.model.bodies[s.joint].limits;
  return s.side > 0 ? l.upper : l.lower;
}

double held_residual(const Simulator& sim) {
  const auto r = sim.residuals();
  return std::max(std::abs(r[kZ]), std::abs(r[kRx]));
}

// 1000 steps of 1 ms: the joint reaches its limit, stops and rests there; from the step
// after the impact, the held directions stay within 1e-6 and the joint on its limit.
void expect_stop_keeps_held_directions(const Scene& s) {
  SCOPED_TRACE(s.name);
  Simulator sim = holding_z_rx(s);
  const double limit = limit_of(s);
  int impact = -1, resting = 0;
  double worst = 0;
  for (int k = 0; k < 1000; ++k) {
    sim.step(1e-3);
    const double q = sim.q[s.joint];
    EXPECT_TRUE(s.side > 0 ? q <= limit : q >= limit) << "step " << k << ": q = " << q;
    if (sim.limit_stop(s.joint) == 0) continue;
    EXPECT_EQ(sim.limit_stop(s.joint), s.side);
    EXPECT_EQ(q, limit);
    EXPECT_EQ(sim.qd[s.joint], 0.0);
    if (impact < 0) {
      impact = k;
      continue;
    }
    ++resting;
    worst = std::max(worst, held_residual(sim));
    EXPECT_LE(held_residual(sim), 1e-6) << "step " << k << " (impact at step " << impact << ")";
  }
  std::printf("  %s: impact at step %d, %d steps resting on the limit, worst held residual %.3g\n",
              s.name.c_str(), impact, resting, worst);
  EXPECT_GE(impact, 0) << "the joint never reached its limit";
  EXPECT_GT(resting, 500);
}

TEST(JointLimitImpacts, Ur5ElbowStopsAndHeldDirectionsStay) { expect_stop_keeps_held_directions(ur5_elbow()); }

TEST(JointLimitImpacts, LwrShoulderStopsAndHeldDirectionsStay) { expect_stop_keeps_held_directions(lwr_shoulder()); }

// Resting on its limit, the joint leaves it once a torque pulls it away (here its own
// ff_torque, twice the stop's reaction the other way), and the held directions stay.
// Without the torque it keeps resting.
void expect_leaves_when_pulled(const Scene& s) {
  SCOPED_TRACE(s.name);
  for (const bool pull : {false, true}) {
    Simulator sim = holding_z_rx(s);
    sim.run(600, 1e-3);
    ASSERT_EQ(sim.limit_stop(s.joint), s.side);
    if (pull) {
      // data(): the last step's first solve, with the joint prescribed: the torque it needed
      // from the actuator and the stop together (ff_torques is 0).
      const double stop_torque = sim.data().prescribed_torques[s.joint];
      ASSERT_GT(stop_torque * -s.side, 0) << "the stop pushes the joint back into its range";
      sim.ff_torques[s.joint] = 2 * stop_torque;
    }
    double worst = 0;
    for (int k = 0; k < 300; ++k) {
      sim.step(1e-3);
      worst = std::max(worst, held_residual(sim));
    }
    const double away = (limit_of(s) - sim.q[s.joint]) * s.side;  // > 0: inside the range
    if (pull) {
      EXPECT_EQ(sim.limit_stop(s.joint), 0);
      EXPECT_GT(away, 1e-3);
    } else {
      EXPECT_EQ(sim.limit_stop(s.joint), s.side);
      EXPECT_EQ(away, 0.0);
    }
    EXPECT_LE(worst, 1e-6) << (pull ? "pulled away" : "resting");
  }
}

TEST(JointLimitImpacts, Ur5ElbowLeavesTheLimitWhenPulledAway) { expect_leaves_when_pulled(ur5_elbow()); }

TEST(JointLimitImpacts, LwrShoulderLeavesTheLimitWhenPulledAway) { expect_leaves_when_pulled(lwr_shoulder()); }

// A joint set off its stop by the caller (reset, or q written directly) is free again.
TEST(JointLimitImpacts, ResetAndMovedJointsLeaveTheirStops) {
  const Scene s = ur5_elbow();
  Simulator moved = holding_z_rx(s), reset = holding_z_rx(s);
  for (Simulator* sim : {&moved, &reset}) {
    sim->run(600, 1e-3);
    ASSERT_EQ(sim->limit_stop(s.joint), s.side);
  }
  moved.q[s.joint] = 1.0;
  moved.step(1e-3);
  EXPECT_EQ(moved.limit_stop(s.joint), 0);
  EXPECT_NE(moved.qd[s.joint], 0.0);
  reset.reset(s.q0, {});
  EXPECT_EQ(reset.limit_stop(s.joint), 0);
  EXPECT_THROW(reset.limit_stop(6), Error);
}

// Without held directions the impact is the plain inelastic joint stop: the joint's
// velocity goes to 0 and the others change as M^-1 e_i lambda says, so the generalised
// momentum of the other joints about the stop, (M qd)_j for j != i, is unchanged, and
// kinetic energy is lost.
TEST(JointLimitImpacts, ImpactWithoutHeldDirectionsKeepsTheOtherJointsMomentum) {
  const Scene s = ur5_elbow();
  SimulatorOptions o;
  o.limits = LimitPolicy::Clamp;
  o.effects = kRotorInertia;  // no forces: the step changes qd only by the impact
  o.integrator = Integrator::ExplicitEuler;
  Simulator sim(s.model, o);
  Eigen::VectorXd qd = Eigen::VectorXd::Constant(6, 0.3);
  qd[s.joint] = -2;
  Eigen::VectorXd q = s.q0;
  q[s.joint] = limit_of(s) + 1e-3;  // reaches the limit in this step
  sim.reset(q, qd);
  sim.step(1e-3);
  ASSERT_EQ(sim.limit_stop(s.joint), s.side);
  const Eigen::MatrixXd M = crba(s.model, sim.q);
  const Eigen::VectorXd before = M * qd, after = M * sim.qd;
  for (int j = 0; j < 6; ++j)
    if (j != s.joint) EXPECT_NEAR(after[j], before[j], 1e-12 * before.cwiseAbs().maxCoeff()) << "joint " << j;
  EXPECT_EQ(sim.qd[s.joint], 0.0);
  // Inelastic: the impact takes kinetic energy, 1/2 qd^T M qd, out.
  EXPECT_LT(0.5 * sim.qd.dot(after), 0.5 * qd.dot(before));
}

// The same through a scene file and `achd simulate`: a UR5 whose elbow's lower limit is
// 0.6 in its URDF, "limits": "clamp", z and rx held for 1 s with the simulator's default
// integrator (RK4 at 1 ms is not accurate to 1e-6 on the UR5's stiff friction). The
// summary's held drift (the largest residual of the run) stays below 1e-6; before, it
// was 0.120 (z) and 0.128 (rx).
TEST(JointLimitImpacts, SceneWithClampKeepsHeldDriftThroughTheCli) {
  std::ifstream in(ACHD_SOURCE_DIR "/robots/ur5.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  const std::string elbow = R"(<limit lower="-3.141592653589793" upper="3.141592653589793" effort="150")";
  const size_t at = urdf.find(elbow);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(urdf.find(elbow, at + 1), std::string::npos) << "only the elbow has these limits";
  urdf.replace(at, elbow.size(), R"(<limit lower="0.6" upper="3.141592653589793" effort="150")");
  const std::string dir = make_temp_dir("achd_limits");
  std::ofstream(dir + "/ur5_elbow_0.6.urdf") << urdf;
  std::ofstream(dir + "/scene.json") << R"({"urdf": ")" + dir + R"(/ur5_elbow_0.6.urdf", "root": "base_link", "tip": "wrist_3_link",
    "q0": [0.2, -1.0, 1.2, -1.5, -1.4, 0.3], "directions": {"z": "hold", "rx": "hold"},
    "dt": 0.001, "duration": 1.0, "gravity": [0, 0, -9.81], "limits": "clamp"})";
  const CliRun run = run_cli(dir, {"simulate", dir + "/scene.json", "--out", dir + "/trajectory.csv"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_LE(summary["held_drift"]["z"].get<double>(), 1e-6) << run.out;
  EXPECT_LE(summary["held_drift"]["rx"].get<double>(), 1e-6) << run.out;
  EXPECT_GT(summary["limit_hits"]["elbow_joint"].get<int>(), 500) << run.out;
}

}  // namespace
}  // namespace achd::test
