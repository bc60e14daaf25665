// The Simulator's x' = f(x): each link's block (alpha set with its directions) gets its
// beta at the state, the prescribed joints their trajectories' accelerations, the
// couplings their drift's decay and the joints the PD torques; one hybrid_dynamics solve
// gives qdd, and the held angles' rates are e . w_link. Also the prescribed joint motion
// the solves follow.
#include <algorithm>
#include <cmath>

#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"
#include "achd/kinematics.hpp"
#include "achd/simulator.hpp"
#include "direction_sets.hpp"
#include "held_directions.hpp"
#include "integrators.hpp"
#include "joint_couplings.hpp"
#include "loop_closure.hpp"
#include "message_number.hpp"
#include "simulator_checks.hpp"
#include "tip_kinematics.hpp"

namespace achd {

void Simulator::evaluate(const SimulationState& x, double w_n, double zeta, Data& out, HeldAngles& angle_rates) {
  if (!x.q.allFinite() || !x.qd.allFinite())
    throw Error("the stage's state is not finite (" + non_finite_joint(model_, x.q, x.qd) + ")");
  // The poses straight into the solve's Data, which takes them (Data::Workspace::poses_given);
  // the links' velocities only where a held direction's or a loop's beta reads them (the
  // 200-joint chain falling free: 2.2% of its instructions).
  if (case_.constraints.empty() && model_.loops.empty()) body_poses(model_, x.q, out.X0, out.r);
  else body_motion(model_, x.q, x.qd, out.X0, out.r, v_);
  const std::vector<LinkDirections>& sets = directions_->sets();
  angle_rates.head(held_angles.size()).setZero();  // sets with no active direction have none
  for (size_t b = 0; b < case_.constraints.size(); ++b) {
    const int s = directions_->block_set()[b];
    const LinkDirections& set = sets[s];
    const TipState at = link_state(model_, out.X0, v_, set.link, set.point);
    const double* angle = x.held_angles.data() + s * kNumDirections;
    ConstraintVector& beta = case_.constraints[b].beta;
    direction_targets(set.held, at, angle, w_n, zeta,
                      options_.effects & kVelocityProducts, beta);
    // beta is the acceleration the solver enforces along each held or accelerated
    // direction, in index order (direction_columns).
    for (int k = 0, column = 0; k < kNumDirections; ++k) {
      if (!set.held.active(k)) continue;
      if (!std::isfinite(beta[column++]))
        throw Error("the acceleration to enforce along " + direction_label(model_, set.link, k) +
                    " is not finite (beta = " + message_number(beta[column - 1]) + "; " +
                    (model_.has_tip() && set.link == model_.num_links() - 1 ? "tip" : "point") + " speed " +
                    message_number(at.v.norm()) + " m/s, " + message_number(at.w.norm()) + " rad/s)");
    }
    for (int k = 0; k < kNumDirections; ++k)
      angle_rates[s * kNumDirections + k] = set.held.mode[k] == DirectionMode::Hold && !is_linear_direction(k)
                                                ? direction_axis(k).dot(at.w) : 0.0;
  }
  // Loop joints: each closure error decays as a held direction's does (loop_closure.hpp).
  if (!model_.loops.empty()) {
    loop_targets(model_, out.X0, v_, w_n, zeta, options_.effects & kVelocityProducts,
                 case_.loop_beta);
    for (int j = 0; j < case_.loop_beta.size(); ++j)
      if (!std::isfinite(case_.loop_beta[j])) throw Error(loop_beta_not_finite(model_, j, case_.loop_beta[j]));
  }
  for (int i = 0; i < model_.num_rates(); ++i)
    if (moving_[i]) case_.qdd_given[i] = sample(motions_[i], x.t).qdd;
  // Coupled joints: e = q_f - k q_l - c decays as the held directions' errors do,
  //   e'' = -2 zeta w e' - w^2 e.
  for (size_t j = 0; j < model_.couplings.size(); ++j) {
    const JointCoupling& cj = model_.couplings[j];
    case_.coupling_beta[j] = -2 * zeta * w_n * coupling_rate_error(model_, cj, x.qd) -
                             w_n * w_n * coupling_position_error(model_, cj, x.q);
  }
  apply_joint_control(x.q, x.qd);
  case_.q = x.q;
  case_.qd = x.qd;
  // A hold asks for no motion along its direction: where the joints' efforts allow it, the
  // exact solve keeps it next to a singularity. A pushed direction asks the arm to move,
  // and into the edge of its workspace: there variable_damping's region decides.
  solver_.exact_within_efforts = options_.solver.exact_within_efforts && !directions_->any_accelerated();
  out.workspace.poses_given = true;  // (set last: a throw above leaves it clear)
  hybrid_dynamics(model_, out, case_, solver_);
  // The columns that give way to the held ones (Options::gives_way): the first solve of a
  // step that chooses them fixes them until the step ends (check_step resets them), so
  // that the step's right-hand side does not jump where the damped direction's largest
  // component passes from one column to another.
  if (!solver_.gives_way) solver_.gives_way = out.workspace.gave_way;
}

// The solve of a linearly implicit step of h (integrators/extrapolated_implicit_euler.cpp):
// with h c_i + h^2 kp_i added to joint i's axial inertia (Case::extra_inertia, swapped in
// and out: no allocation) and the PD torque kp (q* - q - h qd) - kd qd.
void Simulator::evaluate_implicit(const SimulationState& x, double h, double w_n, double zeta, Data& out,
                                  HeldAngles& angle_rates) {
  IntegratorWorkspace& ws = *integrator_;
  const PassiveTerms passive{solver_.effects, solver_.friction_velocity, control_on_ ? &control_.kd : nullptr,
                             control_on_ ? &control_.kp : nullptr};
  implicit_inertia(model_, passive, x.qd, h, ws.extra_inertia);
  case_.extra_inertia.swap(ws.extra_inertia);
  control_lead_ = h;
  const auto restore = [&] {
    case_.extra_inertia.swap(ws.extra_inertia);
    control_lead_ = 0;
  };
  try {
    evaluate(x, w_n, zeta, out, angle_rates);
  } catch (...) {
    restore();
    throw;
  }
  restore();
}

// e . w_link of each held angular direction at (q, qd), 0 for the other directions.
void Simulator::held_angle_rates(const SimulationState& x, HeldAngles& angle_rates) {
  body_motion(model_, x.q, x.qd, X0_, r_, v_);
  const std::vector<LinkDirections>& sets = directions_->sets();
  for (size_t s = 0; s < sets.size(); ++s) {
    const LinkDirections& set = sets[s];
    const Vector3 w = link_state(model_, X0_, v_, set.link, set.point).w;
    for (int k = 0; k < kNumDirections; ++k)
      angle_rates[s * kNumDirections + k] =
          set.held.mode[k] == DirectionMode::Hold && !is_linear_direction(k) ? direction_axis(k).dot(w) : 0.0;
  }
}

double Simulator::loop_error(int loop) const {
  check_loop(model_, loop, "loop_error");
  const ChainMotion& m = thread_chain_motion(model_, q, qd);
  return achd::loop_error(model_, model_.loops[loop], m.X0, m.v);
}

double Simulator::loop_drift(int loop) const {
  if (directions_->events().loop_released(loop)) return loop_drift_[loop];  // not enforced now
  return std::max(loop_error(loop), loop_drift_[loop]);
}

void Simulator::check_joint(int joint, const char* what) const {
  if (joint < 0 || joint >= model_.num_rates())
    throw Error(std::string(what) + ": joint index " + std::to_string(joint) + " is not in 0.." +
                std::to_string(model_.num_rates() - 1));
}

void Simulator::prescribe(int joint, const JointMotion& motion) {
  check_joint(joint, "prescribe");
  if (joint < model_.free_joint_rates())
    throw Error("prescribe: joint '" + model_.root_name + "' is the floating base's free joint; only its joints "
                "after it take a motion");
  validate(motion, "joint '" + model_.bodies[joint].joint_name + "': ");
  if (!std::isfinite(t)) throw Error("prescribe: t is not finite");
  const JointSample at = sample(motion, t);
  if (!std::isfinite(at.q) || !std::isfinite(at.qd) || !std::isfinite(at.qdd))
    throw Error("prescribe: joint '" + model_.bodies[joint].joint_name + "': its motion is not finite at t = " +
                std::to_string(t));
  jump_onto_trajectory(joint, at.q, at.qd);  // throws with nothing changed
  motions_[joint] = motion;
  moving_[joint] = 1;
  case_.prescribed[joint] = true;
  limit_stop_[joint] = 0;  // its motion is given: no stop holds it
  case_.qdd_given[joint] = at.qdd;
}

void Simulator::release(int joint) {
  check_joint(joint, "release");
  moving_[joint] = 0;
  case_.prescribed[joint] = false;
  case_.qdd_given[joint] = 0;  // a limit stop prescribes 0
}

bool Simulator::prescribed(int joint) const {
  check_joint(joint, "prescribed");
  return moving_[joint] != 0;
}

const JointMotion& Simulator::motion(int joint) const {
  check_joint(joint, "motion");
  if (!moving_[joint]) throw Error("motion: joint '" + model_.bodies[joint].joint_name + "' is not prescribed");
  return motions_[joint];
}

void Simulator::follow_trajectories(double t_at) {
  for (int i = 0; i < model_.num_rates(); ++i) {
    if (!moving_[i]) continue;
    const JointSample at = sample(motions_[i], t_at);
    q[model_.position_index(i)] = at.q;
    qd[i] = at.qd;
  }
}

}  // namespace achd
