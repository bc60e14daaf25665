#include "direction_events.hpp"

#include <cmath>
#include <limits>

#include "achd/hybrid_dynamics.hpp"

namespace achd {
namespace {

// A direction is limited as soon as the damping acts on one of its eigen-directions
// (lambda > 0: sigma below the singular region), released when the damping dominates
// (lambda >= sigma: sigma below 0.71 of the region), and resumed once none of its
// eigen-directions has been damped for kResumeAfter seconds: the hysteresis that keeps a
// robot sitting on the edge of the region from producing an event per step.
constexpr double kReleasedRatio = 1.0;
constexpr double kResumeAfter = 0.05;

}  // namespace

DirectionEventLog::DirectionEventLog(std::size_t capacity, int max_sets)
    : state_(max_sets), last_damped_(max_sets), ratio_(max_sets), damped_(max_sets), capacity_(capacity) {
  events_.reserve(capacity);
  column_.reserve(kMaxConstraintColumns);
}

void DirectionEventLog::clear() {
  for (auto& s : state_) s.fill(State::Ok);
  events_.clear();
  not_kept_ = 0;
}

void DirectionEventLog::record(const DirectionEvent& e) {
  if (events_.size() < capacity_) events_.push_back(e);
  else ++not_kept_;
}

void DirectionEventLog::update(const std::vector<LinkDirections>& sets, const Data& first, double t,
                               std::int64_t step, std::vector<unsigned>& resumed) {
  // The active directions in column order, and the largest lambda / sigma attributed to
  // each (0: none of its eigen-directions is damped; inf: sigma = 0).
  column_.clear();
  const int nsets = static_cast<int>(sets.size());
  for (int s = 0; s < nsets; ++s) {
    ratio_[s].fill(0);
    damped_[s].fill(false);
    for (int k = 0; k < kNumDirections; ++k)
      if (sets[s].held.active(k)) column_.emplace_back(s, k);
  }
  // K's columns: the sets' directions, then the loop joints' (Case::loop_beta's), which
  // have no direction of a link to attribute to.
  const Eigen::Index nc = static_cast<Eigen::Index>(column_.size());
  const Eigen::Index ndamped = first.damped.rows() >= nc ? first.damped.cols() : 0;
  for (Eigen::Index j = 0; j < ndamped; ++j) {
    Eigen::Index column = 0;
    first.damped.col(j).cwiseAbs().maxCoeff(&column);
    if (column >= nc) continue;
    const auto [s, k] = column_[column];
    const double sigma = first.damped_sigma[j], lambda = first.damped_lambda[j];
    const double r = sigma > 0 ? lambda / sigma : std::numeric_limits<double>::infinity();
    damped_[s][k] = true;
    ratio_[s][k] = std::max(ratio_[s][k], r);
  }
  bool any = false;
  DirectionEvent e{t, step, 0, 0, DirectionEventKind::Limited, 0.0};
  for (int s = 0; s < nsets; ++s) {
    resumed[s] = 0;
    std::array<State, kNumDirections>& state = state_[s];
    for (int k = 0; k < kNumDirections; ++k) {
      if (!sets[s].held.active(k)) {
        state[k] = State::Ok;
        continue;
      }
      if (damped_[s][k]) last_damped_[s][k] = t;
      State next = state[k];
      if (ratio_[s][k] >= kReleasedRatio) next = State::Released;
      else if (state[k] == State::Ok && damped_[s][k]) next = State::Limited;
      else if (state[k] != State::Ok && !damped_[s][k] && t - last_damped_[s][k] >= kResumeAfter) next = State::Ok;
      if (next == state[k]) continue;
      if (!any) e.sigma_min = sigma_min(first);  // computed once, only when something changed
      any = true;
      e.link = sets[s].link;
      e.direction = k;
      e.kind = next == State::Ok ? DirectionEventKind::Resumed
               : next == State::Limited ? DirectionEventKind::Limited : DirectionEventKind::Released;
      record(e);
      if (state[k] == State::Released && next == State::Ok) resumed[s] |= 1u << k;
      state[k] = next;
    }
  }
}

}  // namespace achd
