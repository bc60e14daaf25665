// Whole accuracy studies (`achd accuracy`) rank and report their runs right:
//   - The quick study of the undamped arm (robots/scenes/kuka_lwr4_undamped_hold_z_rx.json,
//     whose wrist spins up: RK4 at the quick ladder's 50 us reference step is 5e-9 rad
//     off, more than its best rows' own errors) ranks its rows by error as the full study
//     ranks the same rows, and puts the same of them on the error-cost front: the front
//     of the quick rows at the quick study's costs is the same with the full study's
//     errors (the costs are shared, so that timing noise cannot decide the comparison).
//   - The stiff scene (robots/scenes/dual_arm_torso_stiff_hold.json: both hands held in
//     6D under joint PD kp 1e4, kd 100, 0.2 s): the adaptive default's error against RK4
//     at 12.5 us falls with its tolerance (rtol 1e-4, 1e-6, 1e-8: measured 1.3e-8, 2.1e-12,
//     6.9e-13 rad), each fall larger than the reference's own error (1e-13, round-off)
//     could fake, with stiff substeps taken at every tolerance; and its quick study lists
//     every integrator, each row either ok with a finite error or marked unstable or
//     diverged with the reason (the explicit ones fail at every step the quick ladder
//     has down to 0.2 ms), in the CSV and the JSON alike, and the plot's notes name them.
// Release only: about 35 s there on a loaded 2-core machine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "achd/names.hpp"
#include "accuracy_report.hpp"
#include "accuracy_study.hpp"
#include "pareto_front.hpp"

namespace achd::cli {
namespace {

using RowKey = std::tuple<std::string, double, std::string>;  // integrator, dt, setting
RowKey key(const StudyRun& r) { return {r.integrator, r.dt, r.setting}; }

std::string name(const RowKey& k) {
  char dt[32];
  std::snprintf(dt, sizeof dt, "%g ms", std::get<1>(k) * 1e3);
  return std::get<0>(k) + " " + (std::get<2>(k).empty() ? std::string(dt) : std::get<2>(k));
}

// The integrator ladder and tolerances only, timed briefly (the costs matter here only
// as the quick study's own).
Study study(const Scene& scene, bool quick) {
  StudyConfig config = default_config(scene, quick);
  config.knobs = false;
  config.timing_repeats = 1;
  config.timing_steps = 20;
  return run_study(scene, config);
}

TEST(AccuracyStudies, QuickStudyRanksTheUndampedArmAsTheFullStudy) {
  const Scene scene = load_scene(ACHD_SOURCE_DIR "/robots/scenes/kuka_lwr4_undamped_hold_z_rx.json");
  const Study quick = study(scene, true), full = study(scene, false);
  ASSERT_EQ(quick.config.duration, full.config.duration) << "the quick study must cover the scene's whole 0.5 s";
  std::map<RowKey, const StudyRun*> full_rows;
  for (const StudyRun& r : full.runs)
    if (r.kind == "integrator") full_rows[key(r)] = &r;
  // The quick study's stable rows, with its errors and the full study's.
  std::vector<RowKey> rows;
  std::vector<CostError> by_quick, by_full;
  for (const StudyRun& r : quick.runs) {
    if (r.kind != "integrator") continue;
    ASSERT_TRUE(full_rows.count(key(r))) << name(key(r)) << " is not in the full study";
    const StudyRun& f = *full_rows[key(r)];
    EXPECT_EQ(r.status, f.status) << name(key(r));
    if (!r.stable || !f.stable) continue;
    rows.push_back(key(r));
    by_quick.push_back({r.cpu_s_per_sim_s, r.error_q});
    by_full.push_back({r.cpu_s_per_sim_s, f.error_q});
  }
  ASSERT_GE(rows.size(), 10u);
  // The ranking by error.
  std::vector<std::size_t> quick_rank(rows.size()), full_rank(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) quick_rank[i] = full_rank[i] = i;
  std::sort(quick_rank.begin(), quick_rank.end(), [&](auto a, auto b) { return by_quick[a].error < by_quick[b].error; });
  std::sort(full_rank.begin(), full_rank.end(), [&](auto a, auto b) { return by_full[a].error < by_full[b].error; });
  for (std::size_t i = 0; i < rows.size(); ++i)
    EXPECT_EQ(name(rows[quick_rank[i]]), name(rows[full_rank[i]]))
        << "rank " << i << " by error: quick " << by_quick[quick_rank[i]].error << ", full "
        << by_full[full_rank[i]].error;
  // The error-cost front, at the same costs.
  const std::vector<bool> quick_front = pareto_front(by_quick), full_front = pareto_front(by_full);
  for (std::size_t i = 0; i < rows.size(); ++i)
    EXPECT_EQ(quick_front[i], full_front[i]) << name(rows[i]) << ": error " << by_quick[i].error
                                             << " in the quick study, " << by_full[i].error << " in the full one";
  // The quick study's own front is that one.
  std::size_t k = 0;
  for (const StudyRun& r : quick.runs)
    if (r.kind == "integrator" && r.stable) EXPECT_EQ(r.pareto, quick_front[k++]) << name(key(r));
  std::printf("  quick reference RK4 at %.3g s (self error %.3g rad), full RK4 at %.3g s (%.3g rad), best row %s\n",
              quick.reference.dt, quick.reference.self_error_q, full.reference.dt, full.reference.self_error_q,
              name(rows[quick_rank[0]]).c_str());
}

class AccuracyStiffScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(load_scene(ACHD_SOURCE_DIR "/robots/scenes/dual_arm_torso_stiff_hold.json"));
  }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }
  static Scene* scene_;
};
Scene* AccuracyStiffScene::scene_ = nullptr;

