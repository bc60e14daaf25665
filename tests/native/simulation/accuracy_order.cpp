// The accuracy study's error figures are right: on a smooth, non-chaotic scene (the
// planar two-link arm swinging down from rest for 0.5 s with joint damping) the end-state
// error e(dt) = max|q(T) - q_ref(T)| of an integrator of order p falls as dt^p, so the
// observed order log(e(dt) / e(dt/2)) / log 2 is within 0.3 of 4 for RK4 and of 1 for
// explicit Euler; and the RK4 reference is converged: halving its step changes q(T) by
// less than 1e-3 of the smallest error measured.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "accuracy_study.hpp"

namespace achd::cli {
namespace {

constexpr double kDuration = 0.5;
constexpr double kReferenceDt = 0.0625e-3;

class AccuracyOrder : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = load_scene(ACHD_SOURCE_DIR "/robots/scenes/planar2_damped_swing.json");
    ref_ = reference_run(scene_, scene_.options, kReferenceDt, kDuration);
  }

  // e(dt) for each step of `dts` with `integrator`.
  std::vector<double> errors(Integrator integrator, const std::vector<double>& dts) const {
    SimulatorOptions o = scene_.options;
    o.integrator = integrator;
    std::vector<double> e;
    for (double dt : dts) {
      const EndState end = run_to_end(scene_, o, dt, kDuration);
      EXPECT_TRUE(end.finite) << integrator_name(integrator) << " at dt = " << dt;
      e.push_back(max_abs_difference(end.q, ref_.end.q));
    }
    return e;
  }

  void expect_order(Integrator integrator, const std::vector<double>& dts, double order) const {
    const std::vector<double> e = errors(integrator, dts);
    for (std::size_t i = 1; i < e.size(); ++i) {
      const double observed = std::log(e[i - 1] / e[i]) / std::log(dts[i - 1] / dts[i]);
      EXPECT_NEAR(observed, order, 0.3) << integrator_name(integrator) << " from dt = " << dts[i - 1]
                                        << " to " << dts[i] << ": errors " << e[i - 1] << ", " << e[i];
      // The reference resolves every error measured.
      EXPECT_LT(ref_.self_error_q, 1e-3 * e[i]) << "dt = " << dts[i];
    }
  }

  Scene scene_;
  Reference ref_;
};

TEST_F(AccuracyOrder, SceneIsTheDampedSwing) {
  // Damping on, nothing else that is non-smooth: friction off, no held directions.
  EXPECT_TRUE(scene_.options.effects & kDamping);
  EXPECT_FALSE(scene_.options.effects & kFriction);
  for (DirectionMode m : scene_.modes) EXPECT_EQ(m, DirectionMode::Free);
  EXPECT_GT(ref_.self_error_q, 0);  // a real check: the two reference runs differ
}

TEST_F(AccuracyOrder, DurationMustBeWholeSteps) {
  // 0.5 s / 8 ms = 62.5 steps: the end state would be at another time than the reference's.
  EXPECT_THROW(run_to_end(scene_, scene_.options, 8e-3, kDuration), Error);
}

TEST_F(AccuracyOrder, RK4IsFourthOrder) { expect_order(Integrator::RK4, {4e-3, 2e-3, 1e-3}, 4.0); }

TEST_F(AccuracyOrder, ExplicitEulerIsFirstOrder) {
  expect_order(Integrator::ExplicitEuler, {2e-3, 1e-3, 0.5e-3, 0.25e-3}, 1.0);
}

TEST_F(AccuracyOrder, SemiImplicitEulerIsFirstOrder) {
  expect_order(Integrator::SemiImplicitEuler, {2e-3, 1e-3, 0.5e-3, 0.25e-3}, 1.0);
}

// Implicit in the swing's joint damping, still first order.
TEST_F(AccuracyOrder, ImplicitEulerIsFirstOrder) {
  expect_order(Integrator::ImplicitEuler, {2e-3, 1e-3, 0.5e-3, 0.25e-3}, 1.0);
}

// The adaptive integrator over one output step of the whole run (so that the tolerance,
// not the output step, sets its substeps): its error falls with its tolerance, by at least
// 10 per factor 100 of rtol (atol = rtol / 100), and stays within 100 rtol.
TEST_F(AccuracyOrder, DormandPrinceErrorFallsWithTheTolerance) {
  SimulatorOptions o = scene_.options;
  o.integrator = Integrator::DormandPrince;
  double previous = INFINITY;
  for (double rtol : {1e-4, 1e-6, 1e-8}) {
    o.rtol = rtol;
    o.atol = rtol / 100;
    const EndState end = run_to_end(scene_, o, kDuration, kDuration);
    ASSERT_TRUE(end.finite) << end.failure;
    const double e = max_abs_difference(end.q, ref_.end.q);
    EXPECT_LT(e, previous / 10) << "rtol " << rtol;
    EXPECT_LT(e, 100 * rtol) << "rtol " << rtol;
    EXPECT_LT(ref_.self_error_q, 1e-2 * e) << "rtol " << rtol;
    previous = e;
  }
}

// The quick study of the undamped arm (wrist spinning up: RK4 at the quick ladder's 50 us
// reference step is 5e-9 rad off, more than the best rows' own errors) refines its
// reference until it is at least 10x more accurate than the best row, so that the
// adaptive integrator's error falls with every tighter tolerance, as in the full study.
TEST(QuickStudy, ItsReferenceResolvesItsBestRow) {
  const Scene scene = load_scene(ACHD_SOURCE_DIR "/robots/scenes/kuka_lwr4_undamped_hold_z_rx.json");
  StudyConfig config = default_config(scene, true);
  config.knobs = false;
  config.timing_repeats = 1;
  config.timing_steps = 10;
  const Study study = run_study(scene, config);
  double smallest = INFINITY, previous = INFINITY;
  for (const StudyRun& r : study.runs) {
    if (r.kind != "integrator" || !r.stable) continue;
    smallest = std::min(smallest, r.error_q);
    if (r.integrator != "dormand_prince") continue;
    EXPECT_LT(r.error_q, previous) << r.setting << ": the error falls with the tolerance";
    previous = r.error_q;
  }
  ASSERT_TRUE(std::isfinite(smallest));
  EXPECT_GT(study.reference.halvings, 0);
  EXPECT_LE(study.reference.self_error_q, smallest / 10)
      << "reference dt " << study.reference.dt << " s, smallest error " << smallest;
  std::printf("  reference RK4 at %.3g s (%d halvings), self error %.3g rad, smallest row error %.3g rad\n",
              study.reference.dt, study.reference.halvings, study.reference.self_error_q, smallest);
}

}  // namespace
}  // namespace achd::cli
