// Bad input through `achd solve`: every kind exits with code 2, prints nothing on
// stdout and exactly one line "achd: error: ..." on stderr naming the problem.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bad_input_urdfs.hpp"

namespace achd::test {
namespace {

struct Run {
  int code;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Per-process names: ctest -j runs the tests of this program in parallel processes.
std::string temp(const std::string& name) {
  return testing::TempDir() + "achd_bad_input_cli_" + std::to_string(getpid()) + "_" + name;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = temp(name);
  std::ofstream(path) << text;
  return path;
}

Run achd(const std::string& command, const std::string& args) {
  const std::string out = temp("stdout"), err = temp("stderr");
  const std::string cmd = std::string(ACHD_CLI) + " " + command + " " + args + " >" + out + " 2>" + err;
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

Run solve(const std::string& args) { return achd("solve", args); }

// Exit 2, empty stdout, one stderr line starting "achd: error: " containing each part.
void expect_refused(const Run& r, const std::vector<std::string>& parts, const std::string& what) {
  EXPECT_EQ(r.code, 2) << what;
  EXPECT_EQ(r.out, "") << what;
  ASSERT_FALSE(r.err.empty()) << what;
  EXPECT_EQ(r.err.rfind("achd: error: ", 0), 0u) << what << ": " << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << what << ": not one line: " << r.err;
  for (const std::string& p : parts)
    EXPECT_NE(r.err.find(p), std::string::npos) << what << ": '" << r.err << "' lacks '" << p << "'";
}

const std::string kKuka = std::string(ACHD_SOURCE_DIR) + "/robots/kuka_lwr4.urdf";
const std::string kKukaChain = kKuka + " --root lwr_base_link --tip lwr_link_7";
const std::string kQ = "\"q\": [0, 0, 0, 0, 0, 0, 0], \"gravity\": [0, 0, -9.81]";

TEST(BadInputCli, EveryBadUrdfExitsTwoWithOneLineNamingIt) {
  const std::string ok_case = write("ok_case.json", "{\"q\": [0], \"gravity\": [0, 0, -9.81]}");
  for (const BadUrdf& b : bad_urdfs()) {
    const std::string path = write("robot.urdf", b.xml);
    std::vector<std::string> parts = b.message;
    parts.push_back(path + ": ");
    expect_refused(solve(path + " --root " + b.root + " --tip " + b.tip + " --case " + ok_case), parts,
                   b.what);
  }
}

TEST(BadInputCli, MissingFilesNameThePath) {
  const std::string ok_case = write("ok7.json", "{" + kQ + "}");
  expect_refused(solve("/nonexistent/r.urdf --root a --tip b --case " + ok_case),
                 {"/nonexistent/r.urdf: cannot open file"}, "missing URDF");
  expect_refused(solve(kKukaChain + " --case /nonexistent/case.json"),
                 {"/nonexistent/case.json: cannot open file"}, "missing case");
}

TEST(BadInputCli, BadCasesNameTheFieldAndIndex) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{" + kQ + ", \"extra\": 1}", "unknown field 'extra'"},
      {"{\"q\": [0, 0, 0, NaN, 0, 0, 0], \"gravity\": [0, 0, -9.81]}", "invalid JSON"},
      {"{\"q\": [0, 0, 0, 1e999, 0, 0, 0], \"gravity\": [0, 0, -9.81]}", "1e999"},
      {"{\"q\": [0, 0, 0], \"gravity\": [0, 0, -9.81]}", "q: expected 7 values, got 3"},
      {"{" + kQ + ", \"qd\": [0, 0]}", "qd: expected 7 values, got 2"},
      {"{" + kQ + ", \"alpha\": [[1, 0, 0, 0, 0, 0]], \"beta\": []}", "beta: expected 1 values"},
      {"{" + kQ + ", \"alpha\": [[1, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0], "
                  "[1, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0]]}",
       "alpha: at most 6 constraints, got 7"},
      {"{" + kQ + ", \"f_ext\": [[0, 0, 0, 0, 0, \"x\"]]}", "f_ext: expected 7 wrenches"},
      {"{\"gravity\": [0, 0, -9.81]}", "missing required field 'q'"},
      {"{" + kQ, "invalid JSON"},
  };
  for (const auto& [text, part] : cases) {
    const std::string path = write("case.json", text);
    expect_refused(solve(kKukaChain + " --case " + path), {path + ": ", part}, text);
  }
}

TEST(BadInputCli, BadOptionsNameTheOption) {
  const std::string ok_case = write("ok7b.json", "{" + kQ + "}");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--policy fast", "--policy"},
      {"--tolerance nan", "--tolerance"},
      {"--tolerance -1", "--tolerance"},
      {"--damping inf", "--damping"},
      {"--policy damped --damping 0", "damping"},
      {"--bogus 1", "unknown option --bogus"},
  };
  for (const auto& [opts, part] : cases)
    expect_refused(solve(kKukaChain + " --case " + ok_case + " " + opts), {part}, opts);
  // Without --tip the whole tree loads (cli_trees.cpp); an option without its value is refused.
  expect_refused(solve(kKuka + " --root lwr_base_link --case " + ok_case + " --tip"), {"option --tip needs a value"},
                 "--tip without a link");
}

// A chain a -> b -> c whose second joint mimics the first.
std::string mimic_urdf() {
  const std::string limit = "<axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>";
  return write("mimic.urdf", robot(link("a") + link("b") + link("c") + joint("j1", "revolute", "a", "b", limit) +
                                   joint("j2", "revolute", "b", "c", limit + "<mimic joint=\"j1\"/>")));
}

TEST(BadInputCli, MimicJointsAreCoupledUnlessAskedOtherwise) {
  const std::string urdf = mimic_urdf() + " --root a --tip c";
  const std::string c = write("mimic_case.json", "{\"q\": [0.1, 0.1], \"gravity\": [0, 0, -9.81]}");
  const auto coupled = solve(urdf + " --case " + c);
  EXPECT_EQ(coupled.code, 0) << coupled.err;
  EXPECT_NE(coupled.out.find("\"nu_owners\": [\"coupling j2\"]"), std::string::npos) << coupled.out;
  expect_refused(solve(urdf + " --case " + c + " --mimic error"), {"joint 'j2': <mimic> of joint 'j1'", "--mimic independent"},
                 "mimic error");
  expect_refused(solve(urdf + " --case " + c + " --mimic fold"),
                 {"option --mimic: expected 'couple', 'independent' or 'error', got 'fold'"}, "bad --mimic");
  const auto ok = solve(urdf + " --case " + c + " --mimic independent");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("\"qdd\""), std::string::npos);
  const auto explicit_error = solve(urdf + " --case " + c + " --mimic error");
  EXPECT_EQ(explicit_error.code, 2);
  const auto bench = achd("bench", urdf + " --case " + c + " --mimic independent --iterations 1 --repeats 1");
  EXPECT_EQ(bench.code, 0) << bench.err;
  expect_refused(achd("bench", urdf + " --case " + c + " --mimic error --iterations 1 --repeats 1"), {"<mimic>"},
                 "bench mimic error");
}

