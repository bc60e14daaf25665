// `achd bench --against kdl` as a user runs it: KDL's solver cannot take a chain with a
// fixed joint (before: an Eigen assertion inside KDL, exit 134), so the command refuses
// such chains with one error line; kdl_parser's own warnings never reach stderr; stdout
// is strict JSON.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli_run.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

class CliBenchKdl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { dir_ = make_temp_dir("achd_bench_kdl"); }
  static std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }
  static inline std::string dir_;
};

TEST_F(CliBenchKdl, AChainWithAFixedJointIsRefusedWithOneLine) {
  const std::string c = write("mixed.json", R"({"q": [0.4, 0.12, -0.7, 0.9], "gravity": [0, 0, -9.81],
                                                "alpha": [[0, 0, 1, 0, 0, 0]], "beta": [0]})");
  const CliRun r = run_cli(dir_, {"bench", ACHD_SOURCE_DIR "/robots/mixed_chain.urdf", "--root", "base", "--tip",
                                  "tool", "--case", c, "--against", "kdl", "--repeats", "3"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("achd: error: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find("fixed joint"), std::string::npos) << r.err;
  // Without --against kdl the same chain benchmarks.
  const CliRun alone = run_cli(dir_, {"bench", ACHD_SOURCE_DIR "/robots/mixed_chain.urdf", "--root", "base",
                                      "--tip", "tool", "--case", c, "--repeats", "3"});
  EXPECT_EQ(alone.exit_code, 0) << alone.err;
}

// A root link with an inertial makes kdl_parser warn ("KDL does not support a root link
// with an inertia") on stderr in colour; the bench succeeds and stderr stays empty.
TEST_F(CliBenchKdl, KdlParserWarningsStayOffStderr) {
  std::string urdf = read_text(ACHD_SOURCE_DIR "/robots/planar2.urdf");
  const std::regex root_link(R"(<link name="base_link"\s*/>)");
  ASSERT_TRUE(std::regex_search(urdf, root_link)) << "planar2's root link changed";
  urdf = std::regex_replace(urdf, root_link,
                            R"(<link name="base_link"><inertial><mass value="2"/><inertia ixx="0.1" ixy="0" )"
                            R"(ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>)");
  const std::string robot = write("root_inertia.urdf", urdf);
  const std::string c = write("planar.json", R"({"q": [0.4, 0.9], "gravity": [0, 0, -9.81]})");
  const CliRun r = run_cli(dir_, {"bench", robot, "--root", "base_link", "--tip", "link2", "--case", c,
                                  "--against", "kdl", "--repeats", "3"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r.out;
  EXPECT_LE(j["qdd_rel_diff"].get<double>(), 1e-12);
}

}  // namespace
}  // namespace achd::test
