#pragma once
// Side-by-side timing: ns per call, the median over repeats after a warm-up, with the
// repeats of several candidates interleaved so that machine noise hits them alike.
#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace achd::cli {

// Calls per repeat such that one repeat of `fn` takes about `target_ns`.
inline long calibrate_iterations(const std::function<void()>& fn, double target_ns) {
  using clock = std::chrono::steady_clock;
  for (long n = 1;; n *= 2) {
    const auto t0 = clock::now();
    for (long i = 0; i < n; ++i) fn();
    const double ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count();
    if (ns >= target_ns / 4 || n >= (1L << 24))
      return std::max(1L, static_cast<long>(n * target_ns / std::max(ns, 1.0)));
  }
}

// Median ns per call of each candidate: `repeats` rounds, each round timing `iterations`
// calls of every candidate in turn. The first round is a warm-up and is discarded.
inline std::vector<double> median_ns(const std::vector<std::function<void()>>& fns,
                                     const std::vector<long>& iterations, int repeats) {
  using clock = std::chrono::steady_clock;
  std::vector<std::vector<double>> samples(fns.size());
  for (int r = 0; r <= repeats; ++r)
    for (std::size_t k = 0; k < fns.size(); ++k) {
      const auto t0 = clock::now();
      for (long i = 0; i < iterations[k]; ++i) fns[k]();
      const double ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count();
      if (r > 0) samples[k].push_back(ns / iterations[k]);
    }
  std::vector<double> out;
  for (auto& s : samples) {
    std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
    out.push_back(s[s.size() / 2]);
  }
  return out;
}

}  // namespace achd::cli
