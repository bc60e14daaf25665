// Integrator::ImplicitEuler: semi-implicit Euler that is implicit in the joints' passive
// torques (damping and smoothed friction), the scheme of MuJoCo's "implicitfast"
// restricted to joint-space damping.
//
// The passive torque tau_p(qd) = -b qd - F tanh(qd / v_f) is diagonal in qd, with
//   c_i = -d tau_p,i / d qd_i = b_i + F_i / (v_f cosh^2(qd_i / v_f)).
// Backward Euler in qd with tau_p linearised at qd_k,
//   M (qd_{k+1} - qd_k) = dt (tau(q_k, qd_k) - C (qd_{k+1} - qd_k)),  C = diag(c),
// is qd_{k+1} = qd_k + dt qdd with (M + dt C) qdd = tau(q_k, qd_k): the solve of the
// explicit step with dt c_i added to joint i's axial inertia D_i, exactly where a rotor
// inertia (armature) enters (the held directions' constraints are solved with it).
// The joint PD controller's -kd_i qd_i (joint_control.cpp) counts in c_i like damping.
// Then q_{k+1} = q_k + dt qd_{k+1} and the held angles advance with qd_{k+1}, as in
// semi-implicit Euler. A joint's passive decay rate c_i / I_i is then damped for any dt
// (the factor 1 / (1 + dt c_i / I_i) instead of 1 - dt c_i / I_i); the method is first order.
#include <cmath>

#include "achd/simulator.hpp"

namespace achd {

void Simulator::step_implicit_euler(double dt, double w_n, Data& first) {
  const bool damping = options_.effects & kDamping, friction = options_.effects & kFriction;
  const bool rotor = options_.effects & kRotorInertia;
  const double v_f = solver_.friction_velocity;
  for (int i = 0; i < model_.num_joints(); ++i) {
    const Body& b = model_.bodies[i];
    double c = damping ? b.damping : 0.0;
    if (control_on_) c += control_.kd[i];  // the PD controller's -kd qd is damping too
    if (friction && b.friction != 0) {
      const double ch = std::cosh(qd[i] / v_f);  // inf for |qd| >> v_f: c = 0
      c += b.friction / (v_f * ch * ch);
    }
    implicit_model_.bodies[i].rotor_inertia = (rotor ? b.rotor_inertia : 0.0) + dt * c;
  }
  const std::uint32_t effects = solver_.effects;
  solver_.effects |= kRotorInertia;
  // The semi-implicit Euler step, its solve on implicit_model_ with the armature on (a
  // failed step's undo in step() clears implicit_solve_; step() resets solver_).
  implicit_solve_ = true;
  step_semi_implicit_euler(dt, w_n, first);
  implicit_solve_ = false;
  solver_.effects = effects;
}

}  // namespace achd
