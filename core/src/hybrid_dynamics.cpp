// The Popov-Vereshchagin solver in Featherstone's notation, in four steps:
//   1. outward sweep: body poses, joint subspaces, velocities, velocity-product terms,
//      rigid inertias and bias forces;
//   2. inward sweep: articulated inertias IA and bias forces pA (ABA, RBDA 7.3), plus the
//      unit constraint forces E, their acceleration energy G and coupling M
//      (Vereshchagin 1989 eqs. a-e, KDL's P_tilde, R_tilde, E, G, M);
//   3. at the base: the constraint magnitudes nu from K nu = E_0^T a_0 + G_0 - beta,
//      K = -M_0 (eq. f);
//   4. outward sweep: joint and link accelerations (eq. g).
// Every quantity is in base axes, and body i's are taken about its origin p_i: between a
// body and its parent, vectors and inertias move by the shift r_i = p_i - p_parent alone
//   motion:  m_i = [m_p,lin + m_p,ang x r_i; m_p,ang]
//   force:   f_p = [f_i,lin; f_i,ang + r_i x f_i,lin]
// so no transform ever rotates, and each body's rigid inertia is turned into base axes
// once, in step 1. Gravity enters as the fictitious base acceleration a_0 = [-g; 0], so
// the sweeps compute KDL's accelerations a - [g; 0].
#include "achd/hybrid_dynamics.hpp"

#include <cmath>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "articulated_inertia.hpp"
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

// The joint subspace S = [0; z] (revolute) or [z; 0] (prismatic), z the body's z axis.
inline Vector3 joint_axis(const Data& d, int i) { return d.X0[i].R.col(2); }

// S^T f
inline double subspace_dot(bool rotational, const Vector3& z, const Vector6& f) {
  return rotational ? z.dot(f.tail<3>()) : z.dot(f.head<3>());
}

// S s
inline Vector6 subspace_times(bool rotational, const Vector3& z, double s) {
  Vector6 m;
  if (rotational) m << Vector3::Zero(), z * s;
  else m << z * s, Vector3::Zero();
  return m;
}

// Step 1. Poses (body_poses); IA_i = I_i in base axes;
// v_i = v_p (shifted) + S qd_i;  c_i = v_p (shifted) x S qd_i;  pA_i = v_i x* I_i v_i,
// with I_i v = [m v_lin - h x w; h x v_lin + C w] for I_i = [m 1, -[h]x; [h]x, C].
void outward_kinematics(const Model& model, Data& d, const Case& c, bool moving) {
  body_poses(model, c.q, d.X0, d.r);
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    const int p = b.parent;
    SymmetricInertia& I = d.IA[i];
    const Vector3 h = set_rigid_inertia(I, d.X0[i].R, b.inertia);
    if (!moving) {
      d.v[i].setZero();
      d.c[i].setZero();
      d.pA[i].setZero();
      continue;
    }
    const Vector6 vJ = subspace_times(is_rotational(b), joint_axis(d, i), c.qd[i]);
    if (p < 0) {
      d.v[i] = vJ;
      d.c[i].setZero();
    } else {
      const Vector6 vp = motion_shift(d.v[p], d.r[i]);
      d.v[i] = vp + vJ;
      d.c[i] = cross_motion(vp, vJ);
    }
    const Vector3 vl = d.v[i].head<3>(), w = d.v[i].tail<3>();
    Vector6 Iv;
    Iv << b.inertia(0, 0) * vl - h.cross(w), h.cross(vl) + I.C * w;
    d.pA[i] = cross_force(d.v[i], Iv);
  }
}

// pA_b -= f_ext of every link on body b, moved from the link origin to the body origin:
// n_b = n + (p_link - p_b) x f.
void add_external_wrenches(const Model& model, Data& d, const Case& c) {
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    const int b = link.body;
    if (b < 0) continue;  // a link fixed to the root: the base takes the wrench
    const Vector3 f = c.f_ext[l].head<3>();
    d.pA[b].head<3>() -= f;
    d.pA[b].tail<3>() -= c.f_ext[l].tail<3>();
    if (!link.offset.p.isZero()) d.pA[b].tail<3>() -= (d.X0[b].R * link.offset.p).cross(f);
  }
}

// E = alpha moved from the tip link's origin to the tip body's origin.
void constraint_forces_at_tip(const Model& model, Data& d, const Case& c, int nc) {
  const Link& tip = model.tip();
  const Vector3 r = d.X0[tip.body].R * tip.offset.p;
  d.E.resize(6, nc);
  for (int k = 0; k < nc; ++k) {
    const Vector3 f = c.alpha.col(k).head<3>();
    d.E.col(k).head<3>() = f;
    d.E.col(k).tail<3>() = c.alpha.col(k).tail<3>() + r.cross(f);
  }
}

