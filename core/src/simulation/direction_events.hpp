#pragma once
// Whether each active direction of every link and every loop joint is being followed, from
// the variable_damping solve at the start of every step: the damped eigen-directions of the
// coupling matrix K are attributed to the active direction with the largest component of
// the eigenvector (the simulator's columns are unit vectors, one per active direction, set
// by set in the order of nu, then the loops' columns), a damped direction is lost when the
// solve leaves more than w^2 1e-9 of its acceleration undelivered (directions.hpp), and each
// direction moves between ok, limited and released with hysteresis, recording a
// DirectionEvent (naming its link or loop) at each change, and how long it was released.
#include <array>
#include <cstdint>
#include <vector>

#include "achd/data.hpp"
#include "achd/directions.hpp"
#include "achd/model.hpp"

namespace achd {

class DirectionEventLog {
 public:
  // Keeps at most `capacity` events (reserved here: recording never allocates); the
  // ones beyond it are counted in not_kept(). Up to `max_sets` direction sets, and the
  // model's loop joints.
  DirectionEventLog(std::size_t capacity, int max_sets, int num_loops);

  // Every direction back to ok, no events, no released time (Simulator::reset()).
  void clear();
  // Direction k of set s back to ok without an event, its released time 0
  // (Simulator::set_direction()).
  void forget(int s, int k);

  // Reads the damped eigen-directions of `first` (the solve of the state at time t after
  // `step` steps, its held directions stabilised at frequency w) for the directions active
  // in `sets` and the loops, records the changes, and sets bit k of resumed[s] for each
  // direction k of set s that resumed from released (the others 0).
  void update(const Model& model, const std::vector<LinkDirections>& sets, const Data& first, double t,
              std::int64_t step, double w, std::vector<unsigned>& resumed);

  // Whether direction k of set s is released now, and for how long (s) it has been
  // released in all (up to time t) since it was set.
  bool released(int s, int k) const { return state_[s][k] == State::Released; }
  double released_seconds(int s, int k, double t) const;
  // The same for direction k of loop joint l.
  double loop_released_seconds(int l, int k, double t) const { return released_seconds(loop_set(l), k, t); }
  // Whether some direction of loop joint l is released now.
  bool loop_released(int l) const {
    for (State s : state_[loop_set(l)])
      if (s == State::Released) return true;
    return false;
  }

  const std::vector<DirectionEvent>& events() const { return events_; }
  std::int64_t not_kept() const { return not_kept_; }

 private:
  enum class State { Ok, Limited, Released };
  void record(const DirectionEvent& e);
  int loop_set(int l) const { return max_sets_ + l; }  // a loop's row in the per-set arrays

  int max_sets_;

  std::vector<std::array<State, kNumDirections>> state_;  // per set
  std::vector<std::array<double, kNumDirections>> last_lost_;  // t of the last solve that lost it
  std::vector<std::array<double, kNumDirections>> released_at_;  // t it was released (while released)
  std::vector<std::array<double, kNumDirections>> released_s_;   // released time before that
  // Scratch of update(), per set: the largest lambda / sigma of its directions, and whether lost.
  std::vector<std::array<double, kNumDirections>> ratio_;
  std::vector<std::array<bool, kNumDirections>> lost_;
  std::vector<std::array<double, kNumDirections>> unmet_;
  std::vector<std::pair<int, int>> column_;  // column j of K: (set, direction); loops after the sets
  std::vector<DirectionEvent> events_;
  std::size_t capacity_;
  std::int64_t not_kept_ = 0;
};

}  // namespace achd
