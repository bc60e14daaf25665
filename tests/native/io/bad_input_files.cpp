// Input paths that are not files to read whole: a device that never ends (/dev/zero,
// /dev/urandom), a directory, a FIFO with no writer, and regular files past the size
// limit, named as a URDF (info, solve, bench), as a case (solve, bench --case), as a
// scene (simulate, accuracy) and as a scene's "urdf". Each run ends within 2 s with exit
// 2 and one line naming the path and what is wrong with it, its peak memory under
// 100 MB. (Before: /dev/zero and /dev/urandom were read until memory ran out, a FIFO
// waited forever for a writer, a directory was "cannot parse URDF: Error document
// empty".)
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli_child.hpp"

namespace achd::test {
namespace {

namespace fs = std::filesystem;

const std::string kKuka = std::string(ACHD_SOURCE_DIR) + "/robots/kuka_lwr4.urdf";
const std::string kKukaRoot = "lwr_base_link";
constexpr double kSeconds = 2;
constexpr long kPeakKb = 100 * 1024;

class BadInputFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "achd_bad_input_files_XXXXXX";
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    ASSERT_TRUE(fs::create_directory(dir_ + "/a_directory"));
    ASSERT_EQ(mkfifo((dir_ + "/a_fifo").c_str(), 0600), 0);
    ok_case_ = write("ok_case.json", R"({"q": [0, 0, 0, 0, 0, 0, 0], "gravity": [0, 0, -9.81]})");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ + "/" + name) << text;
    return dir_ + "/" + name;
  }

  // A sparse file of `bytes` zero bytes (no disk space used).
  std::string sized(const std::string& name, off_t bytes) const {
    const std::string path = write(name, "");
    EXPECT_EQ(truncate(path.c_str(), bytes), 0);
    return path;
  }

  // The paths that are not files to read, each with what the message must say of it.
  std::vector<std::pair<std::string, std::string>> not_files() const {
    return {{"/dev/zero", "a device"},
            {"/dev/urandom", "a device"},
            {dir_ + "/a_directory", "a directory"},
            {dir_ + "/a_fifo", "a FIFO"}};
  }

  // A scene of the KUKA arm whose "urdf" is `urdf`.
  std::string scene_with_urdf(const std::string& name, const std::string& urdf) const {
    return write(name, R"({"urdf": ")" + urdf + R"(", "root": "lwr_base_link", "tip": "lwr_link_7",
      "q0": [0, 0, 0, 0, 0, 0, 0], "dt": 0.001, "duration": 0.01})");
  }

  // Runs achd `args`; expects exit 2 within 2 s, under 100 MB, one line naming each part.
  void expect_refused_quickly(const std::vector<std::string>& args, const std::vector<std::string>& parts,
                              ChildIo io = {}) {
    std::string what;
    for (const std::string& a : args) what += a + " ";
    const ChildRun r = run_child(dir_, args, kSeconds, io);
    EXPECT_FALSE(r.killed) << what << ": killed after " << r.seconds << " s at " << r.peak_rss_kb << " kB";
    EXPECT_LT(r.seconds, kSeconds) << what;
    EXPECT_LT(r.peak_rss_kb, kPeakKb) << what;
    EXPECT_EQ(r.exit_code, 2) << what << r.err;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(r.err.rfind("achd: error: ", 0), 0u) << what << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << what << ": not one line: " << r.err;
    for (const std::string& p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << what << ": lacks '" << p << "': " << r.err;
    peak_kb_ = std::max(peak_kb_, r.peak_rss_kb);
    slowest_ = std::max(slowest_, r.seconds);
  }

  // The slowest refusal and the highest peak memory of the test, for the record.
  void report_costs() const {
    std::printf("slowest refusal %.3f s, highest peak memory %ld kB\n", slowest_, peak_kb_);
  }

  std::string dir_, ok_case_;
  long peak_kb_ = 0;
  double slowest_ = 0;
};

TEST_F(BadInputFiles, AUrdfPathThatIsNotAFileIsRefusedAtOnce) {
  for (const auto& [path, kind] : not_files()) {
    const std::vector<std::string> parts = {path + ": " + kind + ", expected a regular file"};
    expect_refused_quickly({"info", path}, parts);
    expect_refused_quickly({"solve", path, "--case", ok_case_}, parts);
    expect_refused_quickly({"bench", path, "--case", ok_case_, "--iterations", "1", "--repeats", "1"}, parts);
  }
  report_costs();
}

