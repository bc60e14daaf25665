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

DirectionEventLog::DirectionEventLog(std::size_t capacity) : capacity_(capacity) { events_.reserve(capacity); }

void DirectionEventLog::clear() {
  state_.fill(State::Ok);
  events_.clear();
  not_kept_ = 0;
}

void DirectionEventLog::record(const DirectionEvent& e) {
  if (events_.size() < capacity_) events_.push_back(e);
  else ++not_kept_;
}

unsigned DirectionEventLog::update(const HeldDirections& held, const Data& first, double t, std::int64_t step,
                                   int link) {
  // The active directions in column order, and the largest lambda / sigma attributed to
  // each (0: none of its eigen-directions is damped; inf: sigma = 0).
  int direction_of_column[kNumDirections];
  int nc = 0;
  for (int k = 0; k < kNumDirections; ++k)
    if (held.active(k)) direction_of_column[nc++] = k;
  std::array<double, kNumDirections> ratio{};
  std::array<bool, kNumDirections> damped{};
  const Eigen::Index ndamped = first.damped.rows() == nc ? first.damped.cols() : 0;
  for (Eigen::Index j = 0; j < ndamped; ++j) {
    Eigen::Index column = 0;
    first.damped.col(j).cwiseAbs().maxCoeff(&column);
    const int k = direction_of_column[column];
    const double sigma = first.damped_sigma[j], lambda = first.damped_lambda[j];
    const double r = sigma > 0 ? lambda / sigma : std::numeric_limits<double>::infinity();
    damped[k] = true;
    ratio[k] = std::max(ratio[k], r);
  }
  unsigned resumed = 0;
  bool any = false;
  DirectionEvent e{t, step, link, 0, DirectionEventKind::Limited, 0.0};
  for (int k = 0; k < kNumDirections; ++k) {
    if (!held.active(k)) {
      state_[k] = State::Ok;
      continue;
    }
    if (damped[k]) last_damped_[k] = t;
    State next = state_[k];
    if (ratio[k] >= kReleasedRatio) next = State::Released;
    else if (state_[k] == State::Ok && damped[k]) next = State::Limited;
    else if (state_[k] != State::Ok && !damped[k] && t - last_damped_[k] >= kResumeAfter) next = State::Ok;
    if (next == state_[k]) continue;
    if (!any) e.sigma_min = sigma_min(first);  // computed once, only when something changed
    any = true;
    e.direction = k;
    e.kind = next == State::Ok ? DirectionEventKind::Resumed
             : next == State::Limited ? DirectionEventKind::Limited : DirectionEventKind::Released;
    record(e);
    if (state_[k] == State::Released && next == State::Ok) resumed |= 1u << k;
    state_[k] = next;
  }
  return resumed;
}

}  // namespace achd
