#pragma once
// The real `achd` binary (ACHD_CLI) as a child process held to a time limit, with what
// it cost: the wall time, its peak memory (the kernel's ru_maxrss) and how it ended.
// For inputs that used to hang or eat memory (a FIFO, /dev/zero): the child is killed
// when it passes the time limit or 300 MB of resident memory, so that such a test fails
// quickly instead of taking the machine with it.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace achd::test {

struct ChildRun {
  int exit_code = -1;    // -1 when it ended by a signal (or was killed here)
  int signal = 0;        // the signal that ended it, 0 when it exited
  bool killed = false;   // killed here: past the time limit or the memory limit
  double seconds = 0;    // from the start to the end
  long peak_rss_kb = 0;  // ru_maxrss of the child
  std::string out, err;
};

struct ChildIo {
  std::string stdin_path = "/dev/null";
  int stdout_fd = -1;  // a descriptor to give as stdout; -1: the file dir/stdout.txt
};

inline std::string child_file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Starts ACHD_CLI `args` with stderr (and stdout unless io.stdout_fd) into files in `dir`.
// SIGPIPE is set back to its default in the child, whatever the test runner ignores.
inline pid_t start_child(const std::string& dir, const std::vector<std::string>& args, const ChildIo& io = {}) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, io.stdin_path.c_str(), O_RDONLY, 0);
  if (io.stdout_fd >= 0) posix_spawn_file_actions_adddup2(&actions, io.stdout_fd, 1);
  else posix_spawn_file_actions_addopen(&actions, 1, (dir + "/stdout.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, (dir + "/stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  std::vector<std::string> all = {ACHD_CLI};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, ACHD_CLI, &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  return spawned == 0 ? pid : -1;
}

// The child's resident memory now, in kB (0 when it cannot be read).
inline long child_rss_kb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return 0;
}

// Waits for the child started at `start`; kills it past `seconds` or 300 MB resident.
inline ChildRun finish_child(const std::string& dir, pid_t pid, std::chrono::steady_clock::time_point start,
                             double seconds) {
  ChildRun r;
  if (pid < 0) return r;
  constexpr long kKillKb = 300 * 1024;
  const auto deadline = start + std::chrono::duration<double>(seconds);
  int status = 0;
  struct rusage usage {};
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (std::chrono::steady_clock::now() > deadline || child_rss_kb(pid) > kKillKb) {
      r.killed = true;
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.peak_rss_kb = usage.ru_maxrss;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  r.out = child_file_text(dir + "/stdout.txt");  // "" when stdout went elsewhere
  r.err = child_file_text(dir + "/stderr.txt");
  return r;
}

// start_child and finish_child in one.
inline ChildRun run_child(const std::string& dir, const std::vector<std::string>& args, double seconds,
                          const ChildIo& io = {}) {
  const auto start = std::chrono::steady_clock::now();
  return finish_child(dir, start_child(dir, args, io), start, seconds);
}

}  // namespace achd::test
