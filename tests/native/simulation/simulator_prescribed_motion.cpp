// Prescribed joint motion in the simulator (Simulator::prescribe): the joint
// starts on its trajectory and stays on it, its acceleration in each step's solve is the
// trajectory's exactly, held directions still hold around it, the torque it takes moves
// the free robot the same way, limit stops leave it alone, steps allocate nothing, and
// bad motions are named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>

#include "achd/achd.hpp"
#include "achd/joint_motion.hpp"
#include "achd/names.hpp"

#include "counted_new.hpp"

namespace {

using namespace achd;

const std::filesystem::path kRoot = ACHD_SOURCE_DIR;

Model lwr() { return load_urdf_file((kRoot / "robots/kuka_lwr4.urdf").string(), "lwr_base_link", "lwr_link_7"); }
Eigen::VectorXd lwr_q0() {
  Eigen::VectorXd q(7);
  q << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  return q;
}

JointMotion sine(double centre, double amplitude, double frequency, double phase) {
  JointMotion m;
  m.kind = MotionKind::Sine;
  m.position = centre;
  m.amplitude = amplitude;
  m.frequency = frequency;
  m.phase = phase;
  return m;
}
JointMotion ramp(double from, double velocity) {
  JointMotion m;
  m.kind = MotionKind::Ramp;
  m.position = from;
  m.velocity = velocity;
  return m;
}

// The analytic derivatives of sample() against central differences of its position.
TEST(JointMotion, VelocityAndAccelerationAreTheDerivativesOfThePosition) {
  JointMotion constant;
  constant.position = 0.7;
  for (const JointMotion& m : {sine(0.3, 0.5, 0.5, 0.2), sine(-1, 2, 3, -1), ramp(0.1, -0.4), constant}) {
    for (double t : {0.0, 0.13, 1.7}) {
      const double h = 1e-4;
      const JointSample s = sample(m, t), a = sample(m, t - h), b = sample(m, t + h);
      EXPECT_NEAR(s.qd, (b.q - a.q) / (2 * h), 1e-6 * (1 + std::abs(s.qd))) << kMotionKindNames[int(m.kind)];
      EXPECT_NEAR(s.qdd, (b.qd - a.qd) / (2 * h), 1e-6 * (1 + std::abs(s.qdd))) << kMotionKindNames[int(m.kind)];
    }
  }
  EXPECT_EQ(sample(ramp(0.1, -0.4), 2).q, 0.1 - 0.8);
  EXPECT_EQ(sample(constant, 5).q, 0.7);
}

// Every integrator: the LWR's base joint on a sine (0.5 rad, 0.5 Hz) and its third joint
// on a ramp, the tip holding z and rx, for 0.5 s at 1 ms (friction off: its stiffness near
// rest is not what is tested). Each step's first solve has the trajectories' accelerations
// at the step's start exactly, the joints are on their trajectories after every step, the
// other joints move, and steps allocate nothing. The held directions are set while the
// ramp already moves the tip along them: once the stabilisation has taken that out (0.2 s,
// simulator.hpp), RK4 and Dormand-Prince hold them within 1e-6 (the first-order
// integrators' own error at 1 ms is larger, 1e-4 to 1e-3, as without prescribed joints).
TEST(PrescribedMotion, FollowsTheTrajectoryWhileHeldDirectionsHold) {
  const Model m = lwr();
  const JointMotion base = sine(0.3, 0.5, 0.5, 0), third = ramp(-0.2, 0.3);
  for (Integrator integrator : kIntegrators) {
    SimulatorOptions o;
    o.integrator = integrator;
    o.effects = kAllEffects & ~kFriction;
    Simulator sim(m, o);
    sim.reset(lwr_q0(), {});
    sim.prescribe(0, base);
    sim.prescribe(2, third);
    // Started on the trajectory: q and qd at t = 0.
    EXPECT_EQ(sim.q[0], 0.3);
    EXPECT_EQ(sim.qd[0], sample(base, 0).qd);
    EXPECT_EQ(sim.qd[2], 0.3);
    EXPECT_TRUE(sim.prescribed(0) && sim.prescribed(2) && !sim.prescribed(1));
    sim.set_direction(2, DirectionMode::Hold);
    sim.set_direction(3, DirectionMode::Hold);
    const Eigen::VectorXd q_start = sim.q;
    sim.step(1e-3);  // the first step sizes nothing, but keep the count to the run
    const long before = g_allocations;
    double worst_qdd = 0, worst_q = 0, worst_held = 0;
    for (int k = 1; k < 500; ++k) {
      const double t0 = sim.t;
      sim.step(1e-3);
      if (sim.t > 0.2) {
        const auto r = sim.residuals();
        worst_held = std::max({worst_held, std::abs(r[2]), std::abs(r[3])});
      }
      worst_qdd = std::max({worst_qdd, std::abs(sim.data().qdd[0] - sample(base, t0).qdd),
                            std::abs(sim.data().qdd[2] - sample(third, t0).qdd)});
      worst_q = std::max({worst_q, std::abs(sim.q[0] - sample(base, sim.t).q),
                          std::abs(sim.qd[0] - sample(base, sim.t).qd), std::abs(sim.q[2] - sample(third, sim.t).q)});
    }
    const long allocations = g_allocations - before;
    const std::string name = integrator_name(integrator);
    EXPECT_EQ(allocations, 0) << name;
    EXPECT_EQ(worst_qdd, 0.0) << name << ": the solve's acceleration is the trajectory's";
    EXPECT_EQ(worst_q, 0.0) << name << ": q and qd on the trajectory after every step";
    if (integrator == Integrator::RK4 || integrator == Integrator::DormandPrince)
      EXPECT_LT(worst_held, 1e-6) << name;
    // The base swung through most of its amplitude and the free joints moved to hold.
    EXPECT_GT(std::abs(sim.q[0] - q_start[0]), 0.4) << name;
    EXPECT_GT((sim.q - q_start).tail(4).cwiseAbs().maxCoeff(), 1e-3) << name;
    // The prescribed joints take torque; the free joints' entries are 0.
    EXPECT_NE(sim.data().prescribed_torques[0], 0.0) << name;
    EXPECT_EQ(sim.data().prescribed_torques[1], 0.0) << name;
  }
}

// The torque the prescribed joint takes, applied as its feed-forward torque with the joint
// free, gives the free robot the same accelerations (Data::prescribed_torques), at the
// state of a step of the simulation, the held directions as constraints.
TEST(PrescribedMotion, ItsTorqueDrivesTheFreeRobotTheSameWay) {
  const Model m = lwr();
  SimulatorOptions o;
  o.integrator = Integrator::RK4;
  o.effects = kAllEffects & ~kFriction;  // smooth: the comparison is one solve to another
  Simulator sim(m, o);
  sim.reset(lwr_q0(), {});
  const JointMotion base = sine(0.3, 0.5, 0.5, 0);
  sim.prescribe(0, base);
  sim.set_direction(2, DirectionMode::Hold);
  sim.run(200, 1e-3);
  const Eigen::VectorXd q = sim.q, qd = sim.qd;
  const double t = sim.t;
  sim.step(1e-3);
  const Data& d = sim.data();
  // The same solve with the base joint free and driven by its prescribed torque.
  Case c = Case::zeros(m);
  c.q = q;
  c.qd = qd;
  c.gravity = o.gravity;
  c.ff_torques = Eigen::VectorXd::Zero(7);
  c.ff_torques[0] = d.prescribed_torques[0];
  c.alpha = ConstraintMatrix::Zero(6, 1);
  c.alpha(2, 0) = 1;
  // beta: the spatial z acceleration of the tip (the last link) that the simulator's
  // solve enforced.
  c.beta = ConstraintVector::Constant(1, d.link_accelerations.back()[2]);
  Options so = o.solver;
  so.effects = o.effects;
  Data free(m);
  hybrid_dynamics(m, free, c, so);
  EXPECT_NEAR(free.qdd[0], sample(base, t).qdd, 1e-9);
  EXPECT_LT((free.qdd - d.qdd).cwiseAbs().maxCoeff(), 1e-9);
}

// LimitPolicy::Clamp: the UR5's elbow (lower limit narrowed to 0.6) falls onto its stop
// while the shoulder pan is on a ramp that carries it past its own upper limit (narrowed
// to 0.3). The elbow stops (an impact, then rest); the ramp goes on through its limit at
// its velocity, unchanged by the elbow's impact; limit_hits lists it (RK4, Dormand-Prince).
TEST(PrescribedMotion, LimitStopsLeaveAPrescribedJointAlone) {
  Model m = load_urdf_file((kRoot / "robots/ur5.urdf").string(), "base_link", "wrist_3_link");
  m.bodies[2].limits.lower = 0.6;
  m.bodies[0].limits.upper = 0.3;
  Eigen::VectorXd q0(6);
  q0 << 0.2, -1.0, 1.2, -1.5, -1.4, 0.3;
  for (Integrator integrator : {Integrator::RK4, Integrator::DormandPrince}) {
    SimulatorOptions o;
    o.integrator = integrator;
    o.limits = LimitPolicy::Clamp;
    Simulator sim(m, o);
    sim.reset(q0, {});
    const JointMotion pan = ramp(0.2, 0.5);
    sim.prescribe(0, pan);
    sim.set_direction(2, DirectionMode::Hold);
    sim.step(1e-3);
    const long before = g_allocations;
    bool pan_listed = false;
    double worst = 0;
    for (int k = 0; k < 700; ++k) {
      sim.step(1e-3);
      worst = std::max({worst, std::abs(sim.q[0] - sample(pan, sim.t).q), std::abs(sim.qd[0] - 0.5)});
      for (int i : sim.limit_hits()) pan_listed = pan_listed || i == 0;
    }
    const long allocations = g_allocations - before;
    const std::string name = integrator_name(integrator);
    EXPECT_EQ(allocations, 0) << name;
    EXPECT_EQ(sim.limit_stop(2), -1) << name << ": the elbow rests on its stop";
    EXPECT_EQ(sim.q[2], 0.6) << name;
    EXPECT_EQ(sim.limit_stop(0), 0) << name << ": the prescribed joint is never stopped";
    EXPECT_GT(sim.q[0], 0.3 + 0.1) << name << ": past its upper limit";
    EXPECT_EQ(worst, 0.0) << name << ": on its ramp through the elbow's impact";
    EXPECT_TRUE(pan_listed) << name;
    EXPECT_LT(sim.max_residuals()[2], 1e-6) << name;
  }
}

// The jump onto a trajectory is an inelastic one the held directions respect: the LWR
// holds its tip in 6D, and its base joint is prescribed on a sine whose position and
// velocity at t = 0 are 0.2 rad and 0.38 rad/s away from the state's. After prescribe()
// the base is on the trajectory to the bit, the tip's pose and velocity are those before
// the jump (within 1e-12), the other joints moved to make that so, and the holds keep the
// tip to 1e-9 from the first step (no start transient to wait out). A jump the held
// directions do not see (the base joint turns about the vertical, only z held) moves no
// other joint; a coupled joint's follower follows its leader's jump; a motion not finite
// at t (its velocity overflows) changes nothing.
TEST(PrescribedMotion, AJumpOntoTheTrajectoryKeepsTheHeldDirections) {
  const Model m = lwr();
  const int tip = m.link_index("lwr_link_7");
  Simulator sim(m);
  sim.reset(lwr_q0(), {});
  for (int k = 0; k < kNumDirections; ++k) sim.set_direction(k, DirectionMode::Hold);
  const Eigen::VectorXd q0 = sim.q;
  const Transform before = forward_kinematics(m, sim.q)[tip];
  const JointMotion base = sine(0.5, 0.2, 0.3, 0);
  sim.prescribe(0, base);
  EXPECT_EQ(sim.q[0], 0.5);
  EXPECT_EQ(sim.qd[0], sample(base, 0).qd);
  const Transform after = forward_kinematics(m, sim.q)[tip];
  EXPECT_LT((after.p - before.p).norm(), 1e-12);
  EXPECT_LT(Eigen::AngleAxisd(after.R * before.R.transpose()).angle(), 1e-12);
  EXPECT_LT(link_velocities(m, sim.q, sim.qd)[tip].norm(), 1e-12) << "the tip at rest";
  EXPECT_GT((sim.q - q0).tail(6).cwiseAbs().maxCoeff(), 1e-2) << "the free joints moved";
  double worst = 0;
  for (int k = 0; k < 200; ++k) {
    sim.step(1e-3);
    for (double r : sim.residuals()) worst = std::max(worst, std::abs(r));
  }
  EXPECT_LT(worst, 1e-9) << "held from the first step";

  Simulator z_only(m);
  z_only.reset(lwr_q0(), {});
  z_only.set_direction(2, DirectionMode::Hold);
  z_only.prescribe(0, ramp(0.3, 0.5));
  EXPECT_EQ(z_only.qd[0], 0.5);
  EXPECT_LT(z_only.qd.tail(6).cwiseAbs().maxCoeff(), 1e-12) << "the base's turn moves the tip along no held direction";

  // A coupled joint's follower follows its leader's jump: the Panda-like arm's right
  // finger mimics the left one (multiplier 1), which is put on a ramp already open.
  const Model panda = load_urdf_file((kRoot / "robots/panda_fingers.urdf").string(), "panda_link0", "");
  ASSERT_EQ(panda.couplings.size(), 1u);
  const int leader = panda.couplings[0].leader, follower = panda.couplings[0].follower;
  Simulator fingers(panda);
  fingers.reset(Eigen::VectorXd::Zero(panda.num_positions()), {});
  fingers.prescribe(leader, ramp(0.02, 0.05));
  EXPECT_EQ(fingers.q[leader], 0.02);
  EXPECT_EQ(fingers.qd[leader], 0.05);
  EXPECT_NEAR(fingers.q[follower], 0.02, 1e-12);
  EXPECT_NEAR(fingers.qd[follower], 0.05, 1e-12);

  JointMotion overflowing = sine(0.3, 1e300, 1e10, 0);
  const Eigen::VectorXd q_held = z_only.q, qd_held = z_only.qd;
  try {
    z_only.prescribe(1, overflowing);
    ADD_FAILURE() << "a motion whose velocity overflows was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lwr_joint_2"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(z_only.prescribed(1));
  EXPECT_EQ(z_only.q, q_held);
  EXPECT_EQ(z_only.qd, qd_held);
}

TEST(PrescribedMotion, ReleaseAndResetFreeTheJoint) {
  const Model m = lwr();
  Simulator sim(m);
  sim.reset(lwr_q0(), {});
  sim.prescribe(1, sine(0.6, 0.1, 1, 0));
  sim.run(10, 1e-3);
  const double qd = sim.qd[1];
  sim.release(1);
  EXPECT_FALSE(sim.prescribed(1));
  EXPECT_EQ(sim.qd[1], qd) << "released from where it is";
  sim.step(1e-3);
  EXPECT_EQ(sim.data().prescribed_torques[1], 0.0);
  sim.prescribe(1, sine(0.6, 0.1, 1, 0));
  sim.reset(lwr_q0(), {});
  EXPECT_FALSE(sim.prescribed(1));
}

TEST(PrescribedMotion, BadMotionsAndJointsAreNamed) {
  const Model m = lwr();
  Simulator sim(m);
  const auto message = [&](int joint, const JointMotion& motion) {
    try {
      sim.prescribe(joint, motion);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(7, ramp(0, 1)), "prescribe: joint index 7 is not in 0..6");
  EXPECT_EQ(message(1, sine(0, 1, -1, 0)), "joint 'lwr_joint_2': frequency must be >= 0 (Hz)");
  EXPECT_EQ(message(1, sine(0, NAN, 1, 0)), "joint 'lwr_joint_2': amplitude is not finite");
  JointMotion bad = ramp(0, 1);
  bad.amplitude = 2;
  EXPECT_EQ(message(0, bad), "joint 'lwr_joint_1': amplitude is not a parameter of a 'ramp' motion");
  EXPECT_FALSE(sim.prescribed(0)) << "a refused motion changes nothing";
  EXPECT_THROW(sim.motion(0), Error);
}

}  // namespace
