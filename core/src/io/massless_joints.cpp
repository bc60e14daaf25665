#include "massless_joints.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "achd/srdf.hpp"
#include "free_motions.hpp"
#include "link_inertia.hpp"

namespace achd {
namespace {

// The root of k's group in a union-find forest (`up`), halving the path on the way.
int group_of(std::vector<int>& up, int k) {
  while (up[k] != k) k = up[k] = up[up[k]];
  return k;
}

// How to load it otherwise: "it" or "them".
std::string way_out(const std::string& it) {
  return "the inertia option 'repair' (CLI --inertia repair) gives " + it + " a floor mass instead, 'strict' refuses " +
         it;
}

}  // namespace

MasslessLocks massless_joint_locks(const Model& model) {
  MasslessLocks out;
  const int n = model.num_rates(), first = model.free_joint_rates();
  // moves_mass[i]: body i or a body after it carries inertia (a body follows its parent,
  // so walking backwards sees every body's children before it).
  std::vector<bool> moves_mass(n, false);
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    if (!b.inertia.isZero(0) || b.rotor_inertia != 0) moves_mass[i] = true;
    if (moves_mass[i] && b.parent >= 0) moves_mass[b.parent] = true;
  }
  // The coupled groups: joints joined by couplings; each follower's coupling.
  std::vector<int> up(n), coupling_of(n, -1);
  std::iota(up.begin(), up.end(), 0);
  for (int c = 0; c < static_cast<int>(model.couplings.size()); ++c) {
    const JointCoupling& jc = model.couplings[c];
    coupling_of[jc.follower] = c;
    up[group_of(up, jc.follower)] = group_of(up, jc.leader);
  }
  std::vector<std::vector<int>> members(n);
  for (int k = first; k < n; ++k) members[group_of(up, k)].push_back(k);
  // Each member's position as a[k] * q_leader + b[k], composed down the couplings (set
  // per group, for its members only: a long massless chain costs O(n)).
  std::vector<double> a(n, 0), b(n, 0);
  std::vector<bool> known(n, false);
  // An uncoupled joint locked below another: the topmost such joint above it, whose one
  // warning counts and names the joints after it (top[k] = k at the top; -1: not locked).
  std::vector<int> top(n, -1), after(n, 0);
  std::vector<std::vector<std::string>> named_after(n);  // the first three
  std::vector<std::size_t> warning_of(n, 0);

  for (int g = first; g < n; ++g) {
    const std::vector<int>& group = members[g];
    if (group.empty() || std::any_of(group.begin(), group.end(), [&](int k) { return moves_mass[k]; })) continue;
    const auto leads = std::find_if(group.begin(), group.end(), [&](int k) { return coupling_of[k] < 0; });
    if (leads == group.end()) continue;  // a cycle of <mimic>s: no joint leads
    const int leader = *leads;
    for (int k : group) {
      known[k] = false;
      a[k] = b[k] = 0;
    }
    a[leader] = 1;
    known[leader] = true;
    for (std::size_t placed = 1; placed < group.size();) {
      for (int k : group) {
        if (known[k]) continue;
        const JointCoupling& c = model.couplings[coupling_of[k]];
        if (!known[c.leader]) continue;
        a[k] = c.multiplier * a[c.leader];
        b[k] = c.multiplier * b[c.leader] + c.offset;
        known[k] = true;
        ++placed;
      }
    }
    // The leader's values that keep every member within its limits: lower <= a q + b <= upper.
    double lo = model.bodies[leader].limits.lower, hi = model.bodies[leader].limits.upper;
    bool possible = true;
    for (int k : group) {
      if (k == leader) continue;
      const JointLimits& l = model.bodies[k].limits;
      if (a[k] > 0) {
        lo = std::max(lo, (l.lower - b[k]) / a[k]);
        hi = std::min(hi, (l.upper - b[k]) / a[k]);
      } else if (a[k] < 0) {
        lo = std::max(lo, (l.upper - b[k]) / a[k]);
        hi = std::min(hi, (l.lower - b[k]) / a[k]);
      } else {
        possible = possible && l.lower <= b[k] && b[k] <= l.upper;
      }
    }
    if (!possible || !(lo <= hi)) continue;  // (NaN from overflowing couplings fails too)
    const double value = default_joint_value(lo, hi);
    const std::string& name = model.bodies[leader].joint_name;
    out.values[name] = value;
    const std::string held = "locked at " + inertia_number(value) + " (as --lock " + name + "=" +
                             inertia_number(value) + " does)";
    if (group.size() == 1) {
      const int parent = model.bodies[leader].parent;
      if (parent >= first && top[parent] >= 0) {  // told in the warning of the joint above it
        top[leader] = top[parent];
        if (++after[top[leader]] <= 3) named_after[top[leader]].push_back(name);
        continue;
      }
      top[leader] = leader;
      warning_of[leader] = out.warnings.size();
      out.warnings.push_back("joint '" + name + "' moves nothing: its link and every link after it carry no mass, "
                             "so no torque moves it and its acceleration is undefined; " + held + "; " + way_out("it"));
      continue;
    }
    const std::size_t followers = group.size() - 1;
    out.warnings.push_back("joint '" + name + "' and the " + std::to_string(followers) + " joint" +
                           (followers > 1 ? "s" : "") + " coupled to it (<mimic>) move nothing: their links and "
                           "every link after them carry no mass, so no torque moves them and their accelerations are "
                           "undefined; '" + name + "' " + held + ", each joint coupled to it at its multiplier times "
                           "that plus its offset; " + way_out("them"));
  }
  // A massless subtree is one warning: its top joint's, naming the first joints after it.
  for (int k = first; k < n; ++k) {
    if (top[k] != k || !after[k]) continue;
    std::string listed;
    for (std::size_t i = 0; i < named_after[k].size(); ++i) listed += (i ? ", '" : "'") + named_after[k][i] + "'";
    if (after[k] > 3) listed += " and " + std::to_string(after[k] - 3) + " more";
    std::string& w = out.warnings[warning_of[k]];
    w += "; the " + std::to_string(after[k]) + " joint" + (after[k] > 1 ? "s" : "") + " after it (" + listed +
         ") " + (after[k] > 1 ? "move nothing either and are" : "moves nothing either and is") +
         " locked the same way, each at 0 or the middle of its limits when 0 is outside them";
  }
  return out;
}

void repair_joints_moving_nothing(Model& model) {
  double robot_mass = 0;
  for (const Body& b : model.bodies) robot_mass += b.inertia.topLeftCorner<3, 3>().trace() / 3;
  if (!std::isfinite(robot_mass)) return;  // validate() names the overflow
  const Matrix6 floor = floor_inertia(robot_mass);
  for (int round = 0; round < model.num_rates(); ++round) {
    const int i = joint_moving_nothing_at_checks(model);
    if (i < 0) return;
    Body& b = model.bodies[i];
    b.inertia += floor;
    model.warnings.push_back("joint '" + b.joint_name + "' moved nothing (no mass or inertia after it along its "
                             "motion): link '" + b.link_name + "' was given a floor mass of " +
                             inertia_number(floor(0, 0)) + " kg and a rotational inertia of " +
                             inertia_number(floor(3, 3)) + " kg m^2 at its joint");
  }
}

}  // namespace achd
