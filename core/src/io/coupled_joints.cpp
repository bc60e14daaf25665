#include "coupled_joints.hpp"

#include <string>
#include <vector>

#include "achd/error.hpp"
#include "free_motions.hpp"

namespace achd {

// After validate() refused the model: a coupled joint (<mimic>) that moves nothing. The
// message validate() gives names the one joint and offers to lock it, which for a coupled
// hand only moves the error to the next finger. This names the coupled group instead (the
// joints joined to it by couplings, its leader the one that follows none) and which case
// it is:
// - no joint of the group moves any mass (every body after any of them has no inertia at
//   all: a massless hand, its leader's link included): the dynamics do not define the
//   group's motion (any acceleration at zero torque, none at any other), whatever the
//   couplings; held (its leader locked, the followers with it) or given floor masses, it
//   loads;
// - the group moves something but this joint moves nothing of its own: the coupled solve
//   (joint_couplings.hpp) solves the uncoupled tree, which needs every joint to move
//   something, so it is refused too, saying so.
void check_coupled_joints_move_something(const Model& model) {
  if (model.couplings.empty()) return;
  const int i = joint_moving_nothing_at_checks(model);
  if (i < 0) return;
  const int n = model.num_rates();
  std::vector<bool> member(n, false), follower(n, false);
  member[i] = true;
  for (bool grew = true; grew;) {
    grew = false;
    for (const JointCoupling& c : model.couplings) {
      if (c.follower < 0 || c.follower >= n || c.leader < 0 || c.leader >= n) return;  // validate() names it
      follower[c.follower] = true;
      if (member[c.follower] == member[c.leader]) continue;
      member[c.follower] = true;
      member[c.leader] = true;
      grew = true;
    }
  }
  int size = 0, leader = -1;
  for (int k = 0; k < n; ++k)
    if (member[k]) {
      ++size;
      if (leader < 0 && !follower[k]) leader = k;
    }
  if (size < 2) return;  // not coupled: validate()'s message
  if (leader < 0) leader = i;  // (a cycle of <mimic>s: no joint leads)
  // Every body after a member (bodies come after their parents) without any inertia.
  std::vector<bool> after(n, false);
  bool massless = true;
  for (int k = 0; k < n; ++k) {
    const Body& b = model.bodies[k];
    after[k] = member[k] || (b.parent >= 0 && after[b.parent]);
    if (after[k] && (!b.inertia.isZero(0) || b.rotor_inertia != 0)) massless = false;
  }
  const std::string joint = "joint '" + model.bodies[i].joint_name + "'";
  const std::string lead = model.bodies[leader].joint_name;
  const std::string group = "joint '" + lead + "' and the " + std::to_string(size - 1) + " joint" +
                            (size > 2 ? "s" : "") + " coupled to it (<mimic>)";
  const std::string way_out =
      "a URDF loads with the inertia option 'repair' (CLI --inertia repair), which gives them a floor mass, or "
      "with the group held (--lock " + lead + "=VALUE holds the joints that follow it too)";
  if (massless)
    throw Error(joint + " moves nothing, nor does any joint coupled with it: " + group +
                " have no mass or inertia after them, so the dynamics do not define their motion (the couplings "
                "cannot give it mass); " + way_out);
  throw Error(joint + " moves nothing: the links after it have no mass or inertia along its motion, or later "
              "joints take that motion up (D = S^T IA S = 0); it is one of " + group +
              ", which move something, but the coupled solve still needs each coupled joint to move something of "
              "its own; " + way_out);
}

}  // namespace achd