// A scene's "mimic" field, as --mimic.
TEST(BadInputCli, SceneMimicFieldLoadsMimicJoints) {
  const std::string scene = std::string("{\"urdf\": \"") + mimic_urdf() +
                            "\", \"root\": \"a\", \"tip\": \"c\", \"q0\": [0.1, 0.1], \"dt\": 0.001, "
                            "\"duration\": 0.01";
  const auto coupled = achd("simulate", write("mimic_default.json", scene + "}") + " --out " + temp("coupled.csv"));
  EXPECT_EQ(coupled.code, 0) << coupled.err;
  expect_refused(achd("simulate", write("mimic_error.json", scene + ", \"mimic\": \"error\"}")),
                 {"<mimic> of joint 'j1'"}, "scene mimic error");
  const auto ok = achd("simulate", write("mimic_independent.json", scene + ", \"mimic\": \"independent\"}") +
                                      " --out " + temp("mimic.csv"));
  EXPECT_EQ(ok.code, 0) << ok.err;
  expect_refused(achd("simulate", write("mimic_bad.json", scene + ", \"mimic\": 1}")),
                 {"mimic_bad.json: mimic must be a string"}, "scene mimic not a string");
  expect_refused(achd("simulate", write("mimic_bad2.json", scene + ", \"mimic\": \"both\"}")),
                 {"mimic: expected 'couple', 'independent' or 'error', got 'both'"}, "scene mimic bad name");
}

}  // namespace
}  // namespace achd::test
