#pragma once
// Whether each active direction of every link is being followed, from the
// variable_damping solve at the start of every step: the damped eigen-directions of the
// coupling matrix K are attributed to the active direction with the largest component of
// the eigenvector (the simulator's columns are unit vectors, one per active direction, set
// by set in the order of nu), and each direction moves between ok, limited and released
// with hysteresis, recording a DirectionEvent (naming its link) at each change.
#include <array>
#include <cstdint>
#include <vector>

#include "achd/data.hpp"
#include "achd/directions.hpp"

namespace achd {

class DirectionEventLog {
 public:
  // Keeps at most `capacity` events (reserved here: recording never allocates); the
  // ones beyond it are counted in not_kept(). Up to `max_sets` direction sets.
  DirectionEventLog(std::size_t capacity, int max_sets);

  // Every direction back to ok, no events (Simulator::reset()).
  void clear();
  // Direction k of set s back to ok without an event (Simulator::set_direction()).
  void forget(int s, int k) { state_[s][k] = State::Ok; }

  // Reads the damped eigen-directions of `first` (the solve of the state at time t after
  // `step` steps) for the directions active in `sets`, records the changes, and sets bit k
  // of resumed[s] for each direction k of set s that resumed from released (the others 0).
  void update(const std::vector<LinkDirections>& sets, const Data& first, double t, std::int64_t step,
              std::vector<unsigned>& resumed);

  const std::vector<DirectionEvent>& events() const { return events_; }
  std::int64_t not_kept() const { return not_kept_; }

 private:
  enum class State { Ok, Limited, Released };
  void record(const DirectionEvent& e);

  std::vector<std::array<State, kNumDirections>> state_;  // per set
  std::vector<std::array<double, kNumDirections>> last_damped_;  // t of the last solve that damped it
  // Scratch of update(), per set: the largest lambda / sigma of its directions, and whether damped.
  std::vector<std::array<double, kNumDirections>> ratio_;
  std::vector<std::array<bool, kNumDirections>> damped_;
  std::vector<std::pair<int, int>> column_;  // column j of K: (set, direction)
  std::vector<DirectionEvent> events_;
  std::size_t capacity_;
  std::int64_t not_kept_ = 0;
};

}  // namespace achd
