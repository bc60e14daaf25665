#pragma once
// Joints that move nothing for lack of mass (a gripper's massless fingers, a hand whose
// links carry no inertia): which the default load holds, at what value, and the warning
// that says so; and the floor masses the repair policy gives them instead.
#include <map>
#include <string>
#include <vector>

#include "achd/model.hpp"

namespace achd {

struct MasslessLocks {
  std::map<std::string, double> values;  // joint name -> position held (rad or m)
  std::vector<std::string> warnings;     // one line per joint, or per coupled group
};

// The movable joints of `model` (a URDF as walked, before validate()) whose own body and
// every body after it carry no inertia at all (no mass, no rotational inertia, no rotor
// inertia): no torque moves anything, so their accelerations are undefined (D = S^T IA S
// = 0), and held they change no dynamics, only where their massless links are drawn.
// - A joint of its own is held at 0, or the middle of its limits when 0 is outside them
//   (default_pose's rule).
// - Joints coupled by <mimic> (Model::couplings) are held as a group, and only when every
//   joint of the group has nothing of mass after it: its leader (the one that follows
//   none) is held at the value that rule gives on the leader's limits narrowed to those
//   that keep each follower within its own, and the followers follow it (the loader holds
//   a follower at multiplier * leader + offset). A group some joint of which moves mass,
//   one without a leader (a cycle of <mimic>s), or one no leader value keeps within every
//   follower's limits is left as it is (validate() refuses it, naming it).
// The free joint of a floating base is never held.
MasslessLocks massless_joint_locks(const Model& model);

// Under the repair policy, each body whose joint moves nothing (no mass or inertia after it
// along its motion: a massless finger) gets floor_inertia, until every joint moves
// something; each repair is a warning naming the joint and its link.
void repair_joints_moving_nothing(Model& model);

}  // namespace achd
