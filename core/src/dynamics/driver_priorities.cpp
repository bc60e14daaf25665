// Driver priorities (Popov and Vereshchagin's hybrid problem with the constraint's
// priority over the other drivers made adjustable; see Shakhimardanov's thesis and
// Schneider and Bruyninckx, IROS 2019, for the composable form).
//
// The base equation K nu = y - beta' (constraint_sweep.cpp) has on its right the
// acceleration the columns would see without constraint forces,
//   y = E_0^T a_0 + G_0,   G_0 = sum_i EZ_i u_i / D_i,   u_i = tau_i - S_i^T pA_i,
// and every driver enters y linearly: the external wrenches through pA (-f_ext), the
// feed-forward torques through tau, gravity through a_0, velocity products through pA's
// I kappa. So y splits into one part per driver,
//   y = y_f + y_ff + y_rest,   y_f = A M^-1 J^T f_ext,   y_ff = A M^-1 ff
// (A = alpha^T J at each column's point, the scaled columns), and each part is the G_0 of
// a bias sweep with that driver alone: u_f,i = -S_i^T pf_i, pf_p += X_i^T (pf_i + U_i
// u_f,i / D_i), pf starting from -f_ext on each link's body; likewise u_ff,i = ff_i -
// S_i^T pff_i. (A prescribed joint passes its bias unreduced and adds nothing: its known
// motion belongs to y_rest.) Weights w in [0, 1] per column move the constraint's target
// by the share of each driver that passes through:
//   alpha_k^T a = beta_k + (1 - w_fext,k) y_f,k + (1 - w_ff,k) y_ff,k,
// i.e. rhs_k -= (1 - w_fext,k) y_f,k + (1 - w_ff,k) y_ff,k. With every weight 1 the solve
// is the plain one (this file is not run); a column with both weights 1 holds exactly.
// What it solves: w_fext = 0 along a held direction lets a push on the robot move it
// along that direction as it would move the unconstrained robot (a person guiding a
// held hand), while the other columns and drivers keep their priority; w_ff = 0 lets a
// feed-forward torque show as acceleration along the direction (a controller's torque
// is not cancelled by the constraint).
#include "driver_priorities.hpp"

#include "constraint_sweep.hpp"
#include "joint_subspace.hpp"
#include "solve_blocks.hpp"

namespace achd {
namespace {

bool all_ones(const ConstraintVector& w) {
  for (Eigen::Index k = 0; k < w.size(); ++k)
    if (w[k] != 1.0) return false;
  return true;
}

// The weights of source s's column k (1 when none are given).
double weight(const ConstraintVector& w, int k) { return w.size() ? w[k] : 1.0; }

// The two bias sweeps, f_ext alone and ff_torques alone: u_f,i / D_i and u_ff,i / D_i
// into w.driver_qdd (two per body), 0 for prescribed joints.
void driver_sweeps(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& ff_torques, const Options& o,
                   bool prescribed) {
  Data::Workspace& w = d.workspace;
  const int n = model.num_rates();
  for (int i = 0; i < n; ++i) w.driver_bias[i].setZero();
  if ((o.effects & kExternalWrenches) && !c.f_ext.empty())
    for (int l = 0; l < model.num_links(); ++l) {
      const int b = model.links[l].body;
      if (b < 0) continue;  // a link fixed to the root: the base takes the wrench
      // -f moved from the link origin to the body origin: n_b = n + (p_link - p_b) x f
      w.driver_bias[b].head<6>() -= force_shift(c.f_ext[l], d.X0[b].R * model.links[l].offset.p);
    }
  for (int i = n - 1; i >= 0; --i) {
    const JointSubspace S = body_subspace(model, d, i);
    const Vector6 pf = w.driver_bias[i].head<6>(), pff = w.driver_bias[i].tail<6>();
    const bool given = prescribed && c.prescribed[i];
    // the feed-forward torques: ff_torques and the virtual wrenches' torques
    const double ff = given ? 0.0 : (ff_torques.size() ? ff_torques[i] : 0.0) + d.virtual_torques[i];
    const double uf = -S.z.dot(S.rotational ? pf.tail<3>() : pf.head<3>());
    const double uff = ff - S.z.dot(S.rotational ? pff.tail<3>() : pff.head<3>());
    w.driver_qdd[2 * i] = uf * w.Dinv[i];  // Dinv = 0 for a prescribed joint
    w.driver_qdd[2 * i + 1] = uff * w.Dinv[i];
    const int p = model.bodies[i].parent;
    if (p < 0) continue;
    // pa = p + U u / D, moved to the parent's origin
    const Vector6 U = w.U[i];
    w.driver_bias[p].head<6>() += force_shift(pf + U * w.driver_qdd[2 * i], d.r[i]);
    w.driver_bias[p].tail<6>() += force_shift(pff + U * w.driver_qdd[2 * i + 1], d.r[i]);
  }
}

}  // namespace

bool has_driver_weights(const Case& c) {
  if (!all_ones(c.w_fext) || !all_ones(c.w_ff)) return true;
  for (const ConstraintBlock& b : c.constraints)
    if (!all_ones(b.w_fext) || !all_ones(b.w_ff)) return true;
  return false;
}

void weigh_drivers(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& ff_torques, const Options& o,
                   bool prescribed) {
  driver_sweeps(model, d, c, ff_torques, o, prescribed);
  Data::Workspace& w = d.workspace;
  for (const ConstraintSource& s : w.sources) {
    const ConstraintVector& wf = s.block < 0 ? c.w_fext : solve_block(c, d, s.block).w_fext;
    const ConstraintVector& wff = s.block < 0 ? c.w_ff : solve_block(c, d, s.block).w_ff;
    const int stride = s.columns + (s.columns & 1);
    for (int k = 0; k < s.columns; ++k) {
      // y_f,k and y_ff,k: sum over the path of EZ_i,k u_i / D_i for each driver alone
      double yf = 0, yff = 0;
      for_each_on_path(model, s, 0, [&](int i) {
        const double ez = w.ez[s.ez + i * stride + k];
        yf += ez * w.driver_qdd[2 * i];
        yff += ez * w.driver_qdd[2 * i + 1];
      });
      w.rhs[s.column + k] -= (1 - weight(wf, k)) * yf + (1 - weight(wff, k)) * yff;
    }
  }
}

}  // namespace achd
