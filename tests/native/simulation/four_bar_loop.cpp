// The planar four-bar (robots/four_bar.urdf closed by one revolute loop joint) against
// an independent one-degree-of-freedom reference (support/four_bar_reference.hpp):
// the directions the tree cannot violate are dropped at load, a solve at a closed pose
// gives the reference's joint accelerations, and the simulator with its defaults follows
// the crank's motion, keeps the loop closed and the energy constant, on a fixed base and
// tumbling on a free joint.
#include <gtest/gtest.h>

#include <cmath>

#include "achd/achd.hpp"
#include "four_bar_reference.hpp"

namespace fb = achd::test::four_bar;

namespace {

achd::LoopJointSpec coupler_rocker() {
  achd::LoopJointSpec s;
  s.name = "coupler_rocker";
  s.link_a = "coupler";
  s.origin_a.p = achd::Vector3(fb::parameters().coupler, 0, 0);
  s.link_b = "rocker";
  s.origin_b.p = achd::Vector3(fb::parameters().rocker, 0, 0);
  s.type = achd::LoopType::Revolute;
  s.axis = achd::Vector3(0, 1, 0);
  return s;
}

achd::Model four_bar() {
  achd::UrdfOptions o;
  o.loops = {coupler_rocker()};
  return achd::load_urdf_file(std::string(ACHD_SOURCE_DIR) + "/robots/four_bar.urdf", "", "", o);
}

// q in the model's joint order from the reference's [crank, coupler, rocker] values.
Eigen::VectorXd in_model_order(const achd::Model& m, const double* x) {
  Eigen::VectorXd q(3);
  const char* names[3] = {"crank_joint", "coupler_joint", "rocker_joint"};
  for (int k = 0; k < 3; ++k) q[m.joint_index(names[k])] = x[k];
  return q;
}

double crank(const achd::Model& m, const Eigen::VectorXd& q) { return q[m.joint_index("crank_joint")]; }

}  // namespace

