#include "joint_couplings.hpp"

#include <cmath>
#include <string>

#include <Eigen/Cholesky>

#include "achd/error.hpp"

namespace achd {
namespace {

// C_j x: follower minus multiplier times leader.
double row_times(const JointCoupling& j, const Eigen::VectorXd& x) { return x[j.follower] - j.multiplier * x[j.leader]; }

using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCouplings, kMaxCouplings>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxCouplings, 1>;

// The case of the unit-torque solves: c's state and constraints, nothing else acting.
void homogeneous_case(const Case& c, int n, Case& h) {
  h.q = c.q;
  h.qd.setZero(n);
  h.gravity.setZero();
  h.alpha = c.alpha;
  h.beta.setZero(c.beta.size());
  h.w_fext = c.w_fext;
  h.w_ff = c.w_ff;
  h.constraints = c.constraints;
  for (ConstraintBlock& b : h.constraints) b.beta.setZero();
  h.f_ext.clear();
  h.f_virtual.clear();
  h.prescribed = c.prescribed;
  if (c.any_prescribed()) h.qdd_given.setZero();
  else h.qdd_given.resize(0);
  h.coupling_beta.resize(0);
  h.loop_beta.setZero(c.loop_beta.size());
  h.extra_inertia = c.extra_inertia;  // part of the mass matrix the responses see
}

}  // namespace

double coupling_rate_error(const Model&, const JointCoupling& j, const Eigen::VectorXd& qd) { return row_times(j, qd); }

double coupling_position_error(const Model& model, const JointCoupling& j, const Eigen::VectorXd& q) {
  return q[model.position_index(j.follower)] - j.multiplier * q[model.position_index(j.leader)] - j.offset;
}

void coupled_dynamics(const Model& model, Data& d, const Case& c, const Options& o, SolveOne solve_one) {
  const int n = model.num_rates(), p = static_cast<int>(model.couplings.size());
  Data::Workspace& w = d.workspace;
  Case& h = w.coupling_case;
  Eigen::MatrixXd& R = w.coupling_response;  // n x p: A C^T
  // R's columns: qdd under the unit torques C_j^T alone.
  homogeneous_case(c, n, h);
  Options quiet = o;
  quiet.effects &= ~(kDamping | kFriction);  // (both vanish at qd = 0; skipped outright)
  for (int j = 0; j < p; ++j) {
    const JointCoupling& cj = model.couplings[j];
    h.ff_torques.setZero(n);
    h.ff_torques[cj.follower] = 1;
    h.ff_torques[cj.leader] -= cj.multiplier;
    solve_one(model, d, h, quiet);
    R.col(j) = d.qdd;
  }
  // The plain solve, then (C R) nu_c = C qdd_0 - beta_c over the couplings that can move:
  // a coupling between two prescribed joints has a zero row in C R (no torque moves
  // either); it holds if their given accelerations keep it, and takes no force.
  solve_one(model, d, c, o);
  const auto beta_c = [&](int i) { return c.coupling_beta.size() ? c.coupling_beta[i] : 0.0; };
  const auto prescribed = [&](int joint) { return c.any_prescribed() && c.prescribed[joint]; };
  int active[kMaxCouplings];
  int m = 0;
  for (int i = 0; i < p; ++i) {
    const JointCoupling& ci = model.couplings[i];
    if (!prescribed(ci.follower) || !prescribed(ci.leader)) {
      active[m++] = i;
      continue;
    }
    const double given = row_times(ci, c.qdd_given);
    if (std::abs(given - beta_c(i)) > 1e-12 * (1 + std::abs(c.qdd_given[ci.follower]) + std::abs(ci.multiplier * c.qdd_given[ci.leader])))
      throw Error("joint '" + model.bodies[ci.follower].joint_name + "' coupled to joint '" +
                  model.bodies[ci.leader].joint_name + "': both are prescribed, and their given accelerations break "
                  "the coupling (qdd_f - k qdd_l = " + std::to_string(given) + ")");
  }
  Small S(m, m);
  SmallVector rhs(m);
  for (int a = 0; a < m; ++a) {
    const JointCoupling& ci = model.couplings[active[a]];
    for (int b = 0; b < m; ++b) S(a, b) = R(ci.follower, active[b]) - ci.multiplier * R(ci.leader, active[b]);
    rhs[a] = row_times(ci, d.qdd) - beta_c(active[a]);
  }
  // C R = C A C^T is symmetric positive definite when the couplings are independent:
  // LDL^T, its pivots checked.
  const Eigen::LDLT<Small> ldlt(S);
  const double scale = m ? S.diagonal().cwiseAbs().maxCoeff() : 0.0;
  const SmallVector D = ldlt.vectorD();
  for (int a = 0; a < m; ++a)
    if (!(D[a] > 1e-12 * scale) || !std::isfinite(D[a])) {
      const JointCoupling& ci = model.couplings[active[a]];
      throw Error("joint '" + model.bodies[ci.follower].joint_name + "' coupled to joint '" +
                  model.bodies[ci.leader].joint_name +
                  "': the coupling cannot be held (no torque moves it, or the couplings repeat each other)");
    }
  const SmallVector solved = m ? SmallVector(ldlt.solve(rhs)) : SmallVector(0);
  SmallVector nu_c = SmallVector::Zero(p);
  for (int a = 0; a < m; ++a) {
    nu_c[active[a]] = solved[a];
    if (!std::isfinite(solved[a])) {
      const JointCoupling& ci = model.couplings[active[a]];
      throw Error("joint '" + model.bodies[ci.follower].joint_name + "' coupled to joint '" +
                  model.bodies[ci.leader].joint_name + "': the coupling force overflows (nu_c = " +
                  std::to_string(solved[a]) + ")");
    }
  }
  // The final solve: ff - C^T nu_c.
  h.q = c.q;
  h.qd = c.qd;
  h.gravity = c.gravity;
  h.beta = c.beta;
  h.constraints = c.constraints;
  h.loop_beta = c.loop_beta;
  h.f_ext = c.f_ext;
  h.f_virtual = c.f_virtual;
  h.qdd_given = c.qdd_given;
  if (c.ff_torques.size()) h.ff_torques = c.ff_torques;
  else h.ff_torques.setZero(n);
  for (int j = 0; j < p; ++j) {
    const JointCoupling& cj = model.couplings[j];
    h.ff_torques[cj.follower] -= nu_c[j];
    h.ff_torques[cj.leader] += cj.multiplier * nu_c[j];
  }
  solve_one(model, d, h, o);
  d.coupling_forces = nu_c;
}

}  // namespace achd
