// The constraint sweep through a floating base's free joint in one step.
//
// The free joint's six bodies (free_joint.hpp) sit at the root's origin, massless but the
// last, and their axes S = [S_5 ... S_0] span every motion. Rolling a block's columns
// through them one axis at a time (constraint_sweep.cpp, eqs. c-e) eliminates S^T IA_r S
// axis by axis, IA_r = IA_5 the whole robot's articulated inertia at the root, so that
// what the six bodies add up to is the 6-DoF step of a floating-base ABA:
//   sum_k EZ_s,k EZ_t,k^T / D_k  = F_s^T S (S^T IA_r S)^-1 S^T F_t = F_s^T IA_r^-1 F_t,
//   sum_k EZ_s,k u_k / D_k       = F_s^T IA_r^-1 (w - pA_r),
// F_s the block's columns at the root (before body 5), pA_r = pA_5, and w the wrench with
// S^T w = tau (the free joint's torques as a wrench [f; n]: the public form). Nothing is
// left for the world: E_0 = F - IA_r IA_r^-1 F = 0. One 6 x 6 factorisation replaces six
// passes of every block's columns and the couplings of every pair of blocks on the six
// bodies they all share. The constraint torques of the six bodies need the forces only
// through F nu', rolled through them as one column.
#include "free_joint_constraints.hpp"

#include <cmath>

#include "driver_priorities.hpp"
#include "free_joint.hpp"
#include "joint_subspace.hpp"

namespace achd {

bool use_free_joint_step(const Model& model, Data& d, const Case& c) {
  bool use = model.floating && !has_driver_weights(c);
  if (use && c.any_prescribed()) use = !c.prescribed[0];  // the six come together
  d.workspace.free_joint_step = use;
  return use;
}

namespace {

// IA = L L^T (Cholesky, 6 x 6, IA symmetric positive definite: the whole robot's inertia).
struct Cholesky6 {
  double L[6][6] = {};
  explicit Cholesky6(const Matrix6& A) {
    for (int j = 0; j < 6; ++j) {
      double d = A(j, j);
      for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
      L[j][j] = std::sqrt(d);
      const double inv = 1 / L[j][j];
      for (int i = j + 1; i < 6; ++i) {
        double x = A(i, j);
        for (int k = 0; k < j; ++k) x -= L[i][k] * L[j][k];
        L[i][j] = x * inv;
      }
    }
  }
  // y = L^-1 b, so that b^T IA^-1 c = (L^-1 b) . (L^-1 c).
  void forward(const double* b, double* y) const {
    for (int i = 0; i < 6; ++i) {
      double x = b[i];
      for (int k = 0; k < i; ++k) x -= L[i][k] * y[k];
      y[i] = x / L[i][i];
    }
  }
};

}  // namespace

double free_joint_coupling(Data& d) {
  Data::Workspace& w = d.workspace;
  constexpr int r = kFreeJointBodies - 1;  // the root link's body
  const Cholesky6 IA(d.IA[r]);
  const int m = static_cast<int>(d.E.cols());
  // K_st += (L^-1 F_s) . (L^-1 F_t),  G_s += (L^-1 F_s) . (L^-1 (w - pA_r))
  double Y[kMaxConstraintColumns][6];
  for (int s = 0; s < m; ++s) IA.forward(d.E.col(s).data(), Y[s]);
  Vector6 wrench;  // w: [f; n] with S^T w = tau
  free_joint_torques_to_public(d.X0[r].R, w.tau.data(), wrench.data());
  const Vector6 b = wrench - d.pA[r];
  double yb[6];
  IA.forward(b.data(), yb);
  auto dot6 = [](const double* x, const double* y) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2] + x[3] * y[3] + x[4] * y[4] + x[5] * y[5];
  };
  double probe = 0;
  for (int s = 0; s < m; ++s) {
    for (int t = s; t < m; ++t) {
      const double k = d.K(s, t) + dot6(Y[s], Y[t]);
      d.K(s, t) = d.K(t, s) = k;
      probe += k * 0.0;
    }
    d.G0[s] += dot6(Y[s], yb);
    probe += d.G0[s] * 0.0;
  }
  return probe;
}

void free_joint_constraint_torques(const Model& model, Data& d) {
  const Data::Workspace& w = d.workspace;
  Vector6 force = d.E * d.nu;  // F nu', at the root's origin
  for (int k = kFreeJointBodies - 1; k >= 0; --k) {
    // ct_k = -S_k^T f;  f <- f - U_k S_k^T f / D_k   (the six share one origin: no shift)
    const JointSubspace S = body_subspace(model, d, k);
    const double along = S.z.dot(S.rotational ? force.tail<3>() : force.head<3>());
    d.constraint_torques[k] -= along;
    force -= w.U[k] * (along * w.Dinv[k]);
  }
}

}  // namespace achd
