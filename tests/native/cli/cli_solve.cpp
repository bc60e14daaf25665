// The real `achd solve` binary (ACHD_CLI, from CMake) run as a child process: on every
// robot of robots/index.json it prints the result JSON (docs/design.md section 5) and
// nothing else, equal to the library's solve; on bad input it exits 2 with one line
// "achd: error: ..." on stderr that names the problem, and nothing on stdout.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "random_chain.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

class CliSolve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = make_temp_dir("achd_cli"); }

  static std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }

  static CliRun run(const std::vector<std::string>& args) { return run_cli(dir_, args); }

  // A solve of planar2 with `case_text` (or a URDF/link override) that must fail: exit
  // code 2, nothing on stdout, one line "achd: error: ..." containing every `needles`.
  static void expect_error(const std::vector<std::string>& args,
                           const std::vector<std::string>& needles) {
    const CliRun r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err.rfind("achd: error: ", 0), 0u) << r.err;
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << n << " not in: " << r.err;
  }

  static std::vector<std::string> planar2(const std::string& case_path) {
    return {"solve", ACHD_SOURCE_DIR "/robots/planar2.urdf", "--root", "base_link", "--tip",
            "link2", "--case", case_path};
  }

  static inline std::string dir_;
};

Eigen::VectorXd json_vector(const nlohmann::json& j) {
  const std::vector<double> v = j;
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// Every robot: a case at q0 with velocities, torques and a tip constraint; the printed
// JSON has every result field, and its numbers (17 significant digits) are the
// library's, in both conventions.
TEST_F(CliSolve, EveryIndexRobotPrintsTheLibraryResult) {
  std::mt19937 rng(909);
  int robots = 0;
  for (const IndexedRobot& r : load_robot_index(ACHD_SOURCE_DIR)) {
    SCOPED_TRACE(r.name);
    const std::optional<Case> found = case_at(rng, r.model, r.q0, 1, true);
    ASSERT_TRUE(found.has_value());
    const Case& c = *found;
    nlohmann::json j = {{"q", std::vector<double>(c.q.data(), c.q.data() + c.q.size())},
                        {"qd", std::vector<double>(c.qd.data(), c.qd.data() + c.qd.size())},
                        {"ff_torques", std::vector<double>(c.ff_torques.data(),
                                                           c.ff_torques.data() + c.ff_torques.size())},
                        {"gravity", {0, 0, -9.81}},
                        {"alpha", {std::vector<double>(c.alpha.data(), c.alpha.data() + 6)}},
                        {"beta", {c.beta[0]}},
                        {"f_ext", nlohmann::json::array()}};
    for (const Vector6& w : c.f_ext) j["f_ext"].push_back(std::vector<double>(w.data(), w.data() + 6));
    const std::string case_path = write(r.name + ".json", j.dump());
    for (const Convention convention : {Convention::Physical, Convention::Kdl}) {
      const bool kdl = convention == Convention::Kdl;
      const CliRun run_result = run({"solve", r.urdf_path, "--root", r.root, "--tip", r.tip, "--case",
                                  case_path, "--convention", kdl ? "kdl" : "physical"});
      ASSERT_EQ(run_result.exit_code, 0) << run_result.err;
      EXPECT_EQ(run_result.err, "");
      const nlohmann::json out = nlohmann::json::parse(run_result.out);
      for (const char* key : {"qdd", "constraint_torques", "total_torques", "nu", "joint_torques",
                              "constraint_wrench", "link_accelerations", "rank", "sigma_min"})
        EXPECT_TRUE(out.contains(key)) << key;
      Case lc = c;
      lc.gravity = Vector3(0, 0, -9.81);
      Options o;
      o.convention = convention;
      Data d(r.model);
      hybrid_dynamics(r.model, d, lc, o);
      EXPECT_LE(rel_error(json_vector(out.at("qdd")), d.qdd), 1e-15);
      EXPECT_LE(rel_error(json_vector(out.at("joint_torques")), d.joint_torques), 1e-15);
      EXPECT_LE(rel_error(json_vector(out.at("nu")), d.nu), 1e-15);
      ASSERT_EQ(out.at("link_accelerations").size(), d.link_accelerations.size());
      EXPECT_LE(rel_error(json_vector(out.at("link_accelerations").back()),
                          d.link_accelerations.back()),
                1e-15);
      EXPECT_EQ(out.at("rank").get<int>(), d.rank);
    }
    ++robots;
  }
  EXPECT_GE(robots, 6);
}

const char* kGoodCase = R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81]})";

TEST_F(CliSolve, BrokenUrdfNamesTheFile) {
  const std::string good = write("good.json", kGoodCase);
  const std::string urdf = write("broken.urdf", "<robot name=\"x\"><link name=\"a\"></robot>");
  expect_error({"solve", urdf, "--root", "a", "--tip", "a", "--case", good}, {"broken.urdf"});
}

TEST_F(CliSolve, UnknownLinkIsNamed) {
  std::vector<std::string> args = planar2(write("good.json", kGoodCase));
  args[5] = "no_such_link";
  expect_error(args, {"no_such_link"});
}

