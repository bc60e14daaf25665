// The adaptive Dormand-Prince 5(4) integrator and implicit Euler (implicit in joint
// damping and friction and in the held directions' stabilisation), and physics that does not depend on the step: friction's
// smoothing velocity and the held directions' Baumgarte frequency are the options', so
// the simulator's answer at one output step equals its answer at another.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "achd/achd.hpp"
#include "scene_json.hpp"

namespace {

using namespace achd;

const std::filesystem::path kRoot = ACHD_SOURCE_DIR;

Model lwr() { return load_urdf_file((kRoot / "robots/kuka_lwr4.urdf").string(), "lwr_base_link", "lwr_link_7"); }
Eigen::VectorXd lwr_q0() {
  Eigen::VectorXd q(7);
  q << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  return q;
}

// The damped LWR holding z and rx (robots/scenes/kuka_lwr4_hold_z_rx.json), run for
// `duration` at output step dt with `options` (the scene's, changed by the caller).
Eigen::VectorXd run_hold_scene(SimulatorOptions o, double dt, double duration) {
  const cli::Scene scene = cli::load_scene((kRoot / "robots/scenes/kuka_lwr4_hold_z_rx.json").string());
  Simulator sim(scene.model, o);
  cli::start_scene(scene, sim);
  sim.run(steps_for_duration(duration, dt), dt);
  return sim.q;
}

SimulatorOptions hold_scene_options() {
  return cli::load_scene((kRoot / "robots/scenes/kuka_lwr4_hold_z_rx.json").string()).options;
}

// The same state stepped at two dt: the first solve (data(), at the state the step starts
// from) is the same, with friction on and a held direction off its target. The old
// simulator raised the friction smoothing velocity with dt and set the Baumgarte
// frequency to 0.1 / dt: its qdd differed here.
TEST(StepIndependentPhysics, TheFirstSolveOfAStepDoesNotDependOnDt) {
  SimulatorOptions o;
  o.integrator = Integrator::RK4;
  Eigen::VectorXd qdd[2];
  const double dts[2] = {1e-3, 1e-5};
  for (int r = 0; r < 2; ++r) {
    Simulator sim(lwr(), o);
    Eigen::VectorXd qd(7);
    qd << 0.01, -0.02, 0.005, 0.01, -0.01, 0.02, 0.001;  // friction in its steep part
    sim.reset(lwr_q0(), qd);
    sim.set_direction(2, DirectionMode::Hold);
    sim.q[1] += 1e-3;  // z is now off its target
    sim.step(dts[r]);
    qdd[r] = sim.data().qdd;
  }
  EXPECT_EQ(qdd[0], qdd[1]) << "qdd at dt 1 ms: " << qdd[0].transpose() << "\nat 0.01 ms: " << qdd[1].transpose();
}

TEST(StepIndependentPhysics, DefaultsAreFixedParameters) {
  const SimulatorOptions o;
  EXPECT_EQ(o.solver.friction_velocity, 0.05);
  EXPECT_EQ(o.stabilisation_frequency, kDefaultStabilisationFrequency);
  EXPECT_EQ(o.stabilisation_frequency, 100);
  EXPECT_EQ(o.stabilisation_damping, 1.0);
  EXPECT_EQ(o.integrator, Integrator::DormandPrince);
}

TEST(StepIndependentPhysics, NonPositiveStabilisationAndTolerancesAreNamedErrors) {
  const auto message = [](void (*change)(SimulatorOptions&)) {
    SimulatorOptions o;
    change(o);
    Simulator sim(lwr(), o);
    sim.reset(lwr_q0(), {});
    try {
      sim.step(1e-3);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message([](SimulatorOptions& o) { o.stabilisation_frequency = 0; }).find("stabilisation_frequency"),
            std::string::npos);
  EXPECT_NE(message([](SimulatorOptions& o) { o.stabilisation_damping = -1; }).find("stabilisation_damping"),
            std::string::npos);
  EXPECT_NE(message([](SimulatorOptions& o) { o.rtol = NAN; }).find("rtol"), std::string::npos);
  EXPECT_NE(message([](SimulatorOptions& o) { o.rtol = o.atol = 0; }).find("rtol and atol"), std::string::npos);
}

// The simulator's answer at 1 ms and at 10 ms output steps equals its answer at 0.1 ms:
// one set of equations, integrated to the tolerance whatever the output step (the old
// RK4 at 1 ms differed from its own 0.1 ms answer by 5.9e-2 rad over 2 s).
TEST(DormandPrince, TheAnswerDoesNotDependOnTheOutputStep) {
  const SimulatorOptions o = hold_scene_options();
  ASSERT_EQ(o.integrator, Integrator::DormandPrince);
  const Eigen::VectorXd fine = run_hold_scene(o, 1e-4, 2.0);
  for (double dt : {1e-3, 1e-2}) {
    const double difference = (run_hold_scene(o, dt, 2.0) - fine).cwiseAbs().maxCoeff();
    EXPECT_LT(difference, 1e-6) << "dt " << dt;
  }
}

// Against RK4 at 0.025 ms (error ~1e-12 on this scene): the error falls with rtol.
TEST(DormandPrince, ErrorFallsWithTheTolerance) {
  SimulatorOptions o = hold_scene_options();
  o.integrator = Integrator::RK4;
  const Eigen::VectorXd reference = run_hold_scene(o, 2.5e-5, 1.0);
  o.integrator = Integrator::DormandPrince;
  double previous = INFINITY;
  for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    o.rtol = rtol;
    o.atol = rtol * 1e-2;
    const double error = (run_hold_scene(o, 1e-3, 1.0) - reference).cwiseAbs().maxCoeff();
    std::printf("  rtol %g: error %.3g rad\n", rtol, error);
    EXPECT_LT(error, previous) << "rtol " << rtol;
    EXPECT_LT(error, 1e3 * rtol) << "rtol " << rtol;
    previous = error;
  }
}

// step(dt) ends on t + dt exactly, counts its substeps, and carries its substep size over:
// a stiff start rejects, later steps need fewer substeps; reset() clears the counters.
TEST(DormandPrince, StepsEndOnTheOutputTimesAndCountSubsteps) {
  SimulatorOptions o = hold_scene_options();
  const cli::Scene scene = cli::load_scene((kRoot / "robots/scenes/kuka_lwr4_hold_z_rx.json").string());
  Simulator sim(scene.model, o);
  cli::start_scene(scene, sim);
  EXPECT_EQ(sim.substeps(), 0);
  for (int k = 1; k <= 500; ++k) {
    sim.step(1e-3);
    ASSERT_EQ(sim.t, k * 1e-3);
  }
  EXPECT_GT(sim.substeps(), 500);  // friction is stiff here: more than one substep per ms
  EXPECT_GT(sim.rejected_substeps(), 0);
  EXPECT_EQ(sim.steps_taken(), 500);
  // With a 0.1 s output step the substeps are the same size: about the same count.
  Simulator coarse(scene.model, o);
  cli::start_scene(scene, coarse);
  coarse.run(5, 0.1);
  EXPECT_NEAR(static_cast<double>(coarse.substeps()), static_cast<double>(sim.substeps()),
              0.2 * static_cast<double>(sim.substeps()));
  sim.reset(lwr_q0(), {});
  EXPECT_EQ(sim.substeps(), 0);
  EXPECT_EQ(sim.rejected_substeps(), 0);
}

// A step that cannot meet its tolerance fails with the step's context, and the state,
// time and counters stay those of the last good step.
TEST(DormandPrince, AStepThatCannotProgressFailsNamingItAndKeepsTheState) {
  SimulatorOptions o;
  o.rtol = 0;
  o.atol = 1e-300;  // unreachable
  Simulator sim(lwr(), o);
  sim.reset(lwr_q0(), {});
  sim.set_direction(2, DirectionMode::Hold);
  const Eigen::VectorXd q = sim.q;
  try {
    sim.step(1e-3);
    FAIL() << "the step succeeded";
  } catch (const Error& e) {
    const std::string m = e.what();
    for (const char* part : {"step 1 from t = 0 s to 0.001 s", "dormand_prince", "held: z", "below its floor",
                             "the state stays at t = 0 s"})
      EXPECT_NE(m.find(part), std::string::npos) << part << " in: " << m;
  }
  EXPECT_EQ(sim.q, q);
  EXPECT_EQ(sim.t, 0);
  EXPECT_EQ(sim.steps_taken(), 0);
  EXPECT_EQ(sim.substeps(), 0);
  EXPECT_EQ(sim.rejected_substeps(), 0);
}

// A step that needs more than kMaxSubstepsPerStep substeps fails, naming how far it got,
// instead of running on for as long as its substeps take: after a first step of 1 ms,
// 600 s in one step of the LWR with damping and friction off (not stiff: thousands of
// substeps a second). Before, a substep shrinking towards its floor could run for many
// minutes within one step.
TEST(DormandPrince, AStepOfTooManySubstepsFailsNamingItAndKeepsTheState) {
  SimulatorOptions o;
  o.effects = kAllEffects & ~(kDamping | kFriction);
  Simulator sim(lwr(), o);
  sim.reset(lwr_q0(), {});
  sim.step(1e-3);
  const Eigen::VectorXd q = sim.q;
  const std::int64_t substeps = sim.substeps();
  try {
    sim.step(600);
    FAIL() << "the step succeeded";
  } catch (const Error& e) {
    const std::string m = e.what();
    for (const char* part : {"step 2 from t = 0.001 s to", "100000 adaptive substeps", "covered only",
                             "the state stays at t = 0.001 s"})
      EXPECT_NE(m.find(part), std::string::npos) << part << " in: " << m;
  }
  EXPECT_EQ(sim.q, q);
  EXPECT_EQ(sim.t, 1e-3);
  EXPECT_EQ(sim.substeps(), substeps);
}

// The damped LWR's friction near rest is stiff (F / v_f over a wrist's inertia: about
// 8300 1/s): Dormand-Prince detects it where it dominates and covers 60 s in one step
// (about 58000 substeps, some thousands of them stiff), where without the detection the
// step failed after 100000 substeps below 0.4 ms.
TEST(DormandPrince, StiffFrictionIsDetectedAndTakenImplicitly) {
  Simulator sim(lwr(), SimulatorOptions{});
  sim.reset(lwr_q0(), {});
  sim.step(60);
  std::printf("damped LWR, one step of 60 s: %lld substeps, %lld stiff, %lld rejected\n",
              static_cast<long long>(sim.substeps()), static_cast<long long>(sim.stiff_substeps()),
              static_cast<long long>(sim.rejected_substeps()));
  EXPECT_EQ(sim.t, 60);
  EXPECT_LT(sim.substeps(), kMaxSubstepsPerStep);
  EXPECT_GT(sim.stiff_substeps(), 0);
  EXPECT_TRUE(sim.q.allFinite());
}

// The UR5 with damping and friction off, holding z and rx: with the defaults it runs 20 s
// with its energy and held directions within 1e-6; RK4 at the page's 1 ms fails at
// t = 6.234 s (its tip speed overflows; 3.245 s under the truncate policy).
TEST(DormandPrince, TheUndampedUr5HoldsWhereRk4FailsWithinSeconds) {
  const Model m = load_urdf_file((kRoot / "robots/ur5.urdf").string(), "base_link", "wrist_3_link");
  Eigen::VectorXd q0(6);
  q0 << 0.2, -1.0, 1.2, -1.5, -1.4, 0.3;
  const auto start = [&](Integrator integrator) {
    SimulatorOptions o;
    o.integrator = integrator;
    o.effects = kAllEffects & ~(kDamping | kFriction);
    o.limits = LimitPolicy::Ignore;
    auto sim = std::make_unique<Simulator>(m, o);
    sim->reset(q0, {});
    sim->set_direction(2, DirectionMode::Hold);
    sim->set_direction(3, DirectionMode::Hold);
    return sim;
  };
  const auto sim = start(SimulatorOptions().integrator);
  const double E0 = sim->energy();
  double max_T = 0, max_dE = 0;
  for (int k = 0; k < 20000; ++k) {
    sim->step(1e-3);
    max_T = std::max(max_T, sim->kinetic_energy());
    max_dE = std::max(max_dE, std::abs(sim->energy() - E0));
  }
  const auto r = sim->max_residuals();
  EXPECT_GT(max_T, 1.0);
  EXPECT_LE(max_dE, 1e-6 * max_T);
  EXPECT_LE(std::max(r[2], r[3]), 1e-6);
  const auto rk4 = start(Integrator::RK4);
  EXPECT_THROW(rk4->run(20000, 1e-3), Error);
  EXPECT_LT(rk4->t, 10.0);
}

// Joint 7 of the LWR (2.4e-4 kg m^2 about its axis, Coulomb friction 0.1 N m) near rest:
// friction F tanh(qd / v_f) at v_f = 0.05 is a damper of F / v_f, a decay rate of about
// 8300 1/s. Gravity off, only friction: the true motion decays to rest within
// milliseconds without a sign change. At dt = 1 ms (dt times the rate: 8.3) implicit Euler
// decays monotonically to rest; RK4 (stable for dt rate < 2.785) oscillates, then settles
// on a spurious motion: the joint spins at about 0.09 rad/s against its friction, with
// more kinetic energy than it started with.
TEST(ImplicitEuler, StiffFrictionIsStableAtOneMillisecondWhereRk4IsNot) {
  const auto run = [](Integrator integrator, int& sign_changes, double& kinetic_gain) {
    SimulatorOptions o;
    o.integrator = integrator;
    o.effects = kVelocityProducts | kFriction;
    o.limits = LimitPolicy::Ignore;
    Simulator sim(lwr(), o);
    Eigen::VectorXd qd = Eigen::VectorXd::Zero(7);
    qd[6] = 0.01;
    sim.reset(lwr_q0(), qd);
    const double T0 = sim.kinetic_energy();
    sign_changes = 0;
    double previous = sim.qd[6];
    for (int k = 0; k < 200; ++k) {
      sim.step(1e-3);
      if (sim.qd[6] * previous < 0) ++sign_changes;
      previous = sim.qd[6];
    }
    kinetic_gain = sim.kinetic_energy() - T0;
    return std::abs(sim.qd[6]);
  };
  int implicit_changes = 0, rk4_changes = 0;
  double implicit_gain = 0, rk4_gain = 0;
  const double implicit_end = run(Integrator::ImplicitEuler, implicit_changes, implicit_gain);
  const double rk4_end = run(Integrator::RK4, rk4_changes, rk4_gain);
  EXPECT_EQ(implicit_changes, 0);
  EXPECT_LT(implicit_end, 1e-8);
  EXPECT_LT(implicit_gain, 0);
  // RK4 at 1 ms on the stiff friction.
  EXPECT_GE(rk4_changes, 3);
  EXPECT_GT(rk4_end, 0.05);
  EXPECT_GT(rk4_gain, 0);
}

// Without damping and friction the only implicit part is the held directions'
// stabilisation: implicit Euler is semi-implicit Euler with w and zeta replaced by those
// of backward Euler on e'' = -2 zeta w e' - w^2 e (w'^2 = w^2 / D, 2 zeta' w' =
// (2 zeta w + w^2 dt) / D, D = 1 + 2 zeta w dt + w^2 dt^2), to the bit.
TEST(ImplicitEuler, WithoutPassiveTermsItIsSemiImplicitEulerWithTheStabilisationAtTheStepsEnd) {
  const double dt = 1e-3, w = kDefaultStabilisationFrequency, zeta = 1;
  const double d = 1 + 2 * zeta * w * dt + w * w * dt * dt;
  const double w_end = w / std::sqrt(d);
  const double zeta_end = (2 * zeta * w + w * w * dt) / (d * 2 * w_end);
  Eigen::VectorXd q[2], qd[2];
  const Integrator integrators[2] = {Integrator::ImplicitEuler, Integrator::SemiImplicitEuler};
  for (int r = 0; r < 2; ++r) {
    SimulatorOptions o;
    o.integrator = integrators[r];
    o.effects = kGravity | kVelocityProducts | kConstraints | kRotorInertia;
    o.stabilisation_frequency = r ? w_end : w;
    o.stabilisation_damping = r ? zeta_end : zeta;
    Model m = lwr();
    for (int i = 0; i < 7; ++i) m.set_rotor_inertia(i, 0.01);
    Simulator sim(m, o);
    sim.reset(lwr_q0(), {});
    sim.set_direction(2, DirectionMode::Hold);
    sim.set_direction(3, DirectionMode::Hold);
    sim.run(300, dt);
    q[r] = sim.q;
    qd[r] = sim.qd;
  }
  EXPECT_EQ(q[0], q[1]);
  EXPECT_EQ(qd[0], qd[1]);
}

// The held directions' stabilisation (w = 100 rad/s, zeta = 1) taken at the step's start
// is unstable for w dt > 0.83: semi-implicit Euler at 10 ms spins the LWR holding z and rx
// apart (by a factor of about -1.6 a step) and fails within the first second. Implicit
// Euler takes it at the step's end and holds them for the scene's 2 s.
TEST(ImplicitEuler, HeldDirectionsAreStableAtTenMillisecondsWhereSemiImplicitEulerIsNot) {
  const auto run = [](Integrator integrator, double& worst) {
    SimulatorOptions o = hold_scene_options();
    o.integrator = integrator;
    const cli::Scene scene = cli::load_scene((kRoot / "robots/scenes/kuka_lwr4_hold_z_rx.json").string());
    Simulator sim(scene.model, o);
    cli::start_scene(scene, sim);
    worst = 0;
    for (int k = 0; k < 200; ++k) {
      sim.step(0.01);
      for (double x : sim.residuals()) worst = std::max(worst, std::abs(x));
    }
    return sim.q;
  };
  double worst = 0;
  const Eigen::VectorXd q = run(Integrator::ImplicitEuler, worst);
  EXPECT_TRUE(q.allFinite());
  EXPECT_LT(worst, 1e-2);
  std::printf("implicit Euler at 10 ms: held residual at most %.3g\n", worst);
  EXPECT_THROW(run(Integrator::SemiImplicitEuler, worst), Error);
}

}  // namespace
