#pragma once
// Whether each active tip direction is being followed, from the variable_damping solve
// at the start of every step: the damped eigen-directions of the coupling matrix K are
// attributed to the active direction with the largest component of the eigenvector (the
// simulator's columns are unit vectors, one per active direction in index order), and
// each direction moves between ok, limited and released with hysteresis, recording a
// DirectionEvent at each change.
#include <array>
#include <cstdint>
#include <vector>

#include "achd/data.hpp"
#include "achd/simulator.hpp"

namespace achd {

class DirectionEventLog {
 public:
  // Keeps at most `capacity` events (reserved here: recording never allocates); the
  // ones beyond it are counted in not_kept().
  explicit DirectionEventLog(std::size_t capacity);

  // Every direction back to ok, no events (Simulator::reset()).
  void clear();
  // Direction k back to ok without an event (Simulator::set_direction()).
  void forget(int k) { state_[k] = State::Ok; }

  // Reads the damped eigen-directions of `first` (the solve of the state at time t after
  // `step` steps) for the directions active in `held`, records the changes, and returns
  // the directions that resumed from released (bit k for direction k).
  unsigned update(const HeldDirections& held, const Data& first, double t, std::int64_t step, int link);

  const std::vector<DirectionEvent>& events() const { return events_; }
  std::int64_t not_kept() const { return not_kept_; }

 private:
  enum class State { Ok, Limited, Released };
  void record(const DirectionEvent& e);

  std::array<State, kNumDirections> state_{};
  std::array<double, kNumDirections> last_damped_{};  // t of the last solve that damped it
  std::vector<DirectionEvent> events_;
  std::size_t capacity_;
  std::int64_t not_kept_ = 0;
};

}  // namespace achd
