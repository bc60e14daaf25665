// The first-order integrators and the integrators' workspace.
#include "achd/kinematics.hpp"
#include "integrators.hpp"

namespace achd {

IntegratorWorkspace::IntegratorWorkspace(const Model& model, Eigen::Index max_held_angles)
    : stage_data(model, kMaxConstraintColumns) {
  const int n = model.num_rates();
  const Eigen::VectorXd q0 = Case::zeros(model).q;  // num_positions()
  const auto size = [&](SimulationState& s) {
    s.q = q0;
    s.qd = Eigen::VectorXd::Zero(n);
    s.held_angles = HeldAngles::Zero(max_held_angles);
  };
  size(stage_state);
  size(next_state);
  for (SimulationState& s : extrapolation) size(s);
  rates = HeldAngles::Zero(max_held_angles);
  for (auto& k : k_q) k = Eigen::VectorXd::Zero(q0.size());  // dq/dt: configuration_rate
  for (auto& k : k_qd) k = Eigen::VectorXd::Zero(n);
  for (auto& k : k_angle) k = HeldAngles::Zero(max_held_angles);
  extra_inertia = Eigen::VectorXd::Zero(n);
}

void explicit_euler(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt, Evaluate evaluate,
                    Data& first) {
  ws.stage = 0;
  evaluate(x, first, ws.k_angle[0]);
  integrate(model, x.q, x.qd, dt, x.q);
  x.qd += dt * first.qdd;
  const Eigen::Index na = x.held_angles.size();
  x.held_angles += dt * ws.k_angle[0].head(na);
}

void semi_implicit_euler(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt,
                         Evaluate evaluate, AngleRates angle_rates, Data& first) {
  ws.stage = 0;
  evaluate(x, first, ws.k_angle[0]);
  x.qd += dt * first.qdd;
  angle_rates(x, ws.rates);  // at (q_k, qd_{k+1})
  const Eigen::Index na = x.held_angles.size();
  x.held_angles += dt * ws.rates.head(na);
  integrate(model, x.q, x.qd, dt, x.q);
}

}  // namespace achd
