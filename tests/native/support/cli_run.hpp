#pragma once
// The real `achd` binary (ACHD_CLI, from CMake) run as a child process, its stdout and
// stderr captured in files under a directory of the caller's.
#include <string>
#include <vector>

namespace achd::test {

struct CliRun {
  int exit_code = -1;  // -1: not spawned, or killed by a signal
  std::string out, err;
};

// Runs ACHD_CLI with `args`; stdout and stderr go to `dir`/stdout.txt, stderr.txt.
CliRun run_cli(const std::string& dir, const std::vector<std::string>& args);

// A fresh directory under the test's temporary directory.
std::string make_temp_dir(const std::string& prefix);

}  // namespace achd::test
