// Driver priorities in the simulator (Simulator::set_direction_weights): the KUKA LWR 4
// holds z and rx at its tip while a person pushes the tip along z with 20 N. With the
// default weights the held z resists the push (the tip stays); with w_fext = 0 on z the
// push passes through and, the target re-anchored every step, moves the tip more than
// 1 cm along z in a second, while rx, which still resists, stays held to 1e-6 rad.
#include <gtest/gtest.h>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"

namespace achd {
namespace {

const std::string kUrdf = std::string(ACHD_SOURCE_DIR) + "/robots/kuka_lwr4.urdf";
constexpr int kZ = 2, kRx = 3;

struct PushRun {
  double z_moved, rx_max_residual, z_max_residual;
};

PushRun push(double w_fext_z) {
  const Model m = load_urdf_file(kUrdf, "lwr_base_link", "lwr_link_7");
  Simulator sim(m);
  Eigen::VectorXd q0(7);
  q0 << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  sim.reset(q0, Eigen::VectorXd::Zero(7));
  sim.set_direction(kZ, DirectionMode::Hold);
  sim.set_direction(kRx, DirectionMode::Hold);
  sim.set_direction_weights(kZ, w_fext_z, 1);
  sim.f_ext.assign(m.num_links(), Vector6::Zero());
  sim.f_ext.back()[2] = 20;  // 20 N up on the tip link
  const double z0 = forward_kinematics(m, sim.q).back().p.z();
  sim.run(1000, 1e-3);
  const double z1 = forward_kinematics(m, sim.q).back().p.z();
  return {z1 - z0, sim.max_residuals()[kRx], sim.max_residuals()[kZ]};
}

TEST(SimulatorDriverWeights, AHeldDirectionResistsAPushByDefault) {
  const PushRun r = push(1);
  EXPECT_LE(std::abs(r.z_moved), 1e-6) << "the held z moved";
  EXPECT_LE(r.rx_max_residual, 1e-6);
}

TEST(SimulatorDriverWeights, WithWFextZeroThePushMovesTheHeldDirectionAndTheOthersHold) {
  const PushRun r = push(0);
  std::printf("  w_fext = 0 on z: the tip moved %.4f m along z in 1 s; rx residual %.3g rad\n", r.z_moved,
              r.rx_max_residual);
  EXPECT_GT(r.z_moved, 0.01);
  EXPECT_LE(r.rx_max_residual, 1e-6);
}

TEST(SimulatorDriverWeights, WeightsOutsideTheUnitIntervalAreNamed) {
  const Model m = load_urdf_file(kUrdf, "lwr_base_link", "lwr_link_7");
  Simulator sim(m);
  try {
    sim.set_direction_weights(kZ, 1.5, 1);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("direction z: w_fext must be in [0, 1]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace achd
