// The Popov-Vereshchagin solver in Featherstone's notation, in four steps:
//   1. outward sweep: joint transforms, velocities, velocity-product terms, bias forces;
//   2. inward sweep: articulated inertias IA and bias forces pA (ABA, RBDA 7.3), plus the
//      unit constraint forces E, their acceleration energy G and coupling M
//      (Vereshchagin 1989 eqs. a-e, KDL's P_tilde, R_tilde, E, G, M);
//   3. at the base: the constraint magnitudes nu from K nu = E_0^T a_0 + G_0 - beta,
//      K = -M_0 (eq. f);
//   4. outward sweep: joint and link accelerations (eq. g).
// All body quantities are in the body's own frame; gravity enters as the fictitious base
// acceleration a_0 = [-g; 0], so the sweeps compute KDL's accelerations a - [g; 0].
#include "achd/hybrid_dynamics.hpp"

#include <cmath>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "coupling_solve.hpp"
#include "joint.hpp"

namespace achd {
namespace {

bool any_nonzero(const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (v[i] != 0.0) return true;
  return false;
}

// Joint torques fed to the sweeps: tau = ff - damping qd - friction tanh(qd / v_f).
void joint_forces(const Model& model, Data& d, const Case& c, const Options& o) {
  const int n = model.num_joints();
  if (c.ff_torques.size()) d.tau = c.ff_torques;
  else d.tau.setZero(n);
  if (!c.qd.size()) return;
  if (o.effects & kDamping)
    for (int i = 0; i < n; ++i) d.tau[i] -= model.bodies[i].damping * c.qd[i];
  if (o.effects & kFriction)
    for (int i = 0; i < n; ++i)
      d.tau[i] -= model.bodies[i].friction * std::tanh(c.qd[i] / o.friction_velocity);
}

// Step 1. v_i = Xup_i v_p + S qd_i;  c_i = v_i x S qd_i;  pA_i = v_i x* I_i v_i.
void outward_kinematics(const Model& model, Data& d, const Case& c, bool moving) {
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    d.Xup[i] = joint_transform(b, c.q[i]);
    d.X0[i] = b.parent < 0 ? d.Xup[i] : d.X0[b.parent] * d.Xup[i];
    d.IA[i] = b.inertia;
    if (moving) {
      const Vector6 vJ = subspace_times(b, c.qd[i]);
      d.v[i] = b.parent < 0 ? vJ : Vector6(d.Xup[i].motion_to_child(d.v[b.parent]) + vJ);
      d.c[i] = cross_motion(d.v[i], vJ);
      d.pA[i] = cross_force(d.v[i], b.inertia * d.v[i]);
    } else {
      d.v[i].setZero();
      d.c[i].setZero();
      d.pA[i].setZero();
    }
  }
}

// pA_b -= f_ext of every link on body b, moved from the link origin (base orientation)
// to the body origin in body coordinates: f_b = R0^T f, n_b = R0^T n + p x f_b.
void add_external_wrenches(const Model& model, Data& d, const Case& c) {
  for (int l = 0; l < model.num_links(); ++l) {
    const int b = model.links[l].body;
    if (b < 0) continue;  // a link fixed to the root: the base takes the wrench
    const Matrix3& R0 = d.X0[b].R;
    const Vector3 f = R0.transpose() * c.f_ext[l].head<3>();
    d.pA[b].head<3>() -= f;
    d.pA[b].tail<3>() -= R0.transpose() * c.f_ext[l].tail<3>() + model.links[l].offset.p.cross(f);
  }
}

// alpha (tip origin, base orientation) -> the tip body's frame and origin.
void constraint_forces_at_tip(const Model& model, Data& d, const Case& c, int nc) {
  const Link& tip = model.tip();
  const Matrix3& R0 = d.X0[tip.body].R;
  d.alpha_body.resize(6, nc);
  for (int k = 0; k < nc; ++k) {
    const Vector3 f = R0.transpose() * c.alpha.col(k).head<3>();
    d.alpha_body.col(k).head<3>() = f;
    d.alpha_body.col(k).tail<3>() = R0.transpose() * c.alpha.col(k).tail<3>() + tip.offset.p.cross(f);
  }
}

// Step 2, for i = n-1 .. 0. IA_i and pA_i are overwritten with Ia_i and pa_i (what the
// parent receives); E holds the unit constraint forces at body i, rolled towards the base.
void inward_sweep(const Model& model, Data& d, int nc, bool moving, bool rotor) {
  for (int i = model.num_joints() - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    // U = IA S,  D = S^T IA S + rotor inertia (RBDA 9.28),  u = tau - S^T pA
    d.U[i] = inertia_times_subspace(b, d.IA[i]);
    d.D[i] = subspace_dot(b, d.U[i]) + (rotor ? b.rotor_inertia : 0.0);
    d.u[i] = d.tau[i] - subspace_dot(b, d.pA[i]);
    if (!(d.D[i] > 0) || !std::isfinite(d.D[i]))
      throw Error("joint '" + b.joint_name + "': nothing to move (D = S^T IA S = " +
                  std::to_string(d.D[i]) + ")");
    const double Dinv = 1.0 / d.D[i];
    const Vector6 Ud = d.U[i] * Dinv;
    const int p = b.parent;
    if (p >= 0) {
      // Ia = IA - U U^T / D;  pa = pA + Ia c + U u / D;  the parent adds X^T Ia X, X^T pa
      d.IA[i].noalias() -= Ud * d.U[i].transpose();
      if (moving) d.pA[i].noalias() += d.IA[i] * d.c[i];
      d.pA[i] += Ud * d.u[i];
      add_inertia_to_parent(d.Xup[i], d.IA[i], d.IA[p]);
      d.pA[p] += d.Xup[i].force_to_parent(d.pA[i]);
    }
    if (!nc) continue;
    // EZ = E^T S;  Ea = E - U EZ^T / D                        (eq. c)
    // G  += Ea^T c + EZ u / D;  M -= EZ EZ^T / D               (eqs. e, d)
    ConstraintVector& EZ = d.EZ[i];
    EZ.resize(nc);
    for (int k = 0; k < nc; ++k) EZ[k] = subspace_dot(b, d.E.col(k));
    d.E.noalias() -= Ud * EZ.transpose();
    if (moving) d.G0.noalias() += d.E.transpose() * d.c[i];
    d.G0 += EZ * (d.u[i] * Dinv);
    d.M0.noalias() -= (EZ * Dinv) * EZ.transpose();
    // E_parent = X^T Ea: f_P = R f, n_P = R n + p x f_P, all columns at once
    const Matrix3& R = d.Xup[i].R;
    d.Ea.resize(6, nc);
    d.Ea.topRows<3>().noalias() = R * d.E.topRows<3>();
    d.Ea.bottomRows<3>().noalias() = R * d.E.bottomRows<3>();
    for (int k = 0; k < nc; ++k)
      d.Ea.col(k).tail<3>() += d.Xup[i].p.cross(Vector3(d.Ea.col(k).head<3>()));
    d.E.swap(d.Ea);
  }
}

// Step 4. a'_i = Xup_i a_p + c_i;  qdd_i = (u_i - U_i^T a'_i - EZ_i^T nu) / D_i;
// a_i = a'_i + S qdd_i.
void outward_accelerations(const Model& model, Data& d, const Vector6& a0, int nc) {
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    const Vector6 a_in = d.Xup[i].motion_to_child(b.parent < 0 ? a0 : d.a[b.parent]) + d.c[i];
    const double ct = nc ? -d.EZ[i].dot(d.nu) : 0.0;  // KDL's constraint torque -S^T E nu
    d.qdd[i] = (d.u[i] - d.U[i].dot(a_in) + ct) / d.D[i];
    d.a[i] = a_in + subspace_times(b, d.qdd[i]);
    d.constraint_torques[i] = ct;
    d.total_torques[i] = d.D[i] * d.qdd[i];
  }
}

