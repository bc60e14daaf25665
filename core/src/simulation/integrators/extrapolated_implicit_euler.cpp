// The extrapolated linearly implicit Euler method: the substeps Dormand-Prince takes where
// it has detected stiffness (dormand_prince.cpp). Stiff is what the joint PD controller and
// the joints' damping and friction make of light links: tau_i = kp_i (q*_i - q_i) - c_i qd_i
// with c_i = b_i + kd_i + the friction slope, whose decay rates reach c_i / m_i.
//
// A linearly implicit Euler step of h from x = (q, qd), with J the Jacobian of those
// torques (diagonal: -kp in q, -c in qd, the implicit_euler.cpp idea extended to kp),
//   (I - h [0 I; -M^-1 Kp  -M^-1 C]) dx = h f(x),
// is, eliminating dq = h (qd + dqd):
//   (M + h C + h^2 Kp) qdd = tau(q, qd) - h Kp qd,   qd' = qd + h qdd,   q' = q + h qd'
// (q' on the configuration manifold: integrate()). That is one solve of the simulator's
// x' = f(x) with h c_i + h^2 kp_i added to joint i's axial inertia, where a rotor inertia
// enters, and the PD torque taken at q + h qd (implicit_evaluate); the held directions are
// solved within it, with their stabilisation, as in every solve. The held angles, not
// stiff, advance explicitly (h e . w(q, qd), the rates of that solve). The step damps the
// stiff decay rates for any h (the factor 1 / (1 + h c/m + h^2 kp/m)), to first order.
//
// Extrapolation (Deuflhard; Hairer, Wanner, Solving ODEs II, IV.9, as in their SEULEX):
// row j takes n_j = j steps of h / n_j, T_j1 its result; the Aitken-Neville scheme for an
// error expansion in powers of h,
//   T_j,l+1 = T_j,l + (T_j,l - T_j-1,l) / (n_j / n_j-l - 1),
// makes T_jj of order j, and err_j = T_jj - T_j,j-1 estimates the error of T_j,j-1,
// O(h^j): measured as Dormand-Prince's, RMS of err_i / (atol + rtol max(|x_i|, |x'_i|))
// over q, qd and the integrated held angles. Rows are added until err_j <= 1 (x' = T_jj,
// the substep accepted with j rows: 1 + 2 + ... + j solves) or kMaxImplicitRows have
// failed (rejected), so that a substep the output step dt caps takes only the rows its
// accuracy needs. The entries T_jl are stable for any h on the stiff decay rates (their
// stability functions, combinations of 1 / (1 - z / n)^n, vanish as z -> -inf). The
// expansion in h exists for any fixed linearisation, so on the smooth motion the order
// holds whatever the Jacobian leaves out (the configuration dependence of M, the velocity
// products); the error estimate, not the order, is what the step control relies on.
#include <algorithm>
#include <cmath>
#include <utility>

#include "achd/kinematics.hpp"
#include "integrators.hpp"

namespace achd {

namespace {

// One linearly implicit Euler step of h from s, in place (s.t advances by h; its first na
// held angles are x's); false when the new state is not finite (then s is partly advanced).
bool implicit_step(const Model& model, IntegratorWorkspace& ws, SimulationState& s, Eigen::Index na, double h,
                   ImplicitEvaluate implicit_evaluate) {
  implicit_evaluate(s, h, ws.stage_data, ws.rates);  // the held angles' rates at (q, qd)
  s.qd += h * ws.stage_data.qdd;
  s.held_angles.head(na) += h * ws.rates.head(na);
  integrate(model, s.q, s.qd, h, s.q);
  s.t += h;
  return s.q.allFinite() && s.qd.allFinite() && s.held_angles.head(na).allFinite();
}

}  // namespace

ImplicitSubstep extrapolated_implicit_euler(const Model& model, IntegratorWorkspace& ws, const SimulationState& x,
                                            double t, double h, double rtol, double atol,
                                            const std::vector<char>& integrated_angles,
                                            ImplicitEvaluate implicit_evaluate) {
  const Eigen::Index na = x.held_angles.size();
  SimulationState* T = ws.extrapolation;  // T[l] = T_j,l+1 of the latest row j
  SimulationState* cur = &ws.stage_state;  // T_j,l
  SimulationState* next = &ws.extrapolation[kMaxImplicitRows];  // T_j,l+1
  const auto exchange = [](SimulationState& a, SimulationState& b) {  // (the vectors' buffers: no copy)
    a.q.swap(b.q);
    a.qd.swap(b.qd);
    a.held_angles.swap(b.held_angles);
  };
  double err = INFINITY;
  int j = 1;
  for (; j <= kMaxImplicitRows; ++j) {
    SimulationState& row = *cur;  // T_j,1: j steps of h / j from x
    row.q = x.q;
    row.qd = x.qd;
    row.held_angles.head(na) = x.held_angles;
    row.t = t;
    for (int step = 0; step < j; ++step)
      if (!implicit_step(model, ws, row, na, h / j, implicit_evaluate)) return {INFINITY, j};
    for (int l = 1; l < j; ++l) {
      // T_j,l+1 = T_j,l + (T_j,l - T_j-1,l) / (n_j / n_j-l - 1), T_j-1,l in T[l - 1]
      const double f = 1 / (static_cast<double>(j) / (j - l) - 1);
      next->q = cur->q + f * (cur->q - T[l - 1].q);
      next->qd = cur->qd + f * (cur->qd - T[l - 1].qd);
      next->held_angles.head(na) =
          cur->held_angles.head(na) + f * (cur->held_angles.head(na) - T[l - 1].held_angles.head(na));
      exchange(T[l - 1], *cur);  // T[l - 1] = T_j,l
      std::swap(cur, next);
    }
    exchange(T[j - 1], *cur);  // T[j - 1] = T_j,j
    if (j < 2) continue;
    // err = T_jj - T_j,j-1 in the error norm
    const SimulationState &best = T[j - 1], &lower = T[j - 2];
    double sum = 0;
    int count = 0;
    const auto add = [&](double x0, double x1, double e) {
      const double scale = atol + rtol * std::max(std::abs(x0), std::abs(x1));
      sum += (e / scale) * (e / scale);
      ++count;
    };
    for (Eigen::Index i = 0; i < x.q.size(); ++i) add(x.q[i], best.q[i], best.q[i] - lower.q[i]);
    for (Eigen::Index i = 0; i < x.qd.size(); ++i) add(x.qd[i], best.qd[i], best.qd[i] - lower.qd[i]);
    for (Eigen::Index a = 0; a < na; ++a)
      if (integrated_angles[a]) add(x.held_angles[a], best.held_angles[a], best.held_angles[a] - lower.held_angles[a]);
    err = count ? std::sqrt(sum / count) : 0;
    if (err <= 1) break;  // converged: T_jj
  }
  if (j > kMaxImplicitRows) return {err, kMaxImplicitRows};
  // x' = T_jj, into ws.next_state
  SimulationState& out = ws.next_state;
  out.q = T[j - 1].q;
  out.qd = T[j - 1].qd;
  out.held_angles.head(na) = T[j - 1].held_angles.head(na);
  return {err, j};
}

}  // namespace achd
