// Runs of the simulator that were silently wrong: step counts in 64 bits with
// the whole-number rule of steps_for_duration, t = k dt exactly, and a failed step that
// leaves the last good state (finite) and an achd::Error naming the step, the time, the
// held and accelerated directions and the cause.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "accuracy_study.hpp"
#include "achd/achd.hpp"
#include "achd/names.hpp"
#include "achd/simulator.hpp"
#include "scene_json.hpp"

namespace achd {
namespace {

const std::filesystem::path kRoot = ACHD_SOURCE_DIR;

std::string error_of(double duration, double dt) {
  try {
    steps_for_duration(duration, dt);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

void expect_contains(const std::string& text, const std::vector<std::string>& needles) {
  for (const std::string& n : needles) EXPECT_NE(text.find(n), std::string::npos) << "'" << n << "' not in: " << text;
}

// Before: int steps = lround(duration / dt) gave -2094967296 for 2.2e6 s and 5032704
// for 4.3e6 s at 1 ms.
TEST(StepsForDuration, CountsBeyondIntAreExact) {
  EXPECT_EQ(steps_for_duration(2.0, 1e-3), 2000);
  EXPECT_EQ(steps_for_duration(2.2e6, 1e-3), 2200000000LL);
  EXPECT_EQ(steps_for_duration(4.3e6, 1e-3), 4300000000LL);
  EXPECT_EQ(steps_for_duration(0, 1e-3), 0);
  // Within 1e-9 (relative) of a whole number: that number.
  EXPECT_EQ(steps_for_duration(1 + 4e-10, 1e-3), 1000);
  EXPECT_EQ(steps_for_duration(std::ldexp(1.0, 52), 1.0), std::int64_t(1) << 52);
}

TEST(StepsForDuration, AnythingElseIsAnErrorNamingTheCount) {
  // Not a whole number (before: rounded to 1000 steps, t = 1.0000000000000007).
  expect_contains(error_of(1.0005, 1e-3), {"duration 1.0005 s", "dt 0.001 s", "1000.5 steps", "not a whole number"});
  // Zero steps for a positive duration (before: 0 steps, t = 0, exit 0).
  expect_contains(error_of(1e-4, 1e-3), {"0.1 steps", "not a whole number"});
  // More than 2^53 (before: dt 1e-300 gave "steps": 0).
  expect_contains(error_of(1, 1e-300), {"1e+300 steps", "dt 1e-300 s", "2^53"});
  // A whole count below 2^53 whose step is below the spacing of doubles at the end:
  // 1.5 s steps up to t = 1.35e16 s, where doubles are 2 s apart.
  const double n = std::ldexp(1.0, 53) - 1;
  expect_contains(error_of(n * 1.5, 1.5), {"9007199254740991 steps", "t + dt == t"});
  expect_contains(error_of(1, 0), {"dt must be positive"});
  expect_contains(error_of(-1, 1e-3), {"duration must be finite and >= 0"});
}

// t is computed as t0 + k dt, so the summary's steps * dt is the simulated time (before:
// a running sum, 2183 steps of 1 ms ended at t = 2.1829999999998706).
TEST(SimulatorTime, IsStepsTimesDt) {
  const Model m = load_urdf_file((kRoot / "robots/planar2.urdf").string(), "base_link", "link2");
  Simulator sim(m);
  sim.reset(Eigen::Vector2d(0.4, 0.9), {});
  sim.run(2183, 1e-3);
  EXPECT_EQ(sim.t, 2183 * 1e-3);
  EXPECT_EQ(sim.steps_taken(), 2183);
  // A new dt counts from the time reached; so does a t set by the caller.
  sim.run(10, 0.5e-3);
  EXPECT_EQ(sim.t, 2183 * 1e-3 + 10 * 0.5e-3);
  sim.t = 100;
  sim.run(3, 0.1);
  EXPECT_EQ(sim.t, 100 + 3 * 0.1);
  EXPECT_EQ(sim.steps_taken(), 2196);
  sim.reset(Eigen::Vector2d(0.4, 0.9), {});
  EXPECT_EQ(sim.t, 0);
  EXPECT_EQ(sim.steps_taken(), 0);
  EXPECT_THROW(sim.run(-1, 1e-3), Error);
}

// The UR5 holding z and rx while accelerating its tip along y at 0.5 m/s^2 (RK4, 1 ms)
// is driven into a singular pose and, under the truncate policy, blows up at t = 2.184 s
// (2.183 s while the friction smoothing velocity was raised with dt; the simulator's
// default, variable_damping, runs on: boundary_suite.cpp). Before: the error read
// "beta[0] is not finite" and nothing else.
TEST(SimulatorFailure, NamesStepTimeDirectionsAndCauseAndKeepsTheLastGoodState) {
  const Model m = load_urdf_file((kRoot / "robots/ur5.urdf").string(), "base_link", "wrist_3_link");
  SimulatorOptions o;
  o.integrator = Integrator::RK4;
  o.solver.policy = SingularityPolicy::Truncate;
  Simulator sim(m, o);
  Eigen::VectorXd q0(6);
  q0 << 0.2, -1.0, 1.2, -1.5, -1.4, 0.3;
  sim.reset(q0, {});
  sim.set_direction(index_of_direction("z"), DirectionMode::Hold);
  sim.set_direction(index_of_direction("rx"), DirectionMode::Hold);
  sim.set_direction(index_of_direction("y"), DirectionMode::Accelerate, 0.5);
  std::string what;
  try {
    sim.run(5000, 1e-3);
  } catch (const Error& e) {
    what = e.what();
  }
  expect_contains(what, {"step 2185", "t = 2.184 s", "held: z, rx", "accelerated: y = 0.5 m/s^2", "rk4",
                         "the state stays at t = 2.184 s"});
  EXPECT_EQ(what.find("beta["), std::string::npos) << what;  // a field the user never wrote
  EXPECT_EQ(sim.steps_taken(), 2184);
  EXPECT_EQ(sim.t, 2184 * 1e-3);
  EXPECT_TRUE(sim.q.allFinite() && sim.qd.allFinite());
  EXPECT_TRUE(sim.data().qdd.allFinite() && sim.data().nu.allFinite());
  // The same step fails again from the same state, with the same message.
  try {
    sim.step(1e-3);
    ADD_FAILURE() << "the failed step succeeded from the same state";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), what);
  }
}

// A step whose solve returns a non-finite acceleration without an error (ff_torques at
// 1e308 on the light planar arm: qdd overflows) is undone. Before: it returned with
// qd = inf, and the next step failed on "qd[0] is not finite".
TEST(SimulatorFailure, NonFiniteStepIsUndone) {
  const Model m = load_urdf_file((kRoot / "robots/planar2.urdf").string(), "base_link", "link2");
  for (Integrator integrator : kIntegrators) {
    SimulatorOptions o;
    o.integrator = integrator;
    Simulator sim(m, o);
    const Eigen::Vector2d q0(0.4, 0.9);
    sim.reset(q0, {});
    sim.run(5, 1e-3);
    const Eigen::VectorXd q = sim.q, qd = sim.qd;
    const double t = sim.t;
    sim.ff_torques << 1e308, -1e308;
    std::string what;
    try {
      sim.step(1e-3);
    } catch (const Error& e) {
      what = e.what();
    }
    expect_contains(what, {"step 6", "t = 0.005 s", "joint"});
    EXPECT_EQ(sim.q, q) << integrator_name(integrator);
    EXPECT_EQ(sim.qd, qd) << integrator_name(integrator);
    EXPECT_EQ(sim.t, t);
    EXPECT_EQ(sim.steps_taken(), 5);
    EXPECT_TRUE(sim.data().qdd.allFinite()) << integrator_name(integrator);
    // With sane torques again it carries on from there.
    sim.ff_torques.setZero();
    sim.step(1e-3);
    EXPECT_EQ(sim.steps_taken(), 6);
  }
}

// Scene files: the count is checked when the scene is read, in 64 bits.
TEST(SceneSteps, CheckedWhenParsedIn64Bits) {
  const std::string head = R"({"urdf": ")" + (kRoot / "robots/planar2.urdf").string() +
                           R"(", "root": "base_link", "tip": "link2", "q0": [0, 0], "dt": )";
  const cli::Scene scene = cli::parse_scene(head + R"(0.001, "duration": 4.3e6})", "long.json");
  EXPECT_EQ(scene.steps(), 4300000000LL);
  for (const auto& [text, needle] : {std::pair<std::string, std::string>{"0.001, \"duration\": 1.0005}", "1000.5 steps"},
                                     {"1e-300, \"duration\": 1}", "1e+300 steps"}}) {
    try {
      cli::parse_scene(head + text, "bad.json");
      ADD_FAILURE() << text << " was accepted";
    } catch (const Error& e) {
      expect_contains(e.what(), {"bad.json", needle});
    }
  }
}

