#include "direction_events.hpp"

#include <cmath>
#include <limits>

#include "achd/hybrid_dynamics.hpp"

namespace achd {
namespace {

// A direction is limited as soon as the damping (lambda > 0 on an eigen-direction: sigma
// below the singular region) leaves its own column with an effect: more than
// kUnmetPosition w^2 of its acceleration undelivered (a constant unmet acceleration u
// settles as a position error u / w^2 under the stabilisation at w, so below it the
// direction stays within kUnmetPosition of its hold, m or rad). It is released when the
// damping dominates (lambda >= sigma: sigma below 0.71 of the region), and resumed once
// it has not been lost for kResumeAfter seconds: the hysteresis that keeps a robot
// sitting on the edge of the region from producing an event per step. A pushed direction
// given up for the joints' efforts is lost the same way (limited while the solve moves
// away from it, released once it is wholly given up).
constexpr double kReleasedRatio = 1.0;
constexpr double kResumeAfter = 0.05;
constexpr double kUnmetPosition = 1e-9;

}  // namespace

DirectionEventLog::DirectionEventLog(std::size_t capacity, int max_sets, int num_loops)
    : max_sets_(max_sets),
      state_(max_sets + num_loops),
      last_lost_(max_sets + num_loops),
      released_at_(max_sets + num_loops),
      released_s_(max_sets + num_loops),
      ratio_(max_sets + num_loops),
      lost_(max_sets + num_loops),
      unmet_(max_sets + num_loops),
      capacity_(capacity) {
  events_.reserve(capacity);
  column_.reserve(kMaxConstraintColumns);
  clear();
}

void DirectionEventLog::clear() {
  for (auto& s : state_) s.fill(State::Ok);
  for (auto& s : released_s_) s.fill(0);
  events_.clear();
  not_kept_ = 0;
}

void DirectionEventLog::forget(int s, int k) {
  state_[s][k] = State::Ok;
  released_s_[s][k] = 0;
}

double DirectionEventLog::released_seconds(int s, int k, double t) const {
  return released_s_[s][k] + (state_[s][k] == State::Released ? t - released_at_[s][k] : 0.0);
}

void DirectionEventLog::record(const DirectionEvent& e) {
  if (events_.size() < capacity_) events_.push_back(e);
  else ++not_kept_;
}

void DirectionEventLog::update(const Model& model, const std::vector<LinkDirections>& sets, const Data& first,
                               double t, std::int64_t step, double w, std::vector<unsigned>& resumed) {
  // The active directions in column order (K's columns: the sets' directions, then the
  // loop joints'), and per direction the largest lambda / sigma of the damped
  // eigen-directions attributed to it (0: none; inf: sigma = 0).
  column_.clear();
  const int nsets = static_cast<int>(sets.size()), nloops = static_cast<int>(model.loops.size());
  for (int s = 0; s < nsets; ++s)
    for (int k = 0; k < kNumDirections; ++k)
      if (sets[s].held.active(k)) column_.emplace_back(s, k);
  for (int l = 0; l < nloops; ++l)
    for (int k = 0; k < kNumDirections; ++k)
      if (model.loops[l].directions >> k & 1u) column_.emplace_back(loop_set(l), k);
  for (const auto& [s, k] : column_) {
    ratio_[s][k] = 0;
    lost_[s][k] = false;
    unmet_[s][k] = 0;
  }
  const Eigen::Index nc = static_cast<Eigen::Index>(column_.size());
  const Eigen::Index ndamped = first.damped.rows() == nc ? first.damped.cols() : 0;
  const bool yielded = first.yielded > 0 && first.nu.size() == nc;
  if (ndamped || yielded) {
    // What the solve leaves undelivered along column j, in m/s^2 or rad/s^2: the
    // residual of K nu = rhs, r = K_s nu' - rhs' in the scaled columns alpha_j s_j
    // (nu' = nu / s), divided by s_j.
    const Data::Workspace& ws = first.workspace;
    for (Eigen::Index j = 0; j < nc; ++j) {
      double r = -ws.rhs[j];
      for (Eigen::Index i = 0; i < nc; ++i) r += first.K(j, i) * (first.nu[i] / ws.alpha_scale[i]);
      const auto [s, k] = column_[j];
      unmet_[s][k] = std::abs(r / ws.alpha_scale[j]);
    }
  }
  // The solve damps whole eigen-directions but leaves them undelivered in the columns that
  // gave way (coupling_solve.cpp's held-first solve: the others are solved exactly), so a
  // direction is lost when its own column's acceleration is undelivered with an effect,
  // whichever eigen-direction the damping acted on; lambda / sigma, the largest of the
  // damped eigen-directions, says whether the damping dominates.
  const double unmet_tolerance = kUnmetPosition * w * w;
  double damping_ratio = 0;
  for (Eigen::Index j = 0; j < ndamped; ++j) {
    const double sigma = first.damped_sigma[j], lambda = first.damped_lambda[j];
    damping_ratio = std::max(damping_ratio, sigma > 0 ? lambda / sigma : std::numeric_limits<double>::infinity());
  }
  for (Eigen::Index j = 0; ndamped && j < nc; ++j) {
    const auto [s, k] = column_[j];
    if (!(unmet_[s][k] > unmet_tolerance)) continue;  // delivered: still followed
    lost_[s][k] = true;
    ratio_[s][k] = damping_ratio;
  }
  // Pushed directions the solve gave up for the joints' efforts (yield_to_efforts.hpp):
  // lost while it did with an effect, released once wholly given up (yielded = 1).
  for (Eigen::Index j = 0; yielded && j < nc; ++j) {
    const auto [s, k] = column_[j];
    if (s >= nsets || sets[s].held.mode[k] != DirectionMode::Accelerate || !(unmet_[s][k] > unmet_tolerance)) continue;
    lost_[s][k] = true;
    ratio_[s][k] = std::max(ratio_[s][k], first.yielded >= 1 ? kReleasedRatio : 0.0);
  }
  bool any = false;
  DirectionEvent e{t, step, -1, -1, 0, DirectionEventKind::Limited, 0.0, 0.0, 0.0};
  for (int s = 0; s < nsets; ++s) resumed[s] = 0;
  for (int s = 0; s < nsets + nloops; ++s) {
    const bool loop = s >= nsets;
    const int row = loop ? loop_set(s - nsets) : s;
    std::array<State, kNumDirections>& state = state_[row];
    for (int k = 0; k < kNumDirections; ++k) {
      const bool active = loop ? (model.loops[s - nsets].directions >> k & 1u) : sets[s].held.active(k);
      if (!active) {
        state[k] = State::Ok;
        continue;
      }
      if (lost_[row][k]) last_lost_[row][k] = t;
      State next = state[k];
      if (ratio_[row][k] >= kReleasedRatio) next = State::Released;
      else if (state[k] == State::Ok && lost_[row][k]) next = State::Limited;
      else if (state[k] != State::Ok && !lost_[row][k] && t - last_lost_[row][k] >= kResumeAfter) next = State::Ok;
      if (next == state[k]) continue;
      if (!any) {  // computed once, only when something changed
        e.sigma_min = sigma_min(first);
        e.effort_ratio = first.effort_ratio;
      }
      any = true;
      e.link = loop ? -1 : sets[s].link;
      e.loop = loop ? s - nsets : -1;
      e.direction = k;
      e.unmet = unmet_[row][k];
      e.kind = next == State::Ok ? DirectionEventKind::Resumed
               : next == State::Limited ? DirectionEventKind::Limited : DirectionEventKind::Released;
      record(e);
      if (next == State::Released) released_at_[row][k] = t;
      if (state[k] == State::Released) {
        released_s_[row][k] += t - released_at_[row][k];
        if (!loop && next == State::Ok) resumed[s] |= 1u << k;
      }
      state[k] = next;
    }
  }
}

}  // namespace achd