TEST_F(AccuracyStiffScene, DormandPrinceErrorFallsWithTheTolerance) {
  const Scene& scene = *scene_;
  const double duration = scene.duration;
  Reference ref = reference_run(scene, scene.options, 12.5e-6, duration);
  std::vector<double> errors;
  SimulatorOptions o = scene.options;
  o.integrator = Integrator::DormandPrince;
  for (double rtol : {1e-4, 1e-6, 1e-8}) {
    o.rtol = rtol;
    o.atol = rtol / 100;
    const EndState end = run_to_end(scene, o, 10e-3, duration);
    ASSERT_TRUE(end.finite) << "rtol " << rtol << ": " << end.failure;
    EXPECT_GT(end.stiff_substeps, 0) << "rtol " << rtol << ": the stiffness switch fired";
    errors.push_back(max_abs_difference(end.q, ref.end.q));
    std::printf("  rtol %g: error %.3g rad, %lld substeps (%lld stiff, %lld rejected)\n", rtol, errors.back(),
                static_cast<long long>(end.substeps), static_cast<long long>(end.stiff_substeps),
                static_cast<long long>(end.rejected_substeps));
  }
  std::printf("  reference RK4 at %.3g s, self error %.3g rad\n", ref.dt, ref.self_error_q);
  // Each fall is larger than the reference's own error could make it (the true errors are
  // within self_error_q of the measured ones).
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i] + 2 * ref.self_error_q, errors[i - 1]) << "rtol 1e-" << 4 + 2 * i << " against the one before";
}

TEST_F(AccuracyStiffScene, StudyShowsEveryIntegratorOrWhyItFailed) {
  StudyConfig config = default_config(*scene_, true);
  config.knobs = false;
  config.timing_repeats = 1;
  config.timing_steps = 20;
  const Study s = run_study(*scene_, config);
  std::set<std::string> seen;
  int failed = 0;
  for (const StudyRun& r : s.runs) {
    seen.insert(r.integrator);
    if (r.stable) {
      EXPECT_EQ(r.status, "ok");
      EXPECT_TRUE(std::isfinite(r.error_q)) << r.integrator;
      EXPECT_TRUE(r.failure.empty()) << r.integrator;
    } else {
      ++failed;
      EXPECT_TRUE(r.status == "unstable" || r.status == "diverged") << r.status;
      EXPECT_FALSE(r.failure.empty()) << r.integrator << " " << r.dt << " " << r.setting << " failed without a reason";
    }
    std::printf("  %s %g %s: %s %s\n", r.integrator.c_str(), r.dt, r.setting.c_str(), r.status.c_str(),
                r.failure.substr(0, 120).c_str());
  }
  for (Integrator integrator : kIntegrators) EXPECT_TRUE(seen.count(integrator_name(integrator))) << integrator_name(integrator);
  EXPECT_GT(failed, 0) << "the stiff scene makes some explicit step fail";
  // The tables and the plot say the same: the CSV's last field and the JSON's "failure"
  // hold each failed row's reason, the plot's notes name each failed integrator.
  const nlohmann::ordered_json json = study_json(s);
  std::istringstream csv(study_csv(s));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.substr(line.rfind(',') + 1), "failure");
  std::string notes;
  for (const std::string& note : study_plot(s, "stiff").notes) notes += note + "\n";
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    const StudyRun& r = s.runs[i];
    ASSERT_TRUE(std::getline(csv, line));
    const bool quoted = !r.failure.empty() && r.failure.find(',') != std::string::npos;
    EXPECT_NE(line.find(quoted ? "\"" + r.failure + "\"" : "," + r.failure), std::string::npos) << line;
    EXPECT_EQ(json["runs"][i].contains("failure"), !r.stable) << i;
    if (r.stable) continue;
    EXPECT_EQ(json["runs"][i]["failure"], r.failure);
    EXPECT_NE(notes.find(r.integrator), std::string::npos) << notes;
  }
}

}  // namespace
}  // namespace achd::cli
