// The real `achd` binary (ACHD_CLI) on runs that used to go wrong with exit 0:
// step counts beyond int, durations that are not whole numbers of steps, output that
// cannot be written (--out /dev/full, stdout on /dev/full), a run that fails mid-way
// (its message and the file it must not leave), Ctrl-C (a real SIGINT: exit 130, what
// was simulated, no file), integer options beyond their range, and the accuracy study's
// guard and Ctrl-C.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "robot_index.hpp"

extern char** environ;

namespace achd::test {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

class CliSimulateRuns : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "achd_cli_runs_XXXXXX";
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }

  // The planar arm's damped swing (robots/scenes/planar2_damped_swing.json) with `fields`
  // (JSON members, leading comma) replacing or adding to it.
  std::string planar2_scene(const std::string& name, const std::string& dt, const std::string& duration) const {
    return write(name, R"({"urdf": ")" ACHD_SOURCE_DIR R"(/robots/planar2.urdf", "root": "base_link",
      "tip": "link2", "q0": [0.4, 0.9], "effects": {"damping": true, "friction": false, "constraints": false},
      "integrator": "semi_implicit_euler", "dt": )" + dt + R"(, "duration": )" + duration + "}");
  }

  // Starts ACHD_CLI with `args`; stdout into `stdout_path` (default: a file in the test
  // directory), stderr into a file.
  pid_t start(const std::vector<std::string>& args, const std::string& stdout_path = "") const {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string out = stdout_path.empty() ? path("stdout.txt") : stdout_path;
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, path("stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> all = {ACHD_CLI};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int spawned = posix_spawn(&pid, ACHD_CLI, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    return spawned == 0 ? pid : -1;
  }

  // Waits for the child; it is killed (and the test fails) after `seconds`.
  CliRun finish(pid_t pid, double seconds = 60) const {
    CliRun r;
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (waitpid(pid, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        ADD_FAILURE() << "achd did not finish within " << seconds << " s";
        return r;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (fs::exists(path("stdout.txt"))) r.out = read_text(path("stdout.txt"));
    r.err = read_text(path("stderr.txt"));
    return r;
  }

  CliRun run(const std::vector<std::string>& args, const std::string& stdout_path = "") const {
    return finish(start(args, stdout_path));
  }

  // Waits until the child's stderr holds `needle` (a progress line), then sends SIGINT.
  CliRun interrupt_after(pid_t pid, const std::string& needle) const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (read_text(path("stderr.txt")).find(needle) == std::string::npos) {
      if (std::chrono::steady_clock::now() > deadline) {
        ADD_FAILURE() << "no '" << needle << "' on stderr within 30 s";
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid, SIGINT);
    return finish(pid);
  }

  // Exit code 2, one line "achd: error: ..." holding every needle.
  static void expect_error(const CliRun& r, const std::vector<std::string>& needles) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("achd: error: ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << n << " not in: " << r.err;
  }

  // The files of the test directory other than those named.
  std::vector<std::string> other_files(const std::set<std::string>& known) const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_))
      if (!known.count(e.path().filename().string())) out.push_back(e.path().filename().string());
    return out;
  }

  fs::path dir_;
};

