// Stiff joint PD on light links with the simulator's defaults: Dormand-Prince detects the
// stiffness and takes its substeps with the extrapolated implicit Euler method.
//   - The floating humanoid on both soles held in 6D under kp 1500, kd 30 (its hands' and
//     wrists' decay rates kd / m reach about 1e5 1/s) runs 10 s: soles within 1e-9, no
//     direction event, most substeps stiff, at most 1 s CPU per simulated second (plain
//     Dormand-Prince took 3.1 s/s; 0.31 to 0.36 s/s while every solve took the
//     variable-damping policy's eigen-decomposition, 0.15 to 0.16 since its soles' coupling
//     is proved outside the singular region without one, on a loaded 2-core machine: above
//     the 0.1 s/s aimed at). It still moves slowly after seconds (|qd| about 0.01), and at
//     rtol 1e-9 the extrapolation's error falls about tenfold a row: 5 rows (15 solves) a
//     1 ms substep, and no row count does better at its own largest substep (14 to 17
//     solves per ms for 4 to 6 rows), so dt = 1 ms is not what binds; about 17000 solves per
//     simulated s (47000 of the 10 s run's 227000 are plain Dormand-Prince's before the
//     stiffness is detected at 0.185 s). robots/scenes/humanoid_stiff_hold.json is this
//     scene (tests/native/hard/hard_scenes.cpp).
//   - The dual-arm torso holding both hands in 6D under kp 1e4, kd 100 runs 10 s: hands
//     within 1e-9, at most 0.1 s CPU per simulated second (0.02 measured, 0.05 before the
//     eigen-decomposition-free proof; plain Dormand-Prince 0.39).
//   - The stiff substeps keep the accuracy the tolerances ask: the humanoid's first 0.5 s
//     (stiff from about 0.19 s) at the default tolerances and at rtol 1e-11, atol 1e-13
//     (where the substeps the accuracy needs are below Dormand-Prince's stability bound:
//     plain Dormand-Prince) end within 1e-9 rad of each other (2.8e-13 measured).
// The CPU time is std::clock's: this process's, which a loaded machine's other work does
// not count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>

#include "achd/achd.hpp"
#include "scene_json.hpp"

