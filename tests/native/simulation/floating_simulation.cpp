// The simulator stepping a floating base (q: position and unit quaternion first, qd: [v; w]
// in world axes; kinematics.hpp's integrate moves q): against motions known in closed form.
//   - Free fall: the quadruped at rest with no torques falls as one body, z = z0 - g t^2 / 2,
//     its joints and orientation unchanged (every integrator; RK4 is exact on a quadratic).
//   - A free rigid body (a box: the floating root alone) spinning about a principal axis
//     turns at a constant rate: its quaternion after t is the turn by w t about that axis.
//   - Spinning about any other axis (Euler's equations, no closed form): its kinetic energy
//     and its angular momentum R I R^T w (world axes) stay constant (the quaternion is
//     integrated as the ODE dh/dt = 1/2 [w; 0] (x) h and normalised after each step, which
//     keeps the integrator's order: with the turns of the averaged rates instead, RK4's
//     error here fell only 4x when dt halved).
//   - Steps allocate nothing, and the quaternion stays unit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"

namespace achd::test {
namespace {

Model load_floating(const std::string& path_or_text, bool text) {
  UrdfOptions options;
  options.floating = true;
  return text ? load_urdf_string(path_or_text, "", "", options) : load_urdf_file(path_or_text, "", "", options);
}

// A box of 2 kg, 0.4 x 0.3 x 0.2 m, its centre of mass at its origin: principal axes x, y, z;
// a massless marker fixed on it (the simulator's records need a link after the root).
const char* kBox = R"(<?xml version="1.0"?>
<robot name="box"><link name="box"><inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="2"/>
<inertia ixx="0.0216667" iyy="0.0333333" izz="0.0416667" ixy="0" ixz="0" iyz="0"/></inertial></link>
<link name="marker"/><joint name="marker_joint" type="fixed"><parent link="box"/><child link="marker"/>
<origin xyz="0.2 0 0" rpy="0 0 0"/></joint></robot>)";

// A zero quaternion is no orientation: reset() and step() name it as such, in q's terms,
// instead of failing later on a held direction's non-finite target.
TEST(FloatingSimulation, AZeroQuaternionIsNamed) {
  const Model m = load_floating(std::string(ACHD_SOURCE_DIR) + "/robots/quadruped.urdf", false);
  Simulator sim(m);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.num_positions());
  try {
    sim.reset(q, Eigen::VectorXd());
    ADD_FAILURE() << "reset took a zero quaternion";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "q0[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero");
  }
  q[6] = 1e-300;  // any length but zero is an orientation
  sim.reset(q, Eigen::VectorXd());
  sim.q.segment<4>(3).setZero();
  try {
    sim.step(1e-3);
    ADD_FAILURE() << "step took a zero quaternion";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "q[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero");
  }
}

TEST(FloatingSimulation, FreeFallIsOneBodyFalling) {
  const Model m = load_floating(std::string(ACHD_SOURCE_DIR) + "/robots/quadruped.urdf", false);
  for (Integrator integrator : {Integrator::RK4, Integrator::DormandPrince, Integrator::SemiImplicitEuler}) {
    SimulatorOptions o;
    o.integrator = integrator;
    o.effects = kAllEffects;
    Simulator sim(m, o);
    Eigen::VectorXd q0 = Case::zeros(m).q;
    q0[2] = 1.0;
    q0.segment<4>(3) = Eigen::Vector4d(0.1, -0.2, 0.3, 0.9).normalized();  // (qx, qy, qz, qw)
    for (int i = 7; i < q0.size(); ++i) q0[i] = 0.3 * std::sin(i);
    sim.reset(q0, Eigen::VectorXd());
    sim.run(1000, 1e-3);
    const double g = 9.81, t = sim.t;
    EXPECT_NEAR(t, 1.0, 1e-12);
    Eigen::VectorXd expected = q0;
    expected[2] = 1.0 - g * t * t / 2;
    const double tol = integrator == Integrator::SemiImplicitEuler ? 1e-2 : 1e-9;  // first order: g dt t / 2
    EXPECT_LE((sim.q - expected).lpNorm<Eigen::Infinity>(), tol) << integrator_name(integrator);
    EXPECT_NEAR(sim.qd[2], -g * t, 1e-9) << integrator_name(integrator);
    EXPECT_NEAR(sim.q.segment<4>(3).norm(), 1.0, 1e-14);
  }
}

TEST(FloatingSimulation, SpinAboutAPrincipalAxisIsAConstantTurn) {
  const Model m = load_floating(kBox, true);
  EXPECT_EQ(m.num_rates(), 6);
  SimulatorOptions o;
  o.gravity = Vector3::Zero();
  Simulator sim(m, o);
  Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(6);
  qd0[5] = 2.0;  // 2 rad/s about z
  sim.reset(Case::zeros(m).q, qd0);
  sim.run(1500, 1e-3);
  const double angle = 2.0 * sim.t;
  const Eigen::Vector4d expected(0, 0, std::sin(angle / 2), std::cos(angle / 2));
  EXPECT_LE((sim.q.segment<4>(3) - expected).norm(), 1e-12);
  EXPECT_LE(sim.q.head<3>().norm(), 1e-15);
  EXPECT_LE((sim.qd - qd0).norm(), 1e-12);
}

TEST(FloatingSimulation, FreeSpinKeepsEnergyAndAngularMomentum) {
  const Model m = load_floating(kBox, true);
  SimulatorOptions o;
  o.gravity = Vector3::Zero();
  const double dt = 1e-3;
  Simulator sim(m, o);
  Eigen::VectorXd qd0 = Eigen::VectorXd::Zero(6);
  qd0.tail<3>() << 1.0, 3.0, 0.5;  // near the unstable middle axis: the body tumbles
  sim.reset(Case::zeros(m).q, qd0);
  const Matrix3 I_body = Vector3(0.0216667, 0.0333333, 0.0416667).asDiagonal();
  auto momentum = [&] {
    const Eigen::Vector4d h = sim.q.segment<4>(3);
    const Matrix3 R = Eigen::Quaterniond(h[3], h[0], h[1], h[2]).normalized().toRotationMatrix();
    return Vector3(R * I_body * R.transpose() * sim.qd.tail<3>());
  };
  const Vector3 L0 = momentum();
  const double T0 = sim.kinetic_energy();
  double worst_L = 0, worst_T = 0;
  for (int k = 0; k < 50; ++k) {
    sim.run(static_cast<int>(0.1 / dt + 0.5), dt);
    worst_L = std::max(worst_L, (momentum() - L0).norm() / L0.norm());
    worst_T = std::max(worst_T, std::abs(sim.kinetic_energy() - T0) / T0);
  }
  std::printf("free spin, 5 s: angular momentum %.2e, kinetic energy %.2e (relative)\n", worst_L, worst_T);
  EXPECT_LE(worst_L, 1e-10);
  EXPECT_LE(worst_T, 1e-10);
  EXPECT_GT((sim.qd.tail<3>() - qd0.tail<3>()).norm(), 0.1);  // it did tumble
}

}  // namespace
}  // namespace achd::test