// Before: "t" was a running sum (5000 steps of 1 ms: 5.000000000000004) and "steps" an int.
TEST_F(CliSimulateRuns, SummaryStepsTimesDtIsT) {
  for (const char* scene : {"planar2_damped_swing.json", "kuka_lwr4_hold_z_rx.json"}) {
    const CliRun r = run({"simulate", ACHD_SOURCE_DIR "/robots/scenes/" + std::string(scene)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Nothing on stderr but progress lines (a run over a second, as under the sanitizers,
    // prints them; a short one none).
    std::istringstream err(r.err);
    for (std::string line; std::getline(err, line);)
      EXPECT_EQ(line.rfind("achd: simulate " ACHD_SOURCE_DIR "/robots/scenes/" + std::string(scene) + ": t = ", 0), 0u)
          << line;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("steps").get<std::int64_t>() * j.at("dt").get<double>(), j.at("t").get<double>()) << scene;
  }
}

// The summary counts the integrator's substeps (and of them the stiff ones: at rtol 1e-5
// the damped LWR's friction near rest is detected stiff, at the default 1e-9 it is not);
// --integrator, --rtol and --atol replace the scene's (before: unknown options, exit 2,
// and no "substeps" in the summary).
TEST_F(CliSimulateRuns, IntegratorAndTolerancesFromTheCommandLineAndSubstepsInTheSummary) {
  const std::string scene = ACHD_SOURCE_DIR "/robots/scenes/kuka_lwr4_hold_z_rx.json";
  const auto summary = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"simulate", scene};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun r = run(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const nlohmann::json adaptive = summary({}), loose = summary({"--rtol", "1e-5", "--atol", "1e-7"}),
                       implicit = summary({"--integrator", "implicit_euler"});
  EXPECT_EQ(adaptive.at("integrator"), "dormand_prince");
  EXPECT_GT(adaptive.at("substeps").get<std::int64_t>(), adaptive.at("steps").get<std::int64_t>());
  EXPECT_GT(adaptive.at("rejected_substeps").get<std::int64_t>(), 0);
  EXPECT_LT(loose.at("substeps").get<std::int64_t>(), adaptive.at("substeps").get<std::int64_t>());
  EXPECT_EQ(adaptive.at("stiff_substeps"), 0);
  EXPECT_GT(loose.at("stiff_substeps").get<std::int64_t>(), 0);
  EXPECT_EQ(implicit.at("integrator"), "implicit_euler");
  EXPECT_EQ(implicit.at("substeps"), implicit.at("steps"));
  EXPECT_EQ(implicit.at("rejected_substeps"), 0);
  EXPECT_EQ(implicit.at("stiff_substeps"), 0);
  EXPECT_EQ(adaptive.at("friction_velocity"), 0.05);
  expect_error(run({"simulate", scene, "--integrator", "rk5"}), {"--integrator", "'dormand_prince'", "'rk5'"});
  expect_error(run({"simulate", scene, "--rtol", "0"}), {"--rtol must be > 0"});
}

// Before: 1.0005 s at 1 ms ran 1000 steps (t = 1.0000000000000007); dt 1e-300 ran 0
// steps; both exit 0.
TEST_F(CliSimulateRuns, DurationsThatAreNotAWholeNumberOfStepsAreErrors) {
  expect_error(run({"simulate", planar2_scene("odd.json", "0.001", "1.0005")}),
               {"odd.json", "1000.5 steps", "duration 1.0005 s", "dt 0.001 s"});
  expect_error(run({"simulate", planar2_scene("tiny.json", "1e-300", "1")}), {"tiny.json", "1e+300 steps", "2^53"});
}

// 4.3e6 s at 1 ms is 4.3e9 steps (before: wrapped to 5032704 steps, exit 0 after 5 s;
// 2.2e6 s gave "steps": -2094967296 and no run at all). The run shows progress on
// stderr; Ctrl-C stops it with exit 130, what was simulated and no file.
TEST_F(CliSimulateRuns, CtrlCStopsALongRunWithExit130AndNoFile) {
  const std::string scene = planar2_scene("long.json", "0.001", "4.3e6");
  const std::string csv = path("traj.csv");
  const CliRun r = interrupt_after(start({"simulate", scene, "--out", csv}), "elapsed");
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("of 4300000000 steps"), std::string::npos) << r.err;  // the count, not wrapped
  // The last line: "achd: interrupted: simulate long.json: t = T s of 4300000 s (N of
  // 4300000000 steps, ...); no file written to traj.csv" with T = N * dt.
  ASSERT_NE(r.err.rfind("achd: "), std::string::npos) << r.err;
  const std::string last = r.err.substr(r.err.rfind("achd: "));
  ASSERT_EQ(last.rfind("achd: interrupted: simulate " + scene + ": t = ", 0), 0u) << r.err;
  EXPECT_NE(last.find("; no file written to " + csv), std::string::npos) << last;
  const long long n = std::stoll(last.substr(last.find(" (") + 2));
  EXPECT_GT(n, 0);
  char t[32];
  std::snprintf(t, sizeof t, "%.15g", n * 1e-3);
  EXPECT_NE(last.find(": t = " + std::string(t) + " s of 4300000 s ("), std::string::npos) << last;
  EXPECT_FALSE(fs::exists(csv));
  EXPECT_EQ(other_files({"long.json", "stdout.txt", "stderr.txt"}), std::vector<std::string>{});
}

// Before: exit 0 and the trajectory lost (write errors were never checked).
TEST_F(CliSimulateRuns, OutputThatCannotBeWrittenIsExitTwo) {
  const std::string scene = ACHD_SOURCE_DIR "/robots/scenes/planar2_damped_swing.json";
  expect_error(run({"simulate", scene, "--out", "/dev/full"}), {"/dev/full", "cannot write", "No space left"});
  expect_error(run({"simulate", scene}, "/dev/full"), {"cannot write the result to stdout"});
  write("case.json", R"({"q": [0.1, 0.2], "gravity": [0, 0, -9.81]})");
  expect_error(run({"solve", ACHD_SOURCE_DIR "/robots/planar2.urdf", "--root", "base_link", "--tip", "link2",
                    "--case", path("case.json")},
                   "/dev/full"),
               {"cannot write the result to stdout"});
  expect_error(run({"simulate", scene, "--out", path("missing/traj.csv")}), {"missing/traj.csv", "cannot create"});
}

// The CSV appears whole: the rows of every step, nothing else left in the directory;
// --out - puts it on stdout instead of the summary.
TEST_F(CliSimulateRuns, TrajectoryIsWrittenWhole) {
  const std::string scene = ACHD_SOURCE_DIR "/robots/scenes/planar2_damped_swing.json";
  const CliRun r = run({"simulate", scene, "--out", path("traj.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = read_text(path("traj.csv"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5002);  // header, t = 0, 5000 steps
  EXPECT_EQ(csv.substr(csv.rfind('\n', csv.size() - 2) + 1, 2), "5,");  // the last row is t = 5
  EXPECT_EQ(other_files({"traj.csv", "stdout.txt", "stderr.txt"}), std::vector<std::string>{});
  const CliRun piped = run({"simulate", scene, "--out", "-"});
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.out, csv);
}

// The UR5 holding z and rx while its tip accelerates along y at 0.5 m/s^2 blows up at
// t = 2.184 s (RK4, 1 ms; 2.183 s while friction smoothing was raised with dt). Before: "achd: error: beta[0] is not finite" and a partial traj.csv in
// place of the previous file.
TEST_F(CliSimulateRuns, FailedRunNamesStepTimeAndDirectionsAndLeavesNoFile) {
  const std::string scene = write("ur5_y.json", R"({"urdf": ")" ACHD_SOURCE_DIR R"(/robots/ur5.urdf",
    "root": "base_link", "tip": "wrist_3_link", "q0": [0.2, -1.0, 1.2, -1.5, -1.4, 0.3],
    "directions": {"z": "hold", "rx": "hold", "y": 0.5}, "integrator": "rk4", "policy": "truncate",
    "dt": 0.001, "duration": 5})");
  const std::string csv = write("traj.csv", "the previous trajectory\n");
  const CliRun r = run({"simulate", scene, "--out", csv});
  expect_error(r, {scene + ": step 2185 from t = 2.184 s", "held: z, rx", "accelerated: y = 0.5 m/s^2",
                   "stopped after 2184 of 5000 steps", "no file written to " + csv});
  EXPECT_EQ(r.err.find("beta["), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(read_text(csv), "the previous trajectory\n");
  EXPECT_EQ(other_files({"ur5_y.json", "traj.csv", "stdout.txt", "stderr.txt"}), std::vector<std::string>{});
}

// The same UR5 scene with the simulator's default policy (variable_damping) runs its 5 s
// and lists the loss of y in the summary's "events", each with the acceleration the solve
// left undelivered (a released one more than w^2 1e-9 = 1e-5 m/s^2 at the default
// stabilisation), and how long y was released; a wrong "policy" names the field.
// Before: the run failed at 2.183 s, and "policy" was an unknown field.
TEST_F(CliSimulateRuns, BoundaryRunReportsDirectionEventsInTheSummary) {
  const std::string fields = R"({"urdf": ")" ACHD_SOURCE_DIR R"(/robots/ur5.urdf",
    "root": "base_link", "tip": "wrist_3_link", "q0": [0.2, -1.0, 1.2, -1.5, -1.4, 0.3],
    "directions": {"z": "hold", "rx": "hold", "y": 0.5}, "dt": 0.001, "duration": 5)";
  const CliRun r = run({"simulate", write("ur5_y.json", fields + "}")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::ordered_json summary = nlohmann::ordered_json::parse(r.out);  // keys in output order
  EXPECT_EQ(summary["t"], 5.0);
  ASSERT_TRUE(summary["events"].is_array());
  bool y_released = false;
  for (const auto& e : summary["events"]) {
    std::vector<std::string> keys;
    for (const auto& item : e.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"t", "step", "link", "direction", "kind", "sigma_min", "unmet", "effort_ratio"}));
    EXPECT_EQ(e["link"], "wrist_3_link");
    if (e["kind"] != "resumed") EXPECT_GT(e["unmet"].get<double>(), 1e-5) << e.dump();
    y_released = y_released || (e["direction"] == "y" && e["kind"] == "released");
  }
  EXPECT_TRUE(y_released) << summary["events"].dump();
  ASSERT_TRUE(summary["released_s"].contains("y")) << summary.dump();
  const double released_s = summary["released_s"]["y"].get<double>();
  EXPECT_GT(released_s, 0);
  EXPECT_LE(released_s, 5.0);
  EXPECT_EQ(summary["link_released_s"]["wrist_3_link"]["y"], released_s);
  EXPECT_FALSE(summary.contains("events_not_kept"));
  expect_error(run({"simulate", write("bad.json", fields + R"(, "policy": "stiff"})")}),
               {"bad.json: policy: expected 'truncate', 'damped' or 'variable_damping', got 'stiff'"});
  expect_error(run({"simulate", write("bad2.json", fields + R"(, "singular_region": 0})")}),
               {"bad2.json: singular_region must be > 0"});
}

// A loop joint the robot cannot close (the planar arm's tip pinned 2.2 m from its base, 0.2
// m beyond its reach): the summary's events name the loop ("loop" instead of "link"), and
// "loop_released_s" says how long each of its directions was not followed.
TEST_F(CliSimulateRuns, LoopEventsNameTheLoop) {
  const std::string scene = R"({"urdf": ")" ACHD_SOURCE_DIR R"(/robots/planar2.urdf", "root": "base_link",
    "q0": [0.3, -0.6], "dt": 0.001, "duration": 2,
    "loops": [{"name": "pin", "link_a": "link2", "origin_a": {"xyz": [1, 0, 0]},
               "link_b": "base_link", "origin_b": {"xyz": [0, 0, -2.2]}, "type": "spherical"}]})";
  const CliRun r = run({"simulate", write("pin.json", scene)});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::ordered_json summary = nlohmann::ordered_json::parse(r.out);
  ASSERT_FALSE(summary["events"].empty()) << r.out;
  for (const auto& e : summary["events"]) {
    std::vector<std::string> keys;
    for (const auto& item : e.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"t", "step", "loop", "direction", "kind", "sigma_min", "unmet", "effort_ratio"}));
    EXPECT_EQ(e["loop"], "pin");
  }
  EXPECT_TRUE(summary["released_s"].empty());
  ASSERT_TRUE(summary["loop_released_s"].contains("pin")) << r.out;
  for (const auto& [direction, seconds] : summary["loop_released_s"]["pin"].items()) {
    EXPECT_GT(seconds.get<double>(), 0) << direction;
    EXPECT_LE(seconds.get<double>(), 2.0) << direction;
  }
}

