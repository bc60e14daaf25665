#pragma once
// Side-by-side timing on a shared, noisy machine: ns per call over many short rounds,
// each round timing every candidate in turn, so that load changes hit them alike.
// Report medians of the rounds, and ratios as the median of per-round ratios. The default
// clock is this thread's CPU time: time spent descheduled (other jobs on the cores) is
// not counted, which on a shared machine is most of the noise. The wall clock is there
// for comparisons with a timer that has no CPU clock (wasm in Node).
#include <time.h>

#include <algorithm>
#include <functional>
#include <vector>

namespace achd::cli {

enum class Clock { ThreadCpu, Wall };

inline double now_ns(Clock clock = Clock::ThreadCpu) {
  timespec t;
  clock_gettime(clock == Clock::Wall ? CLOCK_MONOTONIC : CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e9 + t.tv_nsec;
}

// Calls per round such that one round of `fn` takes about `target_ns`.
inline long calibrate_iterations(const std::function<void()>& fn, double target_ns,
                                 Clock clock = Clock::ThreadCpu) {
  for (long n = 1;; n *= 2) {
    const double t0 = now_ns(clock);
    for (long i = 0; i < n; ++i) fn();
    const double ns = now_ns(clock) - t0;
    if (ns >= target_ns / 4 || n >= (1L << 24))
      return std::max(1L, static_cast<long>(n * target_ns / std::max(ns, 1.0)));
  }
}

// ns per call of each candidate in each of `rounds` rounds (samples[k][r]), after one
// warm-up round that is discarded.
inline std::vector<std::vector<double>> sample_ns(const std::vector<std::function<void()>>& fns,
                                                  const std::vector<long>& iterations, int rounds,
                                                  Clock clock = Clock::ThreadCpu) {
  std::vector<std::vector<double>> samples(fns.size());
  for (int r = 0; r <= rounds; ++r)
    for (std::size_t k = 0; k < fns.size(); ++k) {
      const double t0 = now_ns(clock);
      for (long i = 0; i < iterations[k]; ++i) fns[k]();
      const double ns = now_ns(clock) - t0;
      if (r > 0) samples[k].push_back(ns / iterations[k]);
    }
  return samples;
}

inline double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Median over rounds of a[r] / b[r].
inline double median_ratio(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) r[i] = a[i] / b[i];
  return median(r);
}

}  // namespace achd::cli