// The study runs the simulator as configured: implicit Euler in the ladder beside the
// other fixed-step integrators, Dormand-Prince once per tolerance with its error not rising
// as the tolerance tightens (and falling over the ladder), every run with a cost. Before:
// three integrators, no adaptive runs.
TEST(AccuracyStudy, AdaptiveRunsPerToleranceAndImplicitEulerInTheLadder) {
  const cli::Scene scene = cli::load_scene((kRoot / "robots/scenes/planar2_damped_swing.json").string());
  const cli::StudyConfig config = cli::default_config(scene, true);
  const cli::Study study = cli::run_study(scene, config);
  std::vector<double> adaptive;
  int implicit = 0;
  for (const cli::StudyRun& r : study.runs) {
    EXPECT_GT(r.ns_per_step, 0) << r.kind << " " << r.integrator << " " << r.setting;
    if (r.kind != "integrator") continue;
    if (r.integrator == "implicit_euler") ++implicit;
    if (r.integrator == "dormand_prince") {
      ASSERT_TRUE(r.stable) << r.setting;
      adaptive.push_back(r.error_q);
    }
  }
  EXPECT_EQ(implicit, static_cast<int>(config.dts.size()));
  ASSERT_EQ(adaptive.size(), config.rtols.size());
  for (std::size_t i = 1; i < adaptive.size(); ++i)
    EXPECT_LE(adaptive[i], adaptive[i - 1]) << "rtol " << config.rtols[i];
  EXPECT_LT(adaptive.back(), 1e-2 * adaptive.front());
}

