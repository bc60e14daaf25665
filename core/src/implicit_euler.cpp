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
// Then q_{k+1} = q_k + dt qd_{k+1} and the held angles advance with qd_{k+1}, as in
// semi-implicit Euler. A joint's passive decay rate c_i / I_i is then damped for any dt
// (the factor 1 / (1 + dt c_i / I_i) instead of 1 - dt c_i / I_i); the method is first order.
#include <cmath>

#include "achd/hybrid_dynamics.hpp"
#include "achd/simulator.hpp"
#include "held_directions.hpp"

namespace achd {

void Simulator::step_implicit_euler(double dt, double w_n, Data& first) {
  const bool damping = options_.effects & kDamping, friction = options_.effects & kFriction;
  const bool rotor = options_.effects & kRotorInertia;
  const double v_f = solver_.friction_velocity;
  for (int i = 0; i < model_.num_joints(); ++i) {
    const Body& b = model_.bodies[i];
    double c = damping ? b.damping : 0.0;
    if (friction && b.friction != 0) {
      const double ch = std::cosh(qd[i] / v_f);  // inf for |qd| >> v_f: c = 0
      c += b.friction / (v_f * ch * ch);
    }
    implicit_model_.bodies[i].rotor_inertia = (rotor ? b.rotor_inertia : 0.0) + dt * c;
  }
  const std::uint32_t effects = solver_.effects;
  solver_.effects |= kRotorInertia;
  implicit_solve_ = true;
  stage_ = 0;
  evaluate(q, qd, held_.angle, w_n, first, k_angle_[0]);
  implicit_solve_ = false;
  solver_.effects = effects;
  qd += dt * first.qdd;
  body_motion(model_, q, qd, X0_, r_, v_);
  const Vector3 w = tip_state(model_, X0_, v_).w;
  for (int k = 0; k < kNumDirections; ++k)
    if (held_.mode[k] == DirectionMode::Hold && !is_linear_direction(k))
      held_.angle[k] += dt * direction_axis(k).dot(w);
  q += dt * qd;
}

}  // namespace achd
