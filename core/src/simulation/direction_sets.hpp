#pragma once
// The Simulator's direction sets: per link, a held set (held_directions.hpp) at a point of
// the link, created on first use and kept (in the order of nu) until the simulator goes;
// the constraint blocks they make (one per set with active directions); the events of
// their directions (direction_events.hpp) and the directions each step re-anchors.
// Sized for every link at construction: no step allocates.
#include <string>
#include <vector>

#include "achd/case.hpp"
#include "achd/directions.hpp"
#include "achd/model.hpp"
#include "direction_events.hpp"
#include "tip_kinematics.hpp"

namespace achd {

class DirectionSets {
 public:
  explicit DirectionSets(const Model& model);

  const std::vector<LinkDirections>& sets() const { return sets_; }
  std::vector<LinkDirections>& sets() { return sets_; }
  // The set of link `link` (an achd::Error on a link index outside the model), nullptr if none.
  const LinkDirections* find(int link) const;
  // Its index in sets(), the set created (last, with no active direction) if there is none.
  int find_or_create(int link);
  // Active directions on all links together.
  int active_columns() const;

  // Every direction freed (their weights and points stay), records and events cleared.
  void release_all();
  // Direction k of set s set to `mode`: setpoint (Accelerate), target (Hold, linear), its
  // record and event state cleared.
  void set(int s, int k, DirectionMode mode, double setpoint, double target);

  // The constraint blocks: one per set with active directions, in set order (beta is
  // evaluate()'s); block_set()[b] is the set of blocks[b].
  void write_blocks(std::vector<ConstraintBlock>& blocks);
  const std::vector<int>& block_set() const { return block_set_; }
  // Per held angle (kNumDirections per set), 1 when it is integrated (a held angular
  // direction: its rate is e . w), else 0 (its rate and value stay 0).
  const std::vector<char>& integrated_angles() const { return integrated_; }

  // The largest |residual| of each held direction while it is followed (not released),
  // with the residuals of the state whose body poses and velocities are X0, v.
  void record_residuals(const Model& model, const std::vector<Transform>& X0, const std::vector<Vector6>& v,
                        const HeldAngles& angles);
  // After a step whose first solve is `first` (of the state at t after `step` steps): the
  // events of the directions, and whether some direction is to be re-anchored (anchored():
  // resumed ones, and held ones that yield to a driver).
  // w: the stabilisation frequency of the held directions (rad/s).
  bool update_events(const Model& model, const Data& first, double t, std::int64_t step, double w);
  std::vector<unsigned>& anchored() { return anchored_; }
  const DirectionEventLog& events() const { return events_; }

  // "held: z, rx" / "accelerated: ..." parts of a failed step's message ("" if none).
  std::string held_text(const Model& model) const;
  std::string accelerated_text(const Model& model) const;
  // True when some set accelerates a direction (DirectionMode::Accelerate).
  bool any_accelerated() const;

 private:
  std::vector<LinkDirections> sets_;
  std::vector<int> block_set_;
  std::vector<char> integrated_;
  std::vector<unsigned> anchored_;  // per set, the directions a step re-anchors
  DirectionEventLog events_;
};

}  // namespace achd