// A whole tree on a floating base: robots/scenes/quadruped_stand.json (feet held through
// link_directions, joint_control) stands 10 s; the CSV names the free joint's columns, and
// the summary each foot's drift. Errors name the field.
TEST_F(CliSimulateRuns, FloatingQuadrupedSceneStandsOnItsFeet) {
  const std::string scene = ACHD_SOURCE_DIR "/robots/scenes/quadruped_stand.json";
  const CliRun r = run({"simulate", scene, "--out", path("traj.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["t"], 10.0);
  EXPECT_TRUE(summary["held_drift"].empty());  // no tip: a tree
  ASSERT_EQ(summary["link_held_drift"].size(), 4u);
  for (const auto& foot : summary["link_held_drift"].items())
    for (const auto& d : foot.value().items()) EXPECT_LE(d.value().get<double>(), 1e-9) << foot.key() << " " << d.key();
  std::istringstream csv(read_text(path("traj.csv")));
  std::string header, row, last;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("t,q_trunk_x,q_trunk_y,q_trunk_z,q_trunk_qx,q_trunk_qy,q_trunk_qz,q_trunk_qw,q_lf_haa,", 0), 0u)
      << header;
  EXPECT_NE(header.find(",qd_trunk_vx,"), std::string::npos);
  double worst = 0;
  while (std::getline(csv, row)) {
    const double z = std::stod(row.substr(row.find(',', row.find(',', row.find(',') + 1) + 1) + 1));
    worst = std::max(worst, std::abs(z - 0.3));
  }
  EXPECT_LE(worst, 0.01);  // the trunk's height within 1 cm
  const std::string fields = R"({"urdf": ")" ACHD_SOURCE_DIR R"(/robots/quadruped.urdf", "root": "trunk",
    "floating": true, "q0": [0, 0, 0.3, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0], "dt": 0.001, "duration": 0.01)";
  expect_error(run({"simulate", write("a.json", fields + R"(, "directions": {"z": "hold"}})")}),
               {"a.json: directions: the tip's directions need a tip", "use link_directions"});
  expect_error(run({"simulate", write("b.json", fields + R"(, "link_directions": [{"link": "paw"}]})")}),
               {"b.json: link_directions[0].link: no link 'paw' after the root link 'trunk'"});
  expect_error(run({"simulate", write("c.json", fields + R"(, "joint_control": {"kp": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]}})")}),
               {"c.json: joint control: kp[0] of joint 'trunk' (the floating base's free joint, not actuated) must be 0"});
  expect_error(run({"simulate", write("d.json", fields + R"(, "link_directions": [{"link": "lf_foot", "directions": {"w": "hold"}}]})")}),
               {"d.json: unknown field 'link_directions[0].directions.w'"});
}

// Before: --repeats 4294967297 ran 1 repeat (a long cast to int), exit 0.
TEST_F(CliSimulateRuns, IntegerOptionsOutOfRangeAreErrors) {
  write("case.json", R"({"q": [0.1, 0.2], "gravity": [0, 0, -9.81]})");
  const std::vector<std::string> bench = {"bench", ACHD_SOURCE_DIR "/robots/planar2.urdf", "--root", "base_link",
                                          "--tip", "link2", "--case", path("case.json")};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = bench;
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  };
  expect_error(with({"--repeats", "4294967297"}), {"--repeats", "'4294967297'", "[1, 100000]"});
  expect_error(with({"--repeats", "0"}), {"--repeats", "[1, 100000]"});
  expect_error(with({"--iterations", "99999999999999999999"}), {"--iterations", "[1, 1000000000]"});
  expect_error(with({"--iterations", " 5"}), {"--iterations"});
  const CliRun ok = with({"--repeats", "3", "--iterations", "5"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const nlohmann::json j = nlohmann::json::parse(ok.out);
  EXPECT_EQ(j.at("repeats"), 3);
  EXPECT_EQ(j.at("iterations"), 5);
}

// Before: a 1e9 s scene ran for ever, silently.
TEST_F(CliSimulateRuns, AccuracyRefusesAStudyBeyondTheLimit) {
  expect_error(run({"accuracy", planar2_scene("huge.json", "0.001", "1e9")}, ""),
               {"huge.json", "4.057e+14 steps", "more than the limit of 1e+08", "--quick"});
}

// A long study shows progress; Ctrl-C stops it with exit 130 and writes no file.
TEST_F(CliSimulateRuns, AccuracyCtrlCWritesNothing) {
  const std::string scene = planar2_scene("long.json", "0.001", "200");
  const CliRun r = interrupt_after(start({"accuracy", scene, "--out", path("study")}), "elapsed");
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("achd: accuracy " + scene + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("achd: interrupted: accuracy " + scene), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("study")));
}

// A study writes its three files whole, nothing else. (Its stderr holds at most progress
// lines: 0.2 s in a Release build, it may pass a second in the sanitizer build.)
TEST_F(CliSimulateRuns, AccuracyWritesItsFilesWhole) {
  const std::string scene = ACHD_SOURCE_DIR "/robots/scenes/planar2_damped_swing.json";
  const CliRun r = run({"accuracy", scene, "--quick", "--out", path("study")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);)
    EXPECT_EQ(line.rfind("achd: accuracy " + scene + ": ", 0), 0u) << line;
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(path("study"))) names.insert(e.path().filename().string());
  EXPECT_EQ(names, (std::set<std::string>{"accuracy.csv", "accuracy.json", "accuracy.svg"}));
  EXPECT_EQ(nlohmann::json::parse(read_text(path("study/accuracy.json"))), nlohmann::json::parse(r.out));
}

}  // namespace
}  // namespace achd::test
