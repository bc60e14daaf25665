#include "progress.hpp"

#include <signal.h>

#include <cstdio>
#include <iostream>

namespace achd::cli {
namespace {

// The signal that stopped the run (SIGINT, SIGTERM or SIGHUP), 0 while none has come.
volatile sig_atomic_t g_signal = 0;

void on_stop_signal(int signal) { g_signal = signal; }

// The clock is read every kClockSteps steps: a step takes 0.1 us (2 joints, Euler) to
// tens of us, so a line is at most a few ms late and the clock costs nothing per step.
constexpr std::int64_t kClockSteps = 64;

}  // namespace

void catch_interrupt() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;  // one of each; the next one kills
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaction(signal, &action, nullptr);
}

std::string Interrupted::signal_name() const {
  switch (signal_) {
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "SIGINT";
  }
}

Progress::Progress(std::function<std::string(std::int64_t)> status)
    : status_(std::move(status)),
      start_(std::chrono::steady_clock::now()),
      next_line_(start_ + std::chrono::seconds(1)) {}

void Progress::step(std::int64_t n) {
  done_ += n;
  if (g_signal) throw Interrupted(status_(done_), g_signal);
  if (done_ < next_check_) return;
  next_check_ = done_ + kClockSteps;
  const auto now = std::chrono::steady_clock::now();
  if (now < next_line_) return;
  next_line_ = now + std::chrono::seconds(1);
  char elapsed[32];
  std::snprintf(elapsed, sizeof elapsed, "%.0f", std::chrono::duration<double>(now - start_).count());
  std::cerr << "achd: " << status_(done_) << ", " << elapsed << " s elapsed" << std::endl;
}

}  // namespace achd::cli