TEST_F(BadInputFiles, ACasePathThatIsNotAFileIsRefusedAtOnce) {
  for (const auto& [path, kind] : not_files()) {
    const std::vector<std::string> parts = {path + ": " + kind + ", expected a regular file"};
    expect_refused_quickly({"solve", kKuka, "--root", kKukaRoot, "--tip", "lwr_link_7", "--case", path}, parts);
    expect_refused_quickly({"bench", kKuka, "--root", kKukaRoot, "--tip", "lwr_link_7", "--case", path,
                            "--iterations", "1", "--repeats", "1"},
                           parts);
  }
  report_costs();
}

TEST_F(BadInputFiles, AScenePathThatIsNotAFileIsRefusedAtOnce) {
  for (const auto& [path, kind] : not_files()) {
    const std::vector<std::string> parts = {path + ": " + kind + ", expected a regular file"};
    expect_refused_quickly({"simulate", path, "--out", dir_ + "/traj.csv"}, parts);
    expect_refused_quickly({"accuracy", path, "--quick"}, parts);
  }
  EXPECT_FALSE(fs::exists(dir_ + "/traj.csv"));
  report_costs();
}

TEST_F(BadInputFiles, ASceneUrdfThatIsNotAFileIsRefusedAtOnce) {
  for (const auto& [path, kind] : not_files()) {
    const std::string scene = scene_with_urdf("scene.json", path);
    const std::vector<std::string> parts = {scene + ": ", path + ": " + kind + ", expected a regular file"};
    expect_refused_quickly({"simulate", scene}, parts);
    expect_refused_quickly({"accuracy", scene, "--quick"}, parts);
  }
  report_costs();
}

// Regular files past the limits (sparse: no disk used) are refused before they are read;
// so is a case piped on stdin past 16 MiB (read up to the limit, then refused).
TEST_F(BadInputFiles, FilesPastTheSizeLimitsAreRefusedNamingTheLimit) {
  const std::string big_urdf = sized("big.urdf", (64 << 20) + 1);
  const std::string big_case = sized("big_case.json", (16 << 20) + 1);
  const std::string big_scene = sized("big_scene.json", (16 << 20) + 1);
  const std::string urdf_limit = big_urdf + ": larger than the 64 MiB limit of a URDF file";
  expect_refused_quickly({"info", big_urdf}, {urdf_limit});
  expect_refused_quickly({"solve", big_urdf, "--case", ok_case_}, {urdf_limit});
  expect_refused_quickly({"solve", kKuka, "--root", kKukaRoot, "--tip", "lwr_link_7", "--case", big_case},
                         {big_case + ": larger than the 16 MiB limit of a case file"});
  expect_refused_quickly({"simulate", big_scene}, {big_scene + ": larger than the 16 MiB limit of a scene file"});
  expect_refused_quickly({"simulate", scene_with_urdf("big_urdf_scene.json", big_urdf)}, {urdf_limit});
  ChildIo zeros;
  zeros.stdin_path = "/dev/zero";
  expect_refused_quickly({"solve", kKuka, "--root", kKukaRoot, "--tip", "lwr_link_7", "--case", "-"},
                         {"-: larger than the 16 MiB limit of a case file"}, zeros);
  report_costs();
}

// A file at the limit or under it still loads: the limits refuse only what is past them.
TEST_F(BadInputFiles, FilesUnderTheLimitsStillLoad) {
  const ChildRun r = run_child(dir_, {"solve", kKuka, "--root", kKukaRoot, "--tip", "lwr_link_7", "--case", ok_case_}, 30);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"qdd\""), std::string::npos);
  ChildIo piped;
  piped.stdin_path = ok_case_;
  const ChildRun s =
      run_child(dir_, {"solve", kKuka, "--root", kKukaRoot, "--tip", "lwr_link_7", "--case", "-"}, 30, piped);
  EXPECT_EQ(s.exit_code, 0) << s.err;
}

}  // namespace
}  // namespace achd::test
