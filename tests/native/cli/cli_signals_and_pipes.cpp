// How `achd` ends when it is told to stop or cannot write its result:
//   - SIGTERM and SIGHUP during `simulate --out F` are handled as Ctrl-C is: exit
//     128 + the signal, one line "achd: interrupted by SIGTERM: ..." saying how far the
//     run got, and no file at all, the temporary one included (before: the default
//     action killed the process and left .F.achd-PID-0.tmp behind);
//   - a closed stdout is a failed write like a full disk: exit 2 and one line
//     "achd: error: ... Broken pipe", as docs/guide/cli.md says (before: killed by SIGPIPE,
//     exit 141 and no message), for the result JSON and for `--out -`, and through a
//     real `| head -c 10`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_child.hpp"

namespace achd::test {
namespace {

namespace fs = std::filesystem;

class CliSignalsAndPipes : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "achd_cli_signals_XXXXXX";
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return dir_ + "/" + name; }

  // The planar arm's damped swing for `duration` seconds at 1 ms.
  std::string planar2_scene(const std::string& duration) const {
    std::ofstream(path("long.json")) << R"({"urdf": ")" ACHD_SOURCE_DIR R"(/robots/planar2.urdf", "root": "base_link",
      "tip": "link2", "q0": [0.4, 0.9], "effects": {"damping": true, "friction": false, "constraints": false},
      "integrator": "semi_implicit_euler", "dt": 0.001, "duration": )" << duration << "}";
    return path("long.json");
  }

  // The files in the test directory other than the scene and the captured streams.
  std::vector<std::string> left_behind() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      if (name != "long.json" && name != "stdout.txt" && name != "stderr.txt") out.push_back(name);
    }
    return out;
  }

  // Starts a long simulate --out traj.csv, waits until its temporary file exists (the run
  // is writing), sends `signal` and checks how it ended.
  void expect_stopped_cleanly(int signal, const std::string& name) {
    const std::string scene = planar2_scene("4.3e6");
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = start_child(dir_, {"simulate", scene, "--out", path("traj.csv")});
    ASSERT_GT(pid, 0);
    const auto deadline = start + std::chrono::seconds(30);
    while (left_behind().empty() && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_EQ(left_behind().size(), 1u) << "no temporary file within 30 s";
    EXPECT_EQ(left_behind()[0].rfind(".traj.csv.achd-", 0), 0u) << left_behind()[0];
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // well into the steps
    kill(pid, signal);
    const ChildRun r = finish_child(dir_, pid, start, 60);
    EXPECT_FALSE(r.killed);
    EXPECT_EQ(r.signal, 0) << "ended by signal " << r.signal << " instead of exiting";
    EXPECT_EQ(r.exit_code, 128 + signal) << r.err;
    EXPECT_EQ(r.out, "");
    const std::string line = "achd: interrupted by " + name + ": simulate " + scene + ": t = ";
    EXPECT_EQ(r.err.rfind(line, 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
    EXPECT_NE(r.err.find("; no file written to " + path("traj.csv")), std::string::npos) << r.err;
    EXPECT_EQ(left_behind(), std::vector<std::string>{});
  }

  std::string dir_;
};

TEST_F(CliSignalsAndPipes, SigtermDuringSimulateLeavesNoFile) { expect_stopped_cleanly(SIGTERM, "SIGTERM"); }

TEST_F(CliSignalsAndPipes, SighupDuringSimulateLeavesNoFile) { expect_stopped_cleanly(SIGHUP, "SIGHUP"); }

// stdout a pipe whose reading end is already closed: every write fails at once.
ChildIo closed_pipe(int fds[2]) {
  EXPECT_EQ(pipe(fds), 0);
  close(fds[0]);
  ChildIo io;
  io.stdout_fd = fds[1];
  return io;
}

TEST_F(CliSignalsAndPipes, AClosedStdoutIsExitTwoWithOneLine) {
  int fds[2];
  const ChildRun info =
      run_child(dir_, {"info", ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf"}, 30, closed_pipe(fds));
  close(fds[1]);
  EXPECT_EQ(info.signal, 0) << "ended by signal " << info.signal;
  EXPECT_EQ(info.exit_code, 2) << info.err;
  EXPECT_EQ(info.err, "achd: error: cannot write the result to stdout: Broken pipe\n");

  // The trajectory on stdout: the run stops at the first failed write.
  const ChildRun csv = run_child(dir_, {"simulate", planar2_scene("10"), "--out", "-"}, 30, closed_pipe(fds));
  close(fds[1]);
  EXPECT_EQ(csv.signal, 0) << "ended by signal " << csv.signal;
  EXPECT_EQ(csv.exit_code, 2) << csv.err;
  EXPECT_EQ(csv.err.rfind("achd: error: ", 0), 0u) << csv.err;
  EXPECT_NE(csv.err.find("cannot write: Broken pipe"), std::string::npos) << csv.err;
  EXPECT_EQ(csv.err.find('\n'), csv.err.size() - 1) << "not one line: " << csv.err;
}

// The shell's own pipe: 10 s of trajectory (10001 rows, far more than a pipe holds) into
// `head -c 10`, bash started with SIGPIPE at its default as in a terminal; its
// PIPESTATUS gives achd's exit code.
TEST_F(CliSignalsAndPipes, PipedIntoHeadIsExitTwoWithOneLine) {
  std::string command = "'" ACHD_CLI "' simulate '" + planar2_scene("10") + "' --out - 2>'" + path("stderr.txt") +
                        "' | head -c 10 >/dev/null; exit ${PIPESTATUS[0]}";
  std::vector<char*> argv = {const_cast<char*>("bash"), const_cast<char*>("-c"), command.data(), nullptr};
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = -1;
  ASSERT_EQ(posix_spawnp(&pid, "bash", nullptr, &attr, argv.data(), environ), 0);
  posix_spawnattr_destroy(&attr);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2) << "141 is 128 + SIGPIPE";
  const std::string err = child_file_text(path("stderr.txt"));
  EXPECT_EQ(err.rfind("achd: error: ", 0), 0u) << err;
  EXPECT_NE(err.find("Broken pipe"), std::string::npos) << err;
}

}  // namespace
}  // namespace achd::test