// Step 2, for i = n-1 .. 0. IA_i and pA_i are overwritten with Ia_i and pa_i (what the
// parent adds to its own, shifted by r_i); E holds the unit constraint forces at body i,
// rolled towards the base.
void inward_sweep(const Model& model, Data& d, int nc, bool moving, bool rotor) {
  for (int i = model.num_joints() - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    const bool rotational = is_rotational(b);
    const Vector3 z = joint_axis(d, i);
    SymmetricInertia& IA = d.IA[i];
    // U = IA S = [B z; C z] (revolute) or [A z; B^T z] (prismatic),
    // D = S^T IA S + rotor inertia (RBDA 9.28),  u = tau - S^T pA
    Vector6& U = d.U[i];
    if (rotational) U << IA.B * z, IA.C * z;
    else U << IA.A * z, IA.B.transpose() * z;
    d.D[i] = subspace_dot(rotational, z, U) + (rotor ? b.rotor_inertia : 0.0);
    d.u[i] = d.tau[i] - subspace_dot(rotational, z, d.pA[i]);
    if (!(d.D[i] > 0) || !std::isfinite(d.D[i]))
      throw Error("joint '" + b.joint_name + "': nothing to move (D = S^T IA S = " +
                  std::to_string(d.D[i]) + ")");
    const double Dinv = 1.0 / d.D[i];
    const int p = b.parent;
    if (p >= 0) {
      // Ia = IA - U U^T / D;  pa = pA + Ia c + U u / D;  the parent adds both, shifted
      subtract_rank_one(IA, U, Dinv);
      Vector6 pa = d.pA[i] + U * (d.u[i] * Dinv);
      if (moving) pa += times(IA, d.c[i]);
      add_shifted(IA, d.r[i], d.IA[p]);
      d.pA[p] += force_shift(pa, d.r[i]);
    }
    if (!nc) continue;
    // EZ = E^T S;  E <- E - U EZ^T / D                        (eq. c)
    // G  += E^T c + EZ u / D;  M -= EZ EZ^T / D                (eqs. e, d)
    // then E moves to the parent's origin.
    ConstraintVector& EZ = d.EZ[i];
    EZ.resize(nc);
    for (int k = 0; k < nc; ++k) {
      EZ[k] = subspace_dot(rotational, z, d.E.col(k));
      d.E.col(k) -= U * (EZ[k] * Dinv);
    }
    if (moving)
      for (int k = 0; k < nc; ++k) d.G0[k] += d.E.col(k).dot(d.c[i]);
    const double uD = d.u[i] * Dinv;
    for (int k = 0; k < nc; ++k) {
      d.G0[k] += EZ[k] * uD;
      const double EZk = EZ[k] * Dinv;
      for (int l = 0; l < nc; ++l) d.M0(l, k) -= EZ[l] * EZk;
    }
    for (int k = 0; k < nc; ++k)
      d.E.col(k).tail<3>() += d.r[i].cross(Vector3(d.E.col(k).head<3>()));
  }
}

// Step 4. a'_i = a_p (shifted) + c_i;  qdd_i = (u_i - U_i^T a'_i - EZ_i^T nu) / D_i;
// a_i = a'_i + S qdd_i.
void outward_accelerations(const Model& model, Data& d, const Vector6& a0, int nc) {
  for (int i = 0; i < model.num_joints(); ++i) {
    const int p = model.bodies[i].parent;
    const Vector6 a_in = motion_shift(p < 0 ? a0 : d.a[p], d.r[i]) + d.c[i];
    const double ct = nc ? -d.EZ[i].dot(d.nu) : 0.0;  // KDL's constraint torque -S^T E nu
    d.qdd[i] = (d.u[i] - d.U[i].dot(a_in) + ct) / d.D[i];
    d.a[i] = a_in + subspace_times(is_rotational(model.bodies[i]), joint_axis(d, i), d.qdd[i]);
    d.constraint_torques[i] = ct;
    d.total_torques[i] = d.D[i] * d.qdd[i];
  }
}

// Spatial acceleration of every link at its origin, base orientation: the body's, moved
// from the body origin to the link origin. `shift` = [g; 0] turns the sweeps' KDL
// accelerations into physical ones.
void link_accelerations(const Model& model, Data& d, const Vector6& a0, const Vector6& shift) {
  d.link_accelerations[0] = a0 + shift;
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    Vector6& out = d.link_accelerations[l + 1];
    if (link.body < 0) out = a0;
    else if (link.offset.p.isZero()) out = d.a[link.body];
    else out = motion_shift(d.a[link.body], d.X0[link.body].R * link.offset.p);
    out += shift;
  }
}

// joint_torques = ff - J^T (alpha nu): the tip wrench w = alpha nu carried from the tip
// link's origin down the chain, tau_i -= S_i^T w (w about body i's origin).
void joint_torques(const Model& model, Data& d, const Case& c, int nc) {
  if (c.ff_torques.size()) d.joint_torques = c.ff_torques;
  else d.joint_torques.setZero();
  if (!nc) return;
  const Link& tip = model.tip();
  const Vector6 w_tip = c.alpha * d.nu;
  Vector6 w = force_shift(w_tip, d.X0[tip.body].R * tip.offset.p);
  for (int i = tip.body; i >= 0; --i) {
    d.joint_torques[i] -= subspace_dot(is_rotational(model.bodies[i]), joint_axis(d, i), w);
    w.tail<3>() += d.r[i].cross(Vector3(w.head<3>()));
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
  if (nc) constraint_forces_at_tip(model, d, c, nc);
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