// The loop frame has z along the pin (the URDF's y); in the plane of motion only its x and
// y can open: the out-of-plane offset and the two tilts are held by the tree already.
TEST(FourBarLoop, PlanarLoopKeepsTheTwoInPlaneDirections) {
  const achd::Model m = four_bar();
  ASSERT_EQ(m.loops.size(), 1u);
  EXPECT_EQ(achd::loop_direction_names(m.loops[0].directions), (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(achd::loop_direction_names(m.loops[0].dropped), (std::vector<std::string>{"z", "rx", "ry"}));
  EXPECT_EQ(m.num_loop_columns(), 2);
}

// At a closed pose, at rest and moving, the solve's qdd is the reference's
// dq thetaddot + ddq thetadot^2 once the loop's beta carries the velocity terms of the
// moving pin (at rest beta = 0 is exact).
TEST(FourBarLoop, SolveAtAClosedPoseMatchesTheReference) {
  const achd::Model m = four_bar();
  achd::Data d(m);
  for (double theta : {fb::start_theta, 0.3, 1.9, -2.6}) {
    const fb::Closure c = fb::closure(theta);
    achd::Case cs = achd::Case::zeros(m);
    cs.q = in_model_order(m, c.q);
    achd::hybrid_dynamics(m, d, cs, achd::with_effects(achd::kAllEffects & ~achd::kDamping));
    const double thetaddot = fb::crank_acceleration(theta, 0);
    double expected[3];
    for (int k = 0; k < 3; ++k) expected[k] = c.dq[k] * thetaddot;
    const Eigen::VectorXd want = in_model_order(m, expected);
    EXPECT_LT((d.qdd - want).norm(), 1e-9 * (1 + want.norm())) << "theta " << theta;
    EXPECT_EQ(d.nu.size(), 2);
  }
}

// A loop column whose force is beyond a double (each joint's axial inertia 1e307, so that
// K = J M^-1 J^T underflows and nu = K^-1 beta overflows): the error names the loop and the
// direction of its column, not the block the solve keeps it under; a block of the case
// keeps its own name.
TEST(FourBarLoop, AnOverflowInALoopColumnNamesTheLoop) {
  const achd::Model m = four_bar();
  achd::Data d(m);
  achd::Case cs = achd::Case::zeros(m);
  cs.q = in_model_order(m, fb::closure(0.3).q);
  cs.extra_inertia = Eigen::Vector3d::Constant(1e307);
  cs.loop_beta = Eigen::Vector2d(1, 1);
  const auto message = [&] {
    try {
      achd::hybrid_dynamics(m, d, cs);
    } catch (const achd::Error& e) {
      return std::string(e.what());
    }
    return "solved, nu = " + std::to_string(d.nu[0]);
  };
  EXPECT_EQ(message(),
            "the solve overflows: constraint column 0 (loop 'coupler_rocker', its direction x): the constraint force "
            "nu[0] is not finite (the constraint needs a force beyond the range of a double)");
  achd::ConstraintBlock block;  // the crank's tip held along z: a block of the case, before the loop
  block.link = m.link_index("crank");
  block.alpha = achd::ConstraintMatrix::Zero(6, 1);
  block.alpha(2, 0) = 1;
  block.beta = achd::ConstraintVector::Zero(1);
  cs.constraints.push_back(block);
  EXPECT_EQ(message(),
            "the solve overflows: constraint column 0 (constraints[0].alpha[0], link 'crank'): the constraint force "
            "nu[0] is not finite (the constraint needs a force beyond the range of a double)");
}

// Undamped, under gravity, with the simulator's defaults (Dormand-Prince, its
// tolerances, stabilisation 100 rad/s): the crank angle at 1 s within 1e-6 rad of the
// reference's; over 60 s the loop stays closed (1e-9 m) and the energy constant (1e-8 of
// the energy range the linkage swings through).
TEST(FourBarLoop, SimulationFollowsTheReferenceAndHoldsTheLoop) {
  const achd::Model m = four_bar();
  achd::SimulatorOptions o;
  o.effects = achd::kAllEffects & ~achd::kDamping & ~achd::kFriction;
  achd::Simulator sim(m, o);
  const fb::Closure c0 = fb::closure(fb::start_theta);
  sim.reset(in_model_order(m, c0.q), Eigen::VectorXd::Zero(3));
  const double E0 = sim.energy();
  EXPECT_NEAR(E0, fb::energy(fb::start_theta, 0), 1e-12);
  const double dt = 1e-3;
  sim.run(1000, dt);
  const fb::CrankState ref = fb::crank_motion(fb::start_theta, 0, 1.0);
  EXPECT_NEAR(crank(m, sim.q), ref.theta, 1e-6);
  std::printf("four-bar, 1 s: crank %.17g rad, reference %.17g rad\n", crank(m, sim.q), ref.theta);
  // The energy range: from the lowest to the highest potential energy of the crank's turn.
  double v_min = 1e300, v_max = -1e300;
  for (int k = 0; k < 360; ++k) {
    const double V = fb::terms(k * M_PI / 180).V;
    v_min = std::min(v_min, V), v_max = std::max(v_max, V);
  }
  double worst_energy = 0;
  for (int s = 0; s < 59; ++s) {
    sim.run(1000, dt);
    worst_energy = std::max(worst_energy, std::abs(sim.energy() - E0));
  }
  EXPECT_LT(sim.loop_drift(0), 1e-9);
  EXPECT_LT(worst_energy, 1e-8 * (v_max - v_min)) << "energy range " << v_max - v_min;
  std::printf("four-bar, 60 s: loop drift %.3g m, energy drift %.3g J (range %.3g J), substeps %lld\n",
              sim.loop_drift(0), worst_energy, v_max - v_min, static_cast<long long>(sim.substeps()));
}

// The linkage on a free joint, tumbling (the ground link moving and turning) under gravity,
// undamped, with the simulator's defaults: the loop stays closed (1e-9 m) and the energy
// constant. (The floating solve once dropped loop_beta, which carries the loop's
// stabilisation: the loop opened by 3.4 mm in these 2 s.)
TEST(FourBarLoop, AFreeFloatingLinkageKeepsItsLoopClosed) {
  achd::UrdfOptions u;
  u.floating = true;
  u.loops = {coupler_rocker()};
  const achd::Model m = achd::load_urdf_file(std::string(ACHD_SOURCE_DIR) + "/robots/four_bar.urdf", "", "", u);
  achd::SimulatorOptions o;
  o.effects = achd::kAllEffects & ~achd::kDamping & ~achd::kFriction;
  achd::Simulator sim(m, o);
  Eigen::VectorXd q(10), qd(9);
  q << 0, 0, 1, 0, 0, 0, 1, in_model_order(four_bar(), fb::closure(fb::start_theta).q);
  qd << 0.1, 0, 0, 0.5, 0.2, 0.1, 0, 0, 0;  // the joints at rest: the loop's velocity holds
  sim.reset(q, qd);
  const double E0 = sim.energy();
  sim.run(2000, 1e-3);
  EXPECT_LT(sim.loop_drift(0), 1e-9);
  EXPECT_LT(std::abs(sim.energy() - E0), 1e-10 * std::abs(E0));
  std::printf("free-floating four-bar, 2 s: loop drift %.3g m, energy drift %.3g J of %.3g J\n", sim.loop_drift(0),
              std::abs(sim.energy() - E0), E0);
}

// A limit stop on a looped robot: the rocker given limits inside its swing, under
// LimitPolicy::Clamp. Its inelastic impact is solved with the loop's columns (their
// velocity kept), so the linkage stops as one: the loop stays closed (1e-9 m) through the
// impacts, and once on its stop the rocker (and with it the one-DoF linkage) rests there.
TEST(FourBarLoop, LimitImpactsKeepTheLoopClosed) {
  achd::Model m = four_bar();
  const int rocker = m.joint_index("rocker_joint");
  const fb::Closure c0 = fb::closure(fb::start_theta);
  m.bodies[rocker].limits.lower = c0.q[2] - 0.3;
  m.bodies[rocker].limits.upper = c0.q[2] + 0.3;
  achd::SimulatorOptions o;
  o.limits = achd::LimitPolicy::Clamp;
  achd::Simulator sim(m, o);
  sim.reset(in_model_order(m, c0.q), Eigen::VectorXd::Zero(3));
  bool stopped = false;
  for (int s = 0; s < 2000; ++s) {
    sim.step(1e-3);
    stopped = stopped || sim.limit_stop(rocker) != 0;
  }
  ASSERT_TRUE(stopped) << "the rocker never reached a limit";
  EXPECT_LT(sim.loop_drift(0), 1e-9);
  const achd::JointLimits& l = m.bodies[rocker].limits;
  const double x = sim.q[rocker];
  EXPECT_TRUE(x >= l.lower - 1e-9 && x <= l.upper + 1e-9) << "rocker at " << x;
  std::printf("four-bar on a rocker stop: rocker at %.6f rad (limits %.6f, %.6f), qd %.3g, loop drift %.3g m\n", x,
              l.lower, l.upper, sim.qd.norm(), sim.loop_drift(0));
}