// Spatial acceleration of every link at its origin, base orientation; `shift` = [g; 0]
// turns the sweeps' KDL accelerations into physical ones.
void link_accelerations(const Model& model, Data& d, const Vector6& a0, const Vector6& shift) {
  d.link_accelerations[0] = a0 + shift;
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    Vector6& out = d.link_accelerations[l + 1];
    if (link.body < 0) {
      out = a0 + shift;
      continue;
    }
    const Vector6& ab = d.a[link.body];
    const Matrix3& R0 = d.X0[link.body].R;
    out.head<3>() = R0 * (ab.head<3>() + ab.tail<3>().cross(link.offset.p));
    out.tail<3>() = R0 * ab.tail<3>();
    out += shift;
  }
}

// joint_torques = ff - J^T (alpha nu): walk the tip wrench down the chain, tau_i = S^T w.
void joint_torques(const Model& model, Data& d, const Case& c, int nc) {
  if (c.ff_torques.size()) d.joint_torques = c.ff_torques;
  else d.joint_torques.setZero();
  if (!nc) return;
  Vector6 w = d.alpha_body * d.nu;
  for (int i = model.tip().body; i >= 0; --i) {
    d.joint_torques[i] -= subspace_dot(model.bodies[i], w);
    w = d.Xup[i].force_to_parent(w);
  }
}

}  // namespace

void hybrid_dynamics(const Model& model, Data& d, const Case& c, const Options& o) {
  validate(model, c);
  validate(o);
  const int nc = (o.effects & kConstraints) ? c.num_constraints() : 0;
  const bool gravity = o.effects & kGravity;
  // Skipped by themselves when their inputs are zero: the result is identical.
  const bool moving = (o.effects & kVelocityProducts) && any_nonzero(c.qd);
  const bool wrenches = (o.effects & kExternalWrenches) && !c.f_ext.empty();

  joint_forces(model, d, c, o);
  outward_kinematics(model, d, c, moving);
  if (wrenches) add_external_wrenches(model, d, c);

  d.M0.setZero(nc, nc);
  d.G0.setZero(nc);
  if (nc) {
    constraint_forces_at_tip(model, d, c, nc);
    d.E = d.alpha_body;
  }
  inward_sweep(model, d, nc, moving, o.effects & kRotorInertia);

  Vector6 a0 = Vector6::Zero();  // base acceleration: [-g; 0]
  if (gravity) a0.head<3>() = -c.gravity;
  d.nu.setZero(nc);
  if (nc) {
    // K nu = E_0^T a_0 + G_0 - beta_kdl, with beta_kdl = beta - alpha_lin^T g (physical).
    d.rhs.noalias() = d.E.transpose() * a0 + d.G0 - c.beta;
    if (o.convention == Convention::Physical && gravity)
      d.rhs.noalias() += c.alpha.topRows<3>().transpose() * c.gravity;
    d.M0 = -d.M0;
    solve_coupling(d, o);
  } else {
    d.rank = 0;
    d.sigma_min = 0;
    d.dropped.resize(0, 0);
  }
  outward_accelerations(model, d, a0, nc);

  Vector6 shift = Vector6::Zero();
  if (o.convention == Convention::Physical && gravity) shift.head<3>() = c.gravity;
  link_accelerations(model, d, a0, shift);
  joint_torques(model, d, c, nc);
  d.constraint_wrench = nc ? Vector6(c.alpha * d.nu) : Vector6::Zero();
}

}  // namespace achd
