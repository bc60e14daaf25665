// The simulator's joint PD controller (JointControl in simulator.hpp): at every solve
//   ff_i = ff_torques_i + kp_i (q_target,i - q_i) - kd_i qd_i + tau_hold,i
// for each joint i (q at its position index), so that the control torques count in
// joint_torques like any feed-forward torque. The implicit Euler step treats kd as joint
// damping (implicit_euler.cpp), which keeps stiff gains stable at large dt. Gains from a
// frequency and a damping ratio, kp_i = m_i (2 pi f)^2 and kd_i = 2 zeta m_i (2 pi f)
// with m_i the inertia joint i moves while the held links stay still
// (anchored_inertia.hpp), and tau_hold (hold_torques.hpp), are computed at the target here
// and again whenever the held set changes (update_blocks).
#include <cmath>
#include <cstdio>
#include <string>

#include "achd/error.hpp"
#include "achd/simulator.hpp"
#include "anchored_inertia.hpp"
#include "direction_sets.hpp"
#include "hold_torques.hpp"
#include "integrators.hpp"
#include "message_number.hpp"

namespace achd {
namespace {

// The frequency and damping ratio, checked.
void check_frequency(const JointControl& c) {
  if (!std::isfinite(c.frequency) || !(c.frequency > 0))
    throw Error("joint control: frequency must be finite and > 0 (Hz), got " + message_number(c.frequency));
  if (!std::isfinite(c.damping_ratio) || !(c.damping_ratio >= 0))
    throw Error("joint control: damping_ratio must be finite and >= 0, got " + message_number(c.damping_ratio));
}

}  // namespace

void Simulator::set_joint_control(const JointControl& given) {
  const int n = model_.num_rates(), np = model_.num_positions();
  if (given.target.size() != np)
    throw Error("joint control: target: expected " + std::to_string(np) + " values (a pose as q), got " +
                std::to_string(given.target.size()));
  for (int i = 0; i < np; ++i)
    if (!std::isfinite(given.target[i]))
      throw Error("joint control: target[" + std::to_string(i) + "] is not finite");
  JointControl c = given;
  const bool by_frequency = c.kp.size() == 0 && c.kd.size() == 0;
  if (by_frequency) {
    check_frequency(c);
    c.kp = c.kd = Eigen::VectorXd::Zero(n);  // set by update_control_terms()
  } else if (c.frequency != 0 || c.damping_ratio != 0) {
    throw Error("joint control: give kp and kd, or frequency and damping_ratio, not both");
  }
  for (const auto& [gains, field] : {std::pair<const Eigen::VectorXd*, const char*>{&c.kp, "kp"}, {&c.kd, "kd"}})
    if (gains->size() != n)
      throw Error(std::string("joint control: ") + field + ": expected " + std::to_string(n) +
                  " values (one per joint), got " + std::to_string(gains->size()));
  for (int i = 0; i < n; ++i) {
    const std::string joint = i < model_.free_joint_rates() ? model_.root_name : model_.bodies[i].joint_name;
    for (const auto& [g, field] : {std::pair<double, const char*>{c.kp[i], "kp"}, {c.kd[i], "kd"}}) {
      if (!(g >= 0) || !std::isfinite(g))
        throw Error(std::string("joint control: ") + field + " of joint '" + joint + "' must be finite and >= 0, got " +
                    message_number(g));
      if (i < model_.free_joint_rates() && g != 0)
        throw Error(std::string("joint control: ") + field + "[" + std::to_string(i) + "] of joint '" + joint +
                    "' (the floating base's free joint, not actuated) must be 0, got " + message_number(g));
    }
  }
  control_ = c;
  control_on_ = true;
  integrator_->clear_stiffness();  // the stiffness the detection found may have been the old gains'

  update_control_terms();
}

void Simulator::clear_joint_control() {
  control_on_ = false;
  integrator_->clear_stiffness();
}

void Simulator::update_control_terms() {
  if (control_on_ && control_.frequency > 0) {
    // kp_i = m_i (2 pi f)^2, kd_i = 2 zeta m_i (2 pi f), m_i the inertia joint i moves with
    // the held links still (anchored_inertia.hpp; M_ii when nothing is held)
    std::vector<int> anchors;
    for (const LinkDirections& set : directions_->sets())
      if (set.held.count()) anchors.push_back(model_.links[set.link].body);
    const Eigen::VectorXd m = anchored_joint_inertias(model_, control_.target, anchors);
    const double w = 2 * 3.14159265358979323846 * control_.frequency;  // rad/s
    control_.kp = m * (w * w);
    control_.kd = m * (2 * control_.damping_ratio * w);
    for (int i = 0; i < m.size(); ++i)
      if (!std::isfinite(control_.kp[i]) || !std::isfinite(control_.kd[i]))
        throw Error("joint control: the gains of joint '" + model_.bodies[i].joint_name + "' at frequency " +
                    message_number(control_.frequency) + " Hz are not finite");
  }
  if (!control_on_ || !control_.hold) {
    hold_torques_.setZero(model_.num_rates());
    return;
  }
  // (the gravity and solver options a step uses: effects with the gravity bit off mean none)
  Options solver = options_.solver;
  solver.effects = options_.effects;
  solver.convention = Convention::Physical;
  hold_torques_ = hold_torques(model_, control_.target, options_.gravity, f_ext, case_.constraints, solver);
  for (int i = 0; i < hold_torques_.size(); ++i)
    if (!std::isfinite(hold_torques_[i]))
      throw Error("joint control: the hold torque of joint '" + model_.bodies[i].joint_name +
                  "' at the target is not finite");
}

void Simulator::apply_joint_control(const Eigen::VectorXd& q_at, const Eigen::VectorXd& qd_at) {
  if (!control_on_) return;  // step() set case_.ff_torques = ff_torques
  if (ff_torques.size()) case_.ff_torques = ff_torques;
  else case_.ff_torques.setZero(model_.num_rates());
  for (int i = 0; i < model_.num_rates(); ++i) {
    const int p = model_.position_index(i);
    // (a linearly implicit step of h takes the position term at q + h qd: control_lead_)
    const double error = control_lead_ == 0 ? control_.target[p] - q_at[p]
                                            : control_.target[p] - (q_at[p] + control_lead_ * qd_at[i]);
    case_.ff_torques[i] += control_.kp[i] * error - control_.kd[i] * qd_at[i] + hold_torques_[i];
  }
}

}  // namespace achd
