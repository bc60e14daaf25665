// Composite-rigid-body algorithm for the joint-space mass matrix (RBDA table 6.2).
#include "achd/dynamics.hpp"
#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "check_workspace.hpp"
#include "free_joint.hpp"
#include "joint.hpp"

namespace achd {

void crba(const Model& model, ChainWorkspace& ws, const Eigen::VectorXd& q, const Options& options,
          Eigen::MatrixXd& M) {
  const bool rotor_inertia = options.effects & kRotorInertia;
  const int n = model.num_rates();
  check_workspace_call("crba", model, ws, q);
  std::vector<Transform>& Xup = ws.Xup;
  std::vector<Matrix6>& Ic = ws.Ic;
  // A floating base: the free joint's bodies placed from q[0..6] (their poses relative to
  // one another), then body i's angle is q[i + 1] (free_joint.hpp).
  const int first = model.floating ? kFreeJointBodies : 0;
  if (model.floating) {
    free_joint_poses(q.data(), ws.X0.data(), ws.r.data());
    for (int i = 0; i < first; ++i) {
      const Transform& X = ws.X0[i];
      if (i == 0) {
        Xup[i] = X;
      } else {
        const Transform& P = ws.X0[i - 1];
        Xup[i] = Transform{P.R.transpose() * X.R, P.R.transpose() * (X.p - P.p)};
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    if (i >= first) Xup[i] = joint_transform(model.bodies[i], q[model.position_index(i)]);
    Ic[i] = model.bodies[i].inertia;
  }
  // Ic_p += X^T Ic_i X, from the tip inward.
  for (int i = n - 1; i >= 0; --i)
    if (model.bodies[i].parent >= 0)
      Ic[model.bodies[i].parent] += inertia_to_parent(Xup[i], Ic[i]);
  // M_ii = S_i^T Ic_i S_i;  M_ij = S_j^T (X^T ... F),  F = Ic_i S_i carried to each ancestor j.
  M.setZero(n, n);
  for (int i = 0; i < n; ++i) {
    const Body& b = model.bodies[i];
    Vector6 F = inertia_times_subspace(b, Ic[i]);
    M(i, i) = subspace_dot(b, F) + (rotor_inertia ? b.rotor_inertia : 0.0);
    for (int j = i; model.bodies[j].parent >= 0;) {
      F = Xup[j].force_to_parent(F);
      j = model.bodies[j].parent;
      M(i, j) = M(j, i) = subspace_dot(model.bodies[j], F);
    }
  }
  // In the free joint's public rates (world angular velocity w = R u): M = T M_s T^T with
  // T = diag(1, R, 1), since tau_rot = R tau_s,rot and u = R^T w.
  if (model.floating) {
    const Matrix3 R = ws.X0[kFreeJointBodies - 1].R;
    for (int j = 0; j < n; ++j) M.block<3, 1>(3, j) = (R * M.block<3, 1>(3, j)).eval();
    for (int i = 0; i < n; ++i) M.block<1, 3>(i, 3) = (M.block<1, 3>(i, 3) * R.transpose()).eval();
  }
}

Eigen::MatrixXd crba(const Model& model, const Eigen::VectorXd& q, const Options& options) {
  ChainWorkspace ws(model);
  Eigen::MatrixXd M(model.num_rates(), model.num_rates());
  crba(model, ws, q, options, M);
  return M;
}

}  // namespace achd