// The accuracy study's step count, which its guard (kMaxStudySteps) and the CLI's
// progress use, is the number of steps it takes besides the reference's refinement
// (which the study reports): where every run is stable, it is exact.
TEST(AccuracyStudySteps, PlannedAreTaken) {
  const cli::Scene scene = cli::load_scene((kRoot / "robots/scenes/planar2_damped_swing.json").string());
  const cli::StudyConfig config = cli::default_config(scene, true);
  std::int64_t taken = 0;
  const cli::Study study = cli::run_study(scene, config, [&](std::int64_t n) { taken += n; });
  for (const cli::StudyRun& r : study.runs) ASSERT_TRUE(r.stable) << r.kind << " " << r.integrator << " " << r.dt;
  EXPECT_EQ(static_cast<double>(taken),
            cli::planned_steps(scene, config) + static_cast<double>(study.reference.refinement_steps));
  // With held directions and Dormand-Prince the scene's integrator, the knobs add the held
  // drift of explicit and semi-implicit Euler and RK4, each with its default run (the
  // undamped arm holding z and rx, short and at small steps, so that every run is stable).
  const cli::Scene held = cli::load_scene((kRoot / "robots/scenes/kuka_lwr4_undamped_hold_z_rx.json").string());
  ASSERT_EQ(held.options.integrator, Integrator::DormandPrince);
  cli::StudyConfig short_config = cli::default_config(held, true);
  short_config.duration = 0.02;
  short_config.dts = {1e-3, 0.5e-3};
  short_config.reference_dt = 0.125e-3;
  taken = 0;
  const cli::Study held_study = cli::run_study(held, short_config, [&](std::int64_t n) { taken += n; });
  for (const cli::StudyRun& r : held_study.runs) ASSERT_TRUE(r.stable) << r.kind << " " << r.integrator << " " << r.dt;
  EXPECT_EQ(static_cast<double>(taken),
            cli::planned_steps(held, short_config) + static_cast<double>(held_study.reference.refinement_steps));
  // A study beyond the limit is refused before it starts, naming its step count.
  cli::StudyConfig huge = config;
  huge.duration = 1e9;
  try {
    cli::run_study(scene, huge, [&](std::int64_t) { FAIL() << "the study started"; });
    ADD_FAILURE() << "a study of 1e9 s was accepted";
  } catch (const Error& e) {
    expect_contains(e.what(), {"steps, more than the limit of 1e+08", "--quick"});
  }
}

}  // namespace
}  // namespace achd
