#pragma once
// Long CLI runs (achd simulate, achd accuracy): a progress line on stderr at most once a
// second, starting after the first second (short runs stay silent), and Ctrl-C.
// Ctrl-C (SIGINT), SIGTERM (kill, a service manager) and SIGHUP (the terminal closed)
// only set a flag, which Progress::step() checks between steps: it then throws
// Interrupted, which main() reports as one line "achd: interrupted: ..." (SIGINT) or
// "achd: interrupted by SIGTERM: ..." on stderr with exit code 128 + the signal (130,
// 143, 129: the shell's convention); the stack unwinds, so an output file's temporary
// file is removed. The handler is installed for one signal of each kind; a second one
// ends the process at once.
#include <chrono>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

namespace achd::cli {

// A run stopped by a signal; what() says what it had done.
class Interrupted : public std::runtime_error {
 public:
  Interrupted(const std::string& what, int signal) : std::runtime_error(what), signal_(signal) {}
  int signal() const { return signal_; }
  std::string signal_name() const;  // "SIGINT", "SIGTERM", "SIGHUP"

 private:
  int signal_;
};

// Installs the SIGINT, SIGTERM and SIGHUP handler (see above). Call it before creating
// an output file, so that no signal can end the process with the temporary file left.
void catch_interrupt();

class Progress {
 public:
  // status(done): the run after `done` steps, e.g. "simulate s.json: t = 1.2 s of 5 s
  // (1200 of 5000 steps)"; called only to print a line or to build Interrupted.
  explicit Progress(std::function<std::string(std::int64_t)> status);

  // After `n` more steps: prints a line when a second has passed since the last one
  // (or since the start), throws Interrupted(status) after Ctrl-C.
  void step(std::int64_t n = 1);
  std::int64_t done() const { return done_; }

 private:
  std::function<std::string(std::int64_t)> status_;
  std::chrono::steady_clock::time_point start_, next_line_;
  std::int64_t done_ = 0, next_check_ = 0;
};

}  // namespace achd::cli
