// Real robots stand with two numbers: ANYmal C, Solo12 and Go2 on four feet held in x, y,
// z and Talos on both soles held in 6D (robots/scenes/*_stand.json: the robots of
// example-robot-data on a floating base, in their SRDF standing poses, under the joint PD
// controller given as {"frequency": 5, "damping_ratio": 1, "feedforward": "hold"}) run 10
// s with the simulator's defaults. Each: every foot residual <= 1e-6 m (rad), the trunk
// within 2 cm of its start height, and at the end the feet carry the robot's weight (the
// vertical forces of their constraint wrenches sum to m g within 1%). The CPU time per
// simulated second is printed.
#include <gtest/gtest.h>

#include <cmath>
#include <ctime>
#include <string>

#include "achd/achd.hpp"
#include "scene_json.hpp"

namespace achd::test {
namespace {

void stands(const std::string& name) {
  const std::string path = std::string(ACHD_SOURCE_DIR) + "/robots/scenes/" + name + ".json";
  const cli::Scene scene = cli::load_scene(path);
  ASSERT_TRUE(scene.model.floating);
  Simulator sim(scene.model, scene.options);
  cli::start_scene(scene, sim);
  const double z0 = sim.q[2];
  double worst_residual = 0, worst_height = 0;
  const std::clock_t start = std::clock();
  for (std::int64_t k = 0; k < scene.steps(); ++k) {
    sim.step(scene.dt);
    for (const LinkDirections& set : sim.direction_sets())
      for (double r : sim.residuals(set.link)) worst_residual = std::max(worst_residual, std::abs(r));
    worst_height = std::max(worst_height, std::abs(sim.q[2] - z0));
  }
  const double cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  double mass = 0;
  for (const Body& b : scene.model.bodies) mass += b.inertia.topLeftCorner<3, 3>().trace() / 3;
  double fz = 0;
  for (const Vector6& w : sim.data().constraint_wrenches) fz += w[2];
  const double weight = mass * 9.81;
  std::printf("%s: %.1f s, feet residual %.3g, trunk height change %.3g m, feet carry %.6g N of m g = %.6g N, "
              "%.3g s CPU per simulated s, %lld substeps\n",
              name.c_str(), sim.t, worst_residual, worst_height, std::abs(fz), weight, cpu / sim.t,
              static_cast<long long>(sim.substeps()));
  EXPECT_NEAR(sim.t, scene.duration, 1e-9);
  EXPECT_LE(worst_residual, 1e-6);
  EXPECT_LE(worst_height, 0.02);
  EXPECT_NEAR(std::abs(fz), weight, 0.01 * weight);
}

TEST(RealRobotsStand, AnymalCOnFourFeet) { stands("anymal_c_stand"); }
TEST(RealRobotsStand, Solo12OnFourFeet) { stands("solo12_stand"); }
TEST(RealRobotsStand, Go2OnFourFeet) { stands("go2_stand"); }
TEST(RealRobotsStand, TalosOnBothSoles) { stands("talos_stand"); }

}  // namespace
}  // namespace achd::test
