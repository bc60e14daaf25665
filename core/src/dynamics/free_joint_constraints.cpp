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
#include "free_joint_pairs.hpp"
#include "joint_subspace.hpp"
#include "spatial_pairs.hpp"

namespace achd {

bool use_free_joint_step(const Model& model, Data& d, const Case& c, bool prescribed) {
  bool use = model.floating && !has_driver_weights(c);
  if (use && prescribed) use = !c.prescribed[0];  // the six come together
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
};

}  // namespace

double free_joint_coupling(Data& d) {
  Data::Workspace& w = d.workspace;
  constexpr int r = kFreeJointBodies - 1;  // the root link's body
  const Cholesky6 IA(d.IA[r]);
  const int m = static_cast<int>(d.E.cols());
  // The columns F_s, then b = w - pA_r, w the wrench [f; n] with S^T w = tau; turned into
  // y = L^-1 x (free_joint_pairs.hpp), so that x^T IA^-1 x' = y . y'.
  Vector6 wrench;
  free_joint_torques_to_public(d.X0[r].R, w.tau.data(), wrench.data());
  const Vector6 b = wrench - d.pA[r];
  RootColumns y;
  y.count = (m + 2) & ~1;  // (the columns up to b's, rounded up to even)
  y.set_columns(d.E.data(), m);
  for (int i = 0; i < 6; ++i) {
    y.Y[i][m] = b[i];
    y.Y[i][m + 1] = 0;  // the second lane of b's last pair: L^-1 0 = 0
  }
  y.forward(IA.L);
  // K_st += y_s . y_t (both triangles), two rows t of column s at a time (K is
  // column-major), the diagonal alone first where the rows left are odd;
  // G_s += y_s . y_b, two s at a time.
  Pair probe = splat(0.0);
  double diagonal_probe = 0;
  for (int s = 0; s < m; ++s) {
    int t = s;
    if ((m - s) & 1) {
      const double k = d.K(s, s) + y.dots(s, s)[0];
      d.K(s, s) = k;
      diagonal_probe += k * 0.0;
      ++t;
    }
    for (; t < m; t += 2) {
      double* column = &d.K(t, s);  // K(t, s), K(t + 1, s)
      const Pair k = load_pair(column) + y.dots(s, t);
      store_pair(column, k);
      d.K(s, t) = k[0];
      d.K(s, t + 1) = k[1];
      probe += k * splat(0.0);
    }
  }
  double* G0 = d.G0.data();
  int s = 0;
  for (; s + 1 < m; s += 2) {
    const Pair g = load_pair(G0 + s) + y.dots_with(s, m);
    store_pair(G0 + s, g);
    probe += g * splat(0.0);
  }
  if (s < m) {
    G0[s] += y.dots_with(s, m)[0];
    diagonal_probe += G0[s] * 0.0;
  }
  return probe[0] + probe[1] + diagonal_probe;
}

void free_joint_constraint_torques(const Model& model, Data& d) {
  const Data::Workspace& w = d.workspace;
  // F nu', at the root's origin: the first column's share, then the others' (m >= 1)
  const double* F = d.E.data();
  Vector6 force;
  const int m = static_cast<int>(d.nu.size());
  store_pairs(force, add_columns_times(load_pairs(F) * d.nu[0], F + 6, d.nu.data() + 1, m - 1));
  for (int k = kFreeJointBodies - 1; k >= 0; --k) {
    // ct_k = -S_k^T f;  f <- f - U_k S_k^T f / D_k   (the six share one origin: no shift)
    const JointSubspace S = body_subspace(model, d, k);
    const double along = S.z.dot(S.rotational ? force.tail<3>() : force.head<3>());
    d.constraint_torques[k] -= along;
    force -= w.U[k] * (along * w.Dinv[k]);
  }
}

}  // namespace achd
