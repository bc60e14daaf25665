// Classical Runge-Kutta: k1 = f(x), k2 = f(x + dt/2 k1), k3 = f(x + dt/2 k2),
// k4 = f(x + dt k3);  x_{k+1} = x + dt/6 (k1 + 2 k2 + 2 k3 + k4), the stages at
// t, t + dt/2, t + dt/2, t + dt.
#include "achd/kinematics.hpp"
#include "integrators.hpp"

namespace achd {

void rk4(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt, Evaluate evaluate, Data& first) {
  static constexpr double kStageStep[4] = {0, 0.5, 0.5, 1.0};
  const Eigen::Index na = x.held_angles.size();
  SimulationState& xs = ws.stage_state;
  for (int s = 0; s < 4; ++s) {
    ws.stage = s;
    Data& out = s == 0 ? first : ws.stage_data;
    if (s == 0) {
      evaluate(x, out, ws.k_angle[0]);
    } else {
      const double h = kStageStep[s] * dt;
      xs.q = x.q + h * ws.k_q[s - 1];
      xs.qd = x.qd + h * ws.k_qd[s - 1];
      xs.held_angles.head(na) = x.held_angles + h * ws.k_angle[s - 1].head(na);
      xs.t = x.t + h;
      evaluate(xs, out, ws.k_angle[s]);
    }
    configuration_rate(model, s == 0 ? x.q : xs.q, s == 0 ? x.qd : xs.qd, ws.k_q[s]);
    ws.k_qd[s] = out.qdd;
  }
  const double w = dt / 6;
  x.q += w * (ws.k_q[0] + 2 * ws.k_q[1] + 2 * ws.k_q[2] + ws.k_q[3]);
  normalise_configuration(model, x.q);  // a floating base's quaternion back to unit length
  x.qd += w * (ws.k_qd[0] + 2 * ws.k_qd[1] + 2 * ws.k_qd[2] + ws.k_qd[3]);
  x.held_angles += w * (ws.k_angle[0].head(na) + 2 * ws.k_angle[1].head(na) + 2 * ws.k_angle[2].head(na) +
                        ws.k_angle[3].head(na));
}

}  // namespace achd
