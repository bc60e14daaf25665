// Case and scene JSON whose meaning used to be lost or misreported, through `achd`:
//   - a key given twice in one object is an error naming the key and its object (before:
//     nlohmann::json kept the last one silently);
//   - a floating base's zero quaternion in a scene's q0 or a case's q is named as such
//     (before, in a scene: the run failed later, blaming a held direction of a foot);
//   - a name holding a NUL or a newline is printed escaped, so that the message keeps
//     its one line and is not cut at the NUL.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_child.hpp"

namespace achd::test {
namespace {

namespace fs = std::filesystem;

const std::string kKuka = std::string(ACHD_SOURCE_DIR) + "/robots/kuka_lwr4.urdf";
const std::string kQuadruped = std::string(ACHD_SOURCE_DIR) + "/robots/quadruped.urdf";

class BadInputJson : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "achd_bad_input_json_XXXXXX";
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ + "/" + name, std::ios::binary) << text;
    return dir_ + "/" + name;
  }

  // Exit 2, nothing on stdout, one line "achd: error: ..." holding each part.
  void expect_refused(const std::vector<std::string>& args, const std::vector<std::string>& parts) const {
    const ChildRun r = run_child(dir_, args, 30);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err.rfind("achd: error: ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    for (const std::string& p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << "lacks '" << p << "': " << r.err;
  }

  std::vector<std::string> solve_kuka(const std::string& case_path) const {
    return {"solve", kKuka, "--root", "lwr_base_link", "--tip", "lwr_link_7", "--case", case_path};
  }

  // The quadruped standing on its feet (robots/scenes/quadruped_stand.json) from `q0`.
  std::string quadruped_scene(const std::string& name, const std::string& q0) const {
    return write(name, R"({"urdf": ")" + kQuadruped + R"(", "root": "trunk", "floating": true, "q0": )" + q0 + R"(,
      "link_directions": [{"link": "lf_foot", "directions": {"x": "hold", "y": "hold", "z": "hold"}},
                          {"link": "rf_foot", "directions": {"x": "hold", "y": "hold", "z": "hold"}}],
      "integrator": "rk4", "dt": 0.001, "duration": 0.01})");
  }

  std::string dir_;
};

const std::string kQ = R"("q": [0, 0, 0, 0, 0, 0, 0], "gravity": [0, 0, -9.81])";
const std::string kLegs = "0.1, 0.8, -1.6, -0.1, 0.8, -1.6, 0.1, -0.8, 1.6, -0.1, -0.8, 1.6";

TEST_F(BadInputJson, ADuplicateKeyInACaseIsNamed) {
  const std::string top = write("top.json", "{" + kQ + R"(, "q": [1, 1, 1, 1, 1, 1, 1]})");
  expect_refused(solve_kuka(top), {top + ": duplicate key 'q'"});
  const std::string nested =
      write("nested.json", "{" + kQ + R"(, "qd": {"lwr_joint_1": 1, "lwr_joint_2": 0, "lwr_joint_1": 2}})");
  expect_refused(solve_kuka(nested), {nested + ": duplicate key 'lwr_joint_1' in 'qd'"});
  // The same key in two different objects is no duplicate.
  const std::string apart = write("apart.json", "{" + kQ + R"(, "qd": {"lwr_joint_1": 1}, "ff_torques": {"lwr_joint_1": 2}})");
  const ChildRun ok = run_child(dir_, solve_kuka(apart), 30);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST_F(BadInputJson, ADuplicateKeyInASceneIsNamed) {
  const std::string scene = quadruped_scene("dup.json", "[0, 0, 0.3, 0, 0, 0, 1, " + kLegs + "]");
  std::string text = child_file_text(scene);
  text.insert(text.rfind('}'), R"(, "dt": 0.002)");
  expect_refused({"simulate", write("dup.json", text)}, {"dup.json: duplicate key 'dt'"});
  std::string inner = child_file_text(scene);
  const std::string foot = R"("x": "hold", "y": "hold", "z": "hold")";
  inner.replace(inner.find(foot), foot.size(), R"("x": "hold", "y": "hold", "x": "free")");
  expect_refused({"simulate", write("dup_inner.json", inner)}, {"duplicate key 'x' in 'directions'"});
}

TEST_F(BadInputJson, AZeroQuaternionIsNamedAsSuch) {
  expect_refused({"simulate", quadruped_scene("zero_q.json", "[0, 0, 0.3, 0, 0, 0, 0, " + kLegs + "]")},
                 {"zero_q.json: q0[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero"});
  const std::string c = write("zero_q_case.json", R"({"gravity": [0, 0, -9.81], "q": [0, 0, 0.3, 0, 0, 0, 0, )" + kLegs + "]}");
  expect_refused({"solve", kQuadruped, "--floating", "--case", c},
                 {"zero_q_case.json: q[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero"});
}

TEST_F(BadInputJson, NamesWithControlCharactersArePrintedEscaped) {
  const std::string nul = write("nul.json", "{" + kQ + R"(, "qd": {"lwr\u0000evil": 1}})");
  expect_refused(solve_kuka(nul), {"no movable joint 'lwr\\0evil' between the root and the tip"});
  const std::string newline = write("newline.json", "{" + kQ + R"(, "extra\nfield": 1})");
  expect_refused(solve_kuka(newline), {"unknown field 'extra\\nfield'"});
  const std::string scene = write("scene_nul.json", R"({"urdf": ")" + kKuka + R"(", "root": "lwr_base_link",
    "tip": "lwr_link_7", "q0": [0, 0, 0, 0, 0, 0, 0], "dt": 0.001, "duration": 0.01, "f_ext": {"a\u0000b\u0007": [0, 0, 0, 0, 0, 0]}})");
  expect_refused({"simulate", scene}, {"f_ext.a\\0b\\x07: no link of that name"});
}

}  // namespace
}  // namespace achd::test
