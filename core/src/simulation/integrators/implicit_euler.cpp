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
// inertia (armature) enters: the case's extra inertia (Case::extra_inertia; the held
// directions' constraints are solved with it).
// The joint PD controller's -kd_i qd_i (joint_control.cpp) counts in c_i like damping.
// Then q_{k+1} = q_k + dt qd_{k+1} and the held angles advance with qd_{k+1}, as in
// semi-implicit Euler. A joint's passive decay rate c_i / I_i is then damped for any dt
// (the factor 1 / (1 + dt c_i / I_i) instead of 1 - dt c_i / I_i); the method is first order.
//
// The held directions' (loops', couplings') errors e decay as e'' = -2 zeta w e' - w^2 e
// (Baumgarte), the e'' the solve enforces. Taken at the step's start, as semi-implicit
// Euler does, with e'_+ = e' + dt e'' and e_+ = e + dt e'_+ that is unstable once
// w^2 dt^2 + 4 zeta w dt > 4 (w dt > 0.83 at zeta = 1: the default
// w = 100 rad/s at dt = 10 ms spins the dual-arm torso's held arms apart, by a factor
// -1.6 a step). Taken at the step's end, e'' = -2 zeta w e'_+ - w^2 e_+, it is
//   e'' = -((2 zeta w + w^2 dt) e' + w^2 e) / D,   D = 1 + 2 zeta w dt + w^2 dt^2,
// backward Euler on the error's decay, stable for any dt: the solve's beta with
// w'^2 = w^2 / D and 2 zeta' w' = (2 zeta w + w^2 dt) / D (implicit_stabilisation), the
// same decay as dt -> 0.
#include <cmath>

#include "integrators.hpp"

namespace achd {

void implicit_inertia(const Model& model, const PassiveTerms& passive, const Eigen::VectorXd& qd, double h,
                      Eigen::VectorXd& out) {
  const bool damping = passive.effects & kDamping, friction = passive.effects & kFriction;
  const double v_f = passive.friction_velocity;
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    double c = damping ? b.damping : 0.0;
    if (passive.kd) c += (*passive.kd)[i];  // the PD controller's -kd qd is damping too
    if (friction && b.friction != 0) {
      const double ch = std::cosh(qd[i] / v_f);  // inf for |qd| >> v_f: c = 0
      c += b.friction / (v_f * ch * ch);
    }
    out[i] = h * c;
    if (passive.kp) out[i] += h * h * (*passive.kp)[i];
  }
}

Stabilisation implicit_stabilisation(double w, double zeta, double dt) {
  const double d = 1 + 2 * zeta * w * dt + w * w * dt * dt;
  const double w_end = w / std::sqrt(d);
  return {w_end, (2 * zeta * w + w * w * dt) / (d * 2 * w_end)};
}

void implicit_euler(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt,
                    const PassiveTerms& passive, Eigen::VectorXd& solve_extra_inertia, Evaluate evaluate,
                    AngleRates angle_rates, Data& first) {
  implicit_inertia(model, passive, x.qd, dt, ws.extra_inertia);
  // The semi-implicit Euler step with dt C in its solve (swapped in and out: no allocation).
  solve_extra_inertia.swap(ws.extra_inertia);
  try {
    semi_implicit_euler(model, ws, x, dt, evaluate, angle_rates, first);
  } catch (...) {
    solve_extra_inertia.swap(ws.extra_inertia);
    throw;
  }
  solve_extra_inertia.swap(ws.extra_inertia);
}

}  // namespace achd