TEST_F(CliSolve, WrongLengthNamesTheField) {
  expect_error(planar2(write("len.json", R"({"q": [0.4, 0.9, 1], "gravity": [0, 0, -9.81]})")),
               {"len.json", "q", "3"});
  expect_error(planar2(write("fext.json", R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81],
                                              "f_ext": [[0, 0, 0, 0, 0, 0]]})")),
               {"fext.json", "f_ext"});
}

TEST_F(CliSolve, MissingQOrGravityIsNamed) {
  expect_error(planar2(write("noq.json", R"({"gravity": [0, 0, -9.81]})")), {"noq.json", "'q'"});
  expect_error(planar2(write("nog.json", R"({"q": [0.4, 0.9]})")), {"nog.json", "gravity"});
}

TEST_F(CliSolve, UnknownFieldIsNamed) {
  expect_error(planar2(write("unk.json", R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81], "speed": 1})")),
               {"unk.json", "speed"});
}

TEST_F(CliSolve, NonNumberNamesFieldAndIndex) {
  expect_error(planar2(write("str.json", R"({"q": [0.4, "x"], "gravity": [0, 0, -9.81]})")),
               {"str.json", "q[1]"});
}

// JSON has no NaN or Infinity; 1e999 is the non-finite number a case file can hold. The
// message must say which case file holds it.
TEST_F(CliSolve, NonFiniteNumberNamesTheFile) {
  expect_error(planar2(write("inf.json", R"({"q": [0.4, 0.9], "qd": [0, 1e999], "gravity": [0, 0, -9.81]})")),
               {"inf.json", "1e999"});
}

TEST_F(CliSolve, MoreThanSixConstraintsIsAnError) {
  std::string alpha;
  for (int k = 0; k < 7; ++k) alpha += std::string(k ? "," : "") + "[0, 0, 1, 0, 0, 0]";
  expect_error(planar2(write("seven.json", R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81], "alpha": [)" +
                                               alpha + R"(], "beta": [0, 0, 0, 0, 0, 0, 0]})")),
               {"seven.json", "alpha", "7"});
}

TEST_F(CliSolve, MissingFilesAreNamed) {
  expect_error(planar2(dir_ + "/no_such_case.json"), {"no_such_case.json"});
  std::vector<std::string> args = planar2(write("good.json", kGoodCase));
  args[1] = dir_ + "/no_such_robot.urdf";
  expect_error(args, {"no_such_robot.urdf"});
}

// Finite inputs whose solve overflows: before, exit 0 with -nan and inf in the printed
// "JSON"; now exit 2 with one line naming the joint. A case that does not overflow, at
// magnitudes just below, prints strict JSON (no NaN or Infinity literals).
TEST_F(CliSolve, OverflowingSolvesAreErrorsAndResultsAreStrictJson) {
  expect_error(planar2(write("qd.json", R"({"q": [0.4, 0.9], "qd": [1e155, 1e155], "gravity": [0, 0, -9.81]})")),
               {"overflows", "joint '"});
  expect_error(planar2(write("ff.json", R"({"q": [0.4, 0.9], "ff_torques": [1e308, -1e308], "gravity": [0, 0, -9.81]})")),
               {"overflows", "joint '", "ff_torques"});
  for (const char* text : {R"({"q": [0.4, 0.9], "qd": [1e100, 1e100], "gravity": [0, 0, -9.81]})",
                           R"({"q": [0.4, 0.9], "ff_torques": [1e300, -1e300], "gravity": [0, 0, -9.81]})",
                           R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81], "alpha": [[1e-200, 0, 0, 0, 0, 0]], "beta": [0]})"}) {
    const CliRun r = run(planar2(write("big.json", text)));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r.out;  // strict: no NaN, Infinity
    for (const char* field : {"qdd", "joint_torques", "nu", "constraint_wrench"})
      for (const auto& x : j[field]) EXPECT_TRUE(x.is_number() && std::isfinite(x.get<double>())) << field;
  }
}

// A column of 1e-200 is the same constraint as a unit column (before: rank 0, the
// constraint silently dropped): the same qdd to round-off, nu scaled by 1e200.
TEST_F(CliSolve, AConstraintColumnsScaleChangesOnlyItsForce) {
  const CliRun unit = run(planar2(write("unit.json",
      R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81], "alpha": [[1, 0, 0, 0, 0, 0]], "beta": [0.5]})")));
  const CliRun tiny = run(planar2(write("tiny.json",
      R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81], "alpha": [[1e-200, 0, 0, 0, 0, 0]], "beta": [0.5e-200]})")));
  ASSERT_EQ(unit.exit_code, 0) << unit.err;
  ASSERT_EQ(tiny.exit_code, 0) << tiny.err;
  const nlohmann::json a = nlohmann::json::parse(unit.out), b = nlohmann::json::parse(tiny.out);
  EXPECT_EQ(b["rank"], 1);
  EXPECT_LE(rel_error(json_vector(b["qdd"]), json_vector(a["qdd"])), 1e-13);
  EXPECT_NEAR(b["nu"][0].get<double>() * 1e-200, a["nu"][0].get<double>(), 1e-13 * std::abs(a["nu"][0].get<double>()));
}

}  // namespace
}  // namespace achd::test
