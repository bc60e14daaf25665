// The simulator's joint PD controller (JointControl in simulator.hpp): at every solve
//   ff_i = ff_torques_i + kp_i (q_target,i - q_i) - kd_i qd_i
// for each joint i (q at its position index), so that the control torques count in
// joint_torques like any feed-forward torque. The implicit Euler step treats kd as joint
// damping (implicit_euler.cpp), which keeps stiff gains stable at large dt.
#include <cmath>
#include <cstdio>
#include <string>

#include "achd/error.hpp"
#include "achd/simulator.hpp"
#include "message_number.hpp"

namespace achd {
void Simulator::set_joint_control(const JointControl& c) {
  const int n = model_.num_joints(), np = model_.num_positions();
  if (c.target.size() != np)
    throw Error("joint control: target: expected " + std::to_string(np) + " values (a pose as q), got " +
                std::to_string(c.target.size()));
  for (const auto& [gains, field] : {std::pair<const Eigen::VectorXd*, const char*>{&c.kp, "kp"}, {&c.kd, "kd"}})
    if (gains->size() != n)
      throw Error(std::string("joint control: ") + field + ": expected " + std::to_string(n) +
                  " values (one per joint), got " + std::to_string(gains->size()));
  for (int i = 0; i < np; ++i)
    if (!std::isfinite(c.target[i]))
      throw Error("joint control: target[" + std::to_string(i) + "] is not finite");
  for (int i = 0; i < n; ++i) {
    const std::string joint = model_.floating && i < 6 ? model_.root_name : model_.bodies[i].joint_name;
    for (const auto& [g, field] : {std::pair<double, const char*>{c.kp[i], "kp"}, {c.kd[i], "kd"}}) {
      if (!(g >= 0) || !std::isfinite(g))
        throw Error(std::string("joint control: ") + field + " of joint '" + joint + "' must be finite and >= 0, got " +
                    message_number(g));
      if (model_.floating && i < 6 && g != 0)
        throw Error(std::string("joint control: ") + field + "[" + std::to_string(i) + "] of joint '" + joint +
                    "' (the floating base's free joint, not actuated) must be 0, got " + message_number(g));
    }
  }
  control_ = c;
  control_on_ = true;
}

void Simulator::clear_joint_control() { control_on_ = false; }

void Simulator::apply_joint_control(const Eigen::VectorXd& q_at, const Eigen::VectorXd& qd_at) {
  if (!control_on_) return;  // step() set case_.ff_torques = ff_torques
  if (ff_torques.size()) case_.ff_torques = ff_torques;
  else case_.ff_torques.setZero(model_.num_joints());
  for (int i = 0; i < model_.num_joints(); ++i) {
    const int p = model_.position_index(i);
    case_.ff_torques[i] += control_.kp[i] * (control_.target[p] - q_at[p]) - control_.kd[i] * qd_at[i];
  }
}

}  // namespace achd
