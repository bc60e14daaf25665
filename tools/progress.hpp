#pragma once
// Long CLI runs (achd simulate, achd accuracy): a progress line on stderr at most once a
// second, starting after the first second (short runs stay silent), and Ctrl-C.
// Ctrl-C (SIGINT) only sets a flag, which Progress::step() checks between steps: it then
// throws Interrupted, which main() reports as one line "achd: interrupted: ..." on
// stderr with exit code 130 (128 + SIGINT, the shell's convention). The handler is
// installed for one Ctrl-C; a second one ends the process at once.
#include <chrono>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

namespace achd::cli {

// A run stopped by Ctrl-C; what() says what it had done.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(const std::string& what) : std::runtime_error(what) {}
};

// Installs the SIGINT handler (see above).
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