namespace achd::test {
namespace {

const std::string kHold = R"({"x": "hold", "y": "hold", "z": "hold", "rx": "hold", "ry": "hold", "rz": "hold"})";

// The humanoid crouched (hips -0.4, knees 0.8, ankles -0.4, elbows -0.5, shoulders 0.2 rad),
// both soles held in 6D, the PD pulling its waist and arms to another pose.
std::string humanoid_scene(double duration) {
  return R"({"urdf": "robots/humanoid.urdf", "root": "pelvis", "floating": true,
    "q0": [0, 0, 0.9, 0, 0, 0, 1, 0, 0, 0, 0, 0.2, 0, 0, -0.5, 0, 0, 0, 0.2, 0, 0, -0.5, 0, 0, 0,
           0, 0, -0.4, 0.8, -0.4, 0, 0, 0, -0.4, 0.8, -0.4, 0],
    "link_directions": [{"link": "l_sole", "directions": )" +
         kHold + R"(}, {"link": "r_sole", "directions": )" + kHold + R"(}],
    "joint_control": {"target": [0, 0, 0.9, 0, 0, 0, 1, 0.2, 0, 0, 0, 0.6, 0, 0, -1.2, 0, 0.3, 0, -0.3, 0, 0, -0.9,
                                 0, 0, 0, 0, 0, -0.4, 0.8, -0.4, 0, 0, 0, -0.4, 0.8, -0.4, 0],
                      "kp": [0, 0, 0, 0, 0, 0, )" +
         [] {
           std::string s;
           for (int i = 0; i < 30; ++i) s += i ? ", 1500" : "1500";
           return s;
         }() +
         R"(], "kd": [0, 0, 0, 0, 0, 0, )" +
         [] {
           std::string s;
           for (int i = 0; i < 30; ++i) s += i ? ", 30" : "30";
           return s;
         }() +
         R"(]},
    "duration": )" + std::to_string(duration) + "}";
}

// The dual-arm torso in the box scene's closed pose, both hands held in 6D, the PD pulling
// toward the box scene's target (waist 0.3 rad, each arm's joints 2 and 4 by 0.15 rad).
std::string torso_scene(double duration) {
  return R"({"urdf": "robots/dual_arm_torso.urdf", "root": "base_link",
    "q0": [0, -0.2251111675672723, 0.994585533260283, 3.316291633579657, -1.82954602513583, -0.43284629288363236,
           -0.35486759541773044, 0.27962212289617194, 0.09089907487570212, 0.9905810871329143, 3.17540914622311,
           -1.8252529029685591, -0.08809570701542108, -0.3272015854203541, 0.19288645061626766],
    "link_directions": [{"link": "left_hand", "directions": )" +
         kHold + R"(}, {"link": "right_hand", "directions": )" + kHold + R"(}],
    "joint_control": {"target": [0.3, -0.2251111675672723, 1.144585533260283, 3.316291633579657, -1.67954602513583,
                                 -0.43284629288363236, -0.35486759541773044, 0.27962212289617194, 0.09089907487570212,
                                 1.1405810871329143, 3.17540914622311, -1.6752529029685592, -0.08809570701542108,
                                 -0.3272015854203541, 0.19288645061626766],
                      "kp": 1e4, "kd": 100},
    "duration": )" + std::to_string(duration) + "}";
}

struct Result {
  double worst_residual = 0, cpu_per_s = 0;
  std::int64_t substeps = 0, stiff = 0, rejected = 0;
  std::size_t events = 0;
  Eigen::VectorXd q;
};

Result run(const std::string& name, const std::string& text, double rtol = kDefaultRtol, double atol = kDefaultAtol) {
  const cli::Scene scene = cli::parse_scene(text, std::string(ACHD_SOURCE_DIR) + "/robots/scenes/" + name + ".json");
  SimulatorOptions options = scene.options;
  options.rtol = rtol;
  options.atol = atol;
  Simulator sim(scene.model, options);
  cli::start_scene(scene, sim);
  Result r;
  const std::clock_t start = std::clock();
  for (std::int64_t k = 0; k < scene.steps(); ++k) {
    sim.step(scene.dt);
    for (const LinkDirections& set : sim.direction_sets())
      for (double x : sim.residuals(set.link)) r.worst_residual = std::max(r.worst_residual, std::abs(x));
  }
  r.cpu_per_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC / sim.t;
  r.substeps = sim.substeps();
  r.stiff = sim.stiff_substeps();
  r.rejected = sim.rejected_substeps();
  r.events = sim.events().size();
  r.q = sim.q;
  std::printf("%s, %.2f s (rtol %.3g): held residual %.3g, %lld substeps (%lld stiff, %lld rejected), %zu events, "
              "%.3g s CPU per simulated s\n",
              name.c_str(), sim.t, rtol, r.worst_residual, static_cast<long long>(r.substeps),
              static_cast<long long>(r.stiff), static_cast<long long>(r.rejected), r.events, r.cpu_per_s);
  return r;
}

TEST(StiffRobots, HumanoidOnBothSolesUnderKp1500Kd30) {
  const Result r = run("humanoid_stiff_pd", humanoid_scene(10));
  EXPECT_LE(r.worst_residual, 1e-9);
  EXPECT_EQ(r.events, 0u);
  EXPECT_GT(r.stiff, r.substeps / 2);  // the detection found the stiffness and kept it
  EXPECT_LE(r.cpu_per_s, 1.0);
}

TEST(StiffRobots, DualArmTorsoHoldingBothHandsUnderKp1e4Kd100) {
  const Result r = run("torso_stiff_pd", torso_scene(10));
  EXPECT_LE(r.worst_residual, 1e-9);
  EXPECT_EQ(r.events, 0u);
  EXPECT_GT(r.stiff, 0);
  EXPECT_LE(r.cpu_per_s, 0.1);
}

// The stiff substeps are as accurate as the tolerances say: tightening them 100-fold (plain
// Dormand-Prince then) moves the end pose by less than 1e-9 rad (m).
TEST(StiffRobots, HumanoidTighterTolerancesAgree) {
  const Result loose = run("humanoid_stiff_pd", humanoid_scene(0.5));
  const Result tight = run("humanoid_stiff_pd", humanoid_scene(0.5), 1e-11, 1e-13);
  EXPECT_GT(loose.stiff, 0);
  const double diff = (loose.q - tight.q).cwiseAbs().maxCoeff();
  std::printf("end poses differ by %.3g\n", diff);
  EXPECT_LE(diff, 1e-9);
}

}  // namespace
}  // namespace achd::test
