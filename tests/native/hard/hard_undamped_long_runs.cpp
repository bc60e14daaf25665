// Long undamped runs under the simulator's defaults, where nothing dissipates so that
// every lost joule and every held residual is the integrator's and the solver's error.
//
// An hour of the undamped KUKA LWR 4 holding z and rx with the simulator's defaults
// (robots/scenes/kuka_lwr4_undamped_hold_z_rx.json: damping and friction off, the wrist
// turning at up to about 100 rad/s). Before the adaptive default, RK4 at the page's 1 ms lost 6e-2 J in 10 s,
// drifted 1.6 mm by 600 s and failed at 612.5 s. With the defaults (Dormand-Prince, rtol
// 1e-9, atol 1e-11) the run completes, the energy stays within 1e-6 of the largest kinetic
// energy and every held residual within 1e-6 at every output step (measured: energy drift
// 2.7e-8, held residual 2.4e-10, the wrist up to 531 rad/s). Release stage only: 3.6e6
// output steps, 1.07e7 substeps, 2.4e5 rejected; 87 s of CPU (324 s wall on the shared
// 2-core machine at a load of 6).
//
// A minute of the undamped 50-joint chain holding its tip in x, y and z
// (robots/scenes/chain50_undamped_hold_xyz.json): 47 free degrees of freedom, 1.2 kJ of
// kinetic energy at its largest. Measured: held residual 1.3e-9 m, energy drift 9.8e-8,
// no direction event, 4.07e5 substeps, 27 s of CPU.
#include <gtest/gtest.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "achd/achd.hpp"
#include "scene_json.hpp"

namespace achd::test {
namespace {

// The scene conserves energy and runs with the simulator's defaults.
void expect_undamped_with_defaults(const cli::Scene& scene) {
  EXPECT_TRUE(scene.conserves_energy());
  const SimulatorOptions defaults;
  EXPECT_EQ(scene.options.integrator, defaults.integrator);
  EXPECT_EQ(scene.options.rtol, defaults.rtol);
  EXPECT_EQ(scene.options.atol, defaults.atol);
  EXPECT_EQ(scene.options.stabilisation_frequency, defaults.stabilisation_frequency);
}

TEST(HardUndampedLongRuns, DefaultsKeepEnergyAndHeldDirectionsForAnHour) {
  cli::Scene scene = cli::load_scene(ACHD_SOURCE_DIR "/robots/scenes/kuka_lwr4_undamped_hold_z_rx.json");
  expect_undamped_with_defaults(scene);
  ASSERT_EQ(scene.dt, 1e-3);  // the page's step
  Simulator sim(scene.model, scene.options);
  cli::start_scene(scene, sim);
  const double E0 = sim.energy();
  double max_T = sim.kinetic_energy(), max_dE = 0, max_residual = 0, max_speed = 0;
  const auto wall0 = std::chrono::steady_clock::now();
  const std::int64_t steps = steps_for_duration(3600, scene.dt);
  for (std::int64_t k = 0; k < steps; ++k) {
    sim.step(scene.dt);  // an achd::Error fails the test, naming the step
    max_T = std::max(max_T, sim.kinetic_energy());
    max_dE = std::max(max_dE, std::abs(sim.energy() - E0));
    const auto r = sim.residuals();
    max_residual = std::max({max_residual, std::abs(r[2]), std::abs(r[3])});
    max_speed = std::max(max_speed, sim.qd.cwiseAbs().maxCoeff());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  std::printf("3600 s: energy drift %.3g (max |E - E0| %.3g J, max T %.4g J), max held residual %.3g, "
              "max |qd| %.3g rad/s, %lld substeps, %lld rejected, %.1f s wall\n",
              max_dE / max_T, max_dE, max_T, max_residual, max_speed, static_cast<long long>(sim.substeps()),
              static_cast<long long>(sim.rejected_substeps()), wall);
  EXPECT_EQ(sim.t, 3600.0);
  EXPECT_GT(max_speed, 50.0);  // the wrist spins: the hard part of the run
  EXPECT_LE(max_dE, 1e-6 * max_T);
  EXPECT_LE(max_residual, 1e-6);
  const auto r = sim.max_residuals();
  EXPECT_LE(std::max(r[2], r[3]), 1e-6);
}

TEST(HardUndampedLongRuns, FiftyJointChainHoldsItsTipInThreeDirectionsForAMinute) {
  cli::Scene scene = cli::load_scene(ACHD_SOURCE_DIR "/robots/scenes/chain50_undamped_hold_xyz.json");
  expect_undamped_with_defaults(scene);
  ASSERT_EQ(scene.model.num_rates(), 50);
  ASSERT_EQ(scene.steps(), 60000);
  Simulator sim(scene.model, scene.options);
  cli::start_scene(scene, sim);
  const double E0 = sim.energy();
  double max_T = sim.kinetic_energy(), max_dE = 0, max_residual = 0;
  const auto wall0 = std::chrono::steady_clock::now();
  for (std::int64_t k = 0; k < scene.steps(); ++k) {
    sim.step(scene.dt);
    max_T = std::max(max_T, sim.kinetic_energy());
    max_dE = std::max(max_dE, std::abs(sim.energy() - E0));
    const auto r = sim.residuals();
    max_residual = std::max({max_residual, std::abs(r[0]), std::abs(r[1]), std::abs(r[2])});
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  std::printf("60 s: energy drift %.3g (max |E - E0| %.3g J, max T %.4g J), max held residual %.3g m, %zu events, "
              "%lld substeps, %lld rejected, %.1f s wall\n",
              max_dE / max_T, max_dE, max_T, max_residual, sim.events().size(),
              static_cast<long long>(sim.substeps()), static_cast<long long>(sim.rejected_substeps()), wall);
  EXPECT_EQ(sim.t, 60.0);
  EXPECT_GT(max_T, 100.0);  // the chain swings: 47 free degrees of freedom under gravity
  EXPECT_LE(max_dE, 1e-6 * max_T);
  EXPECT_LE(max_residual, 1e-8);
  const auto r = sim.max_residuals();
  EXPECT_LE(std::max({r[0], r[1], r[2]}), 1e-8);
  EXPECT_TRUE(sim.events().empty());
}

}  // namespace
}  // namespace achd::test
