// Joint limits as inelastic stops that the held directions respect (LimitPolicy::Clamp),
// and a prescribed joint's jump onto its trajectory by the same impact solves: the
// Simulator's members for them (the hooks in simulator.cpp and prescribe() call them).
//
// Impact. A joint that reached its limit in a step (q_i at or past it, not yet resting on
// it) is put back on the limit and, when it moves into the limit, stopped by an
// inelastic impact, a velocity jump
//   dqd = M^-1 (e_i lambda + J^T alpha mu)  with  qd_i + dqd_i = 0  and  alpha^T J dqd = 0
// for the held columns alpha (the held directions' velocities do not change; accelerated
// directions are free during the impact). That is one hybrid solve at the same q with
// only the constraints and rotor inertia on (no gravity, velocity products, passive
// terms, ff_torques or f_ext): joint i prescribed with qdd_given = -qd_i, the joints already
// resting on a stop with 0, the held columns with beta = 0; its qdd is dqd. Several joints
// reaching their limits in one step stop together. The position goes back on the limit
// the same way: dq with dq_i = limit_i - q_i and the held quantities (the tip's position
// along a held linear direction, its rotation about a held angular one) unchanged, by the
// same solve with beta the held quantities' change, repeated (Newton) until they are
// unchanged to round-off.
// Rest. A joint on its stop has its acceleration prescribed as 0 in every solve of a
// step (Case::prescribed), so the held directions are solved with the joints that remain
// free, and its q and qd stay exactly the limit and 0.
// Release. Before each step, one solve at the step's state (the step's first solve) gives
// the torque the stop exerts, prescribed_torques_i - ff_i. When it would have to pull the
// joint into the limit (positive on an upper stop, negative on a lower one), the joint is
// free again: the acceleration it would have, free, points out of the limit.
// Prescribed joints (Simulator::prescribe) follow their trajectories through their limits:
// they are never stopped, and in the impact solves they are prescribed with dq = dqd = 0,
// so that an impact of another joint leaves their motion as given.
// Onto a trajectory. Simulator::prescribe sets its joint's q and qd to the trajectory's;
// with held directions, loops or coupled joints, the same two solves then move the free
// joints back (jump_onto_trajectory): the position projection and the impulse with every
// prescribed joint (this one included) and every joint resting on a stop kept (dq = dqd =
// 0), beta the held quantities' and velocities' change since before the jump, so that
// the held directions keep where and how fast they were, the loops stay closed and a
// coupled joint's followers follow it. A jump the held directions do not see changes no
// other joint. Without them (or with
// constraints off) the joint's q and qd are simply set.
#include <algorithm>
#include <cmath>
#include <string>

#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"
#include "achd/kinematics.hpp"
#include "achd/simulator.hpp"
#include "direction_sets.hpp"
#include "held_directions.hpp"
#include "integrators.hpp"
#include "joint_couplings.hpp"
#include "loop_closure.hpp"
#include "tip_kinematics.hpp"

namespace achd {
namespace {

// +1 when q is at or past the upper limit, -1 at or past the lower one, else 0.
int limit_side(const JointLimits& l, double q) { return q >= l.upper ? 1 : q <= l.lower ? -1 : 0; }
double limit_at(const JointLimits& l, int side) { return side > 0 ? l.upper : l.lower; }

// Newton iterations of the position projection; the first leaves the held quantities
// changed by O(dq^2), each next squares that. A limit's dq is one step's overshoot; a jump
// onto a trajectory may be tenths of a radian, and takes more to reach round-off (the
// LWR's base by 0.2 rad, its tip held in 6D: 3e-12 m left after 4).
constexpr int kProjectionIterations = 4, kJumpIterations = 10;

// The held quantity of a held direction k at the tip, measured from `before`: the tip
// origin's displacement along a linear direction, the rotation about an angular one.
double held_change(int k, const Transform& before, const Transform& now) {
  const Vector3 e = direction_axis(k);
  if (is_linear_direction(k)) return e.dot(now.p - before.p);
  const Eigen::AngleAxisd turn(now.R * before.R.transpose());
  return e.dot(turn.axis() * turn.angle());
}

}  // namespace

int Simulator::limit_stop(int joint) const {
  if (joint < 0 || joint >= model_.num_rates())
    throw Error("limit_stop: joint index " + std::to_string(joint) + " is not in 0.." +
                std::to_string(model_.num_rates() - 1));
  return limit_stop_[joint];
}

void Simulator::update_limit_stops(double w_n, double zeta) {
  const int n = model_.num_rates();
  bool resting = false;
  for (int i = 0; i < n; ++i) {
    // A stop the caller moved the joint off (by setting q or qd, or the policy) is gone.
    const bool on_it = limit_stop_[i] && options_.limits == LimitPolicy::Clamp && qd[i] == 0 &&
                       q[model_.position_index(i)] == limit_at(model_.bodies[i].limits, limit_stop_[i]);
    if (!on_it) limit_stop_[i] = 0;
    case_.prescribed[i] = limit_stop_[i] != 0 || moving_[i];
    resting = resting || on_it;
  }
  if (!resting) return;
  // The step's first solve, with the stops' joints prescribed: the torque each stop exerts.
  integrator_->stage = 0;
  evaluate(*this, w_n, zeta, limit_data_, limit_angle_rate_);
  for (int i = 0; i < n; ++i) {
    if (!limit_stop_[i]) continue;
    const double ff = case_.ff_torques.size() ? case_.ff_torques[i] : 0.0;
    const double stop_torque = limit_data_.prescribed_torques[i] - ff;
    if (limit_stop_[i] * stop_torque > 0) {  // it would have to pull the joint into the limit
      limit_stop_[i] = 0;
      case_.prescribed[i] = false;
    }
  }
}

// One solve of the impact case (impact_case_ holds q, the prescribed joints and beta),
// with only the constraints and rotor inertia on; `what` names it in an error, with the
// joint put on its trajectory (`joint` >= 0) or else the joints at their limits.
void Simulator::solve_impact(const char* what, int joint) {
  Options o = solver_;
  o.effects = options_.effects & (kConstraints | kRotorInertia);
  o.convention = Convention::Physical;
  try {
    hybrid_dynamics(model_, limit_data_, impact_case_, o);
  } catch (const Error& e) {
    if (joint >= 0)
      throw Error(std::string("the ") + what + " putting joint '" + model_.bodies[joint].joint_name +
                  "' on its trajectory failed: " + e.what());
    std::string joints;
    for (int i = 0; i < model_.num_rates(); ++i)
      if (limit_reached_[i])
        joints += (joints.empty() ? "'" : ", '") + model_.bodies[i].joint_name + "'";
    throw Error(std::string("the ") + what + " of joint " + joints + " at its limit failed: " + e.what());
  }
}

void Simulator::set_impact_blocks() {
  impact_case_.constraints.clear();
  for (const LinkDirections& set : directions_->sets()) {
    int nc = 0;
    for (int k = 0; k < kNumDirections; ++k) nc += set.held.mode[k] == DirectionMode::Hold;
    if (!nc) continue;
    ConstraintBlock& b = impact_case_.constraints.emplace_back();
    b.link = set.link;
    b.point = set.point;
    b.alpha.setZero(6, nc);
    b.beta.setZero(nc);
    for (int k = 0, col = 0; k < kNumDirections; ++k)
      if (set.held.mode[k] == DirectionMode::Hold) b.alpha(k, col++) = 1;  // [e; 0] or [0; e]: row k
  }
}

double Simulator::held_changes(bool velocity) {
  const std::vector<LinkDirections>& sets = directions_->sets();
  size_t b = 0;
  double off = 0;
  for (size_t s = 0; s < sets.size(); ++s) {
    const LinkDirections& set = sets[s];
    if (b >= impact_case_.constraints.size() || impact_case_.constraints[b].link != set.link) continue;
    const TipState now = link_state(model_, X0_, v_, set.link, set.point);
    const TipState& before = impact_points_[s];
    ConstraintVector& beta = impact_case_.constraints[b++].beta;
    for (int k = 0, col = 0; k < kNumDirections; ++k) {
      if (set.held.mode[k] != DirectionMode::Hold) continue;
      const Vector3 e = direction_axis(k);
      beta[col] = !velocity ? -held_change(k, before.pose, now.pose)
                  : is_linear_direction(k) ? e.dot(before.v - now.v) : e.dot(before.w - now.w);
      off = std::max(off, std::abs(beta[col++]));
    }
  }
  return off;
}

double Simulator::loop_changes(bool velocity) {
  double off = 0, e[kNumDirections], g[kNumDirections];
  int column = 0;
  for (const LoopJoint& loop : model_.loops) {
    loop_errors(model_, loop, X0_, v_, e, g);
    for (int j = 0; j < loop.num_columns(); ++j) {
      impact_case_.loop_beta[column++] = -(velocity ? g[j] : e[j]);
      off = std::max(off, std::abs(velocity ? g[j] : e[j]));
    }
  }
  return off;
}

double Simulator::coupling_changes(bool velocity) {
  double off = 0;
  for (size_t j = 0; j < model_.couplings.size(); ++j) {
    const JointCoupling& c = model_.couplings[j];
    const double e = velocity ? coupling_rate_error(model_, c, qd) : coupling_position_error(model_, c, q);
    impact_case_.coupling_beta[j] = -e;
    off = std::max(off, std::abs(e));
  }
  return off;
}

void Simulator::record_impact_points() {
  const std::vector<LinkDirections>& sets = directions_->sets();
  body_motion(model_, q, qd, X0_, r_, v_);
  for (size_t s = 0; s < sets.size(); ++s)
    impact_points_[s] = link_state(model_, X0_, v_, sets[s].link, sets[s].point);
}

void Simulator::project_positions(int joint, bool moved) {
  const int n = model_.num_rates();
  body_motion(model_, q, qd, X0_, r_, v_);
  for (int it = 0; it < (moved ? kJumpIterations : kProjectionIterations); ++it) {
    double off = 0;
    for (int i = 0; i < n; ++i) {
      const double to_target = impact_case_.prescribed[i] ? impact_target_[i] - q[model_.position_index(i)] : 0.0;
      impact_case_.qdd_given[i] = to_target;
      off = std::max(off, std::abs(to_target));
    }
    // The held quantities and loops count from the first iteration when q has already moved.
    if (it > 0 || moved) off = std::max(off, held_changes(false));
    const double loops_open = loop_changes(false);  // the loops closed again
    if (it > 0 || moved) off = std::max(off, loops_open);
    if (moved) off = std::max(off, coupling_changes(false));  // a moved leader's followers too
    if (off == 0) break;
    impact_case_.q = q;
    solve_impact("position projection", joint);
    integrate(model_, q, limit_data_.qdd, 1.0, q);  // the solve's qdd is the displacement
    for (int i = 0; i < n; ++i)
      if (impact_case_.prescribed[i]) q[model_.position_index(i)] = impact_target_[i];
    body_motion(model_, q, qd, X0_, r_, v_);
  }
}

void Simulator::project_velocities(const char* what, int joint) {
  held_changes(true);
  loop_changes(true);  // and the loops their relative velocity 0
  impact_case_.q = q;
  solve_impact(what, joint);
  qd += limit_data_.qdd;
}

void Simulator::stop_at_limits() {
  if (options_.limits != LimitPolicy::Clamp) return;
  if (!q.allFinite() || !qd.allFinite()) return;  // step() names the joint
  const int n = model_.num_rates();
  bool reached = false;
  for (int i = 0; i < n; ++i) {
    const JointLimits& l = model_.bodies[i].limits;
    if (limit_stop_[i]) {
      // Resting: the step's prescribed qdd = 0 kept it there; these are exact.
      q[model_.position_index(i)] = limit_at(l, limit_stop_[i]);
      qd[i] = 0;
      limit_reached_[i] = 0;
      continue;
    }
    // A prescribed joint follows its trajectory through its limits: never stopped.
    limit_reached_[i] = moving_[i] ? 0 : static_cast<signed char>(limit_side(l, q[model_.position_index(i)]));
    reached = reached || limit_reached_[i];
  }
  if (!reached) return;
  integrator_->stage = -1;  // a failure here is no integrator stage's
  set_impact_blocks();
  impact_case_.coupling_beta.setZero();  // a stop leaves the couplings' errors as they are
  // Position: back on the limit with the held quantities unchanged (and the loops closed);
  // a prescribed joint keeps its trajectory through an impact: dq_i = dqd_i = 0.
  for (int i = 0; i < n; ++i) {
    impact_case_.prescribed[i] = limit_stop_[i] || limit_reached_[i] || moving_[i];
    impact_target_[i] = limit_reached_[i] ? limit_at(model_.bodies[i].limits, limit_reached_[i])
                                          : q[model_.position_index(i)];
  }
  record_impact_points();
  project_positions(-1, false);

  // Velocity: the inelastic impact of the joints moving into their limits (a joint past
  // its limit but already moving back stays free), which also gives the held directions
  // back the velocities they had before the position went back (J changed with q).
  for (int i = 0; i < n; ++i) {
    const bool into = limit_reached_[i] && limit_reached_[i] * qd[i] >= 0;
    if (limit_reached_[i] && !into) limit_reached_[i] = 0;
    impact_case_.prescribed[i] = limit_stop_[i] || into || moving_[i];
    impact_case_.qdd_given[i] = into ? -qd[i] : 0.0;
  }
  project_velocities("impact", -1);
  for (int i = 0; i < n; ++i)
    if (limit_reached_[i]) {
      qd[i] = 0;
      limit_stop_[i] = limit_reached_[i];
      case_.prescribed[i] = true;
    }
}

void Simulator::jump_onto_trajectory(int joint, double q_at, double qd_at) {
  const int n = model_.num_rates();
  set_impact_blocks();
  const bool respected = (options_.effects & kConstraints) &&
                         (!impact_case_.constraints.empty() || !model_.loops.empty() || !model_.couplings.empty());
  if (!respected) {
    q[model_.position_index(joint)] = q_at;
    qd[joint] = qd_at;
    return;
  }
  const Eigen::VectorXd q_before = q, qd_before = qd;
  try {
    // The held quantities and velocities before the jump; then the joint on its trajectory
    // and the free joints moved back to them (the prescribed joints and those resting on
    // a stop kept): the least motion, in the joint-space inertia's metric, that does.
    record_impact_points();
    q[model_.position_index(joint)] = q_at;
    qd[joint] = qd_at;
    for (int i = 0; i < n; ++i) {
      impact_case_.prescribed[i] = i == joint || limit_stop_[i] || moving_[i];
      impact_target_[i] = q[model_.position_index(i)];
    }
    project_positions(joint, true);
    impact_case_.qdd_given.setZero();
    coupling_changes(true);
    project_velocities("impulse", joint);
  } catch (...) {
    q = q_before;
    qd = qd_before;
    throw;
  }
}

}  // namespace achd
