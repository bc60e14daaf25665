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
#include "spatial_pairs.hpp"
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
inline double subspace_dot(bool rotational, const Vector3& z, const Pairs& f) {
  return z.dot(rotational ? angular_part(f) : linear_part(f));
}

// S s
inline Pairs subspace_times(bool rotational, const Vector3& z, double s) {
  const Vector3 zs = z * s;
  if (rotational) return {{Pair{0, 0}, Pair{0, zs[0]}, Pair{zs[1], zs[2]}}};
  return {{Pair{zs[0], zs[1]}, Pair{zs[2], 0}, Pair{0, 0}}};
}

const Pairs kZero = {{Pair{0, 0}, Pair{0, 0}, Pair{0, 0}}};

// Step 1. Poses (body_poses); IA_i = I_i in base axes;
// v_i = v_p (shifted) + S qd_i;  c_i = v_p (shifted) x S qd_i;  pA_i = v_i x* I_i v_i,
// with I_i v = [m v_lin - h x w; h x v_lin + C w] for I_i = [m 1, -[h]x; [h]x, C].
void outward_kinematics(const Model& model, Data& d, const Case& c, bool moving) {
  body_poses(model, c.q, d.X0, d.r);
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    const int p = b.parent;
    Matrix6& I = d.IA[i];
    const Vector3 h = set_rigid_inertia(I, d.X0[i].R, b.inertia);
    if (!moving) {
      d.v[i].setZero();
      d.c[i].setZero();
      d.pA[i].setZero();
      continue;
    }
    const Vector3 z = joint_axis(d, i), zq = z * c.qd[i];
    Pairs vp = kZero;
    if (p >= 0) {
      vp = load_pairs(d.v[p]);
      motion_to_child(vp, Shift(d.r[i]));
    }
    const Vector3 vl_p = linear_part(vp), w_p = angular_part(vp);
    const bool rotational = is_rotational(b);
    store_pairs(d.v[i], vp + subspace_times(rotational, z, c.qd[i]));
    // c = v_p x S qd: [v_lin x zq; w x zq] (revolute) or [w x zq; 0] (prismatic)
    if (rotational) d.c[i] << vl_p.cross(zq), w_p.cross(zq);
    else d.c[i] << w_p.cross(zq), Vector3::Zero();
    const Vector3 vl = d.v[i].head<3>(), w = d.v[i].tail<3>();
    const Vector3 f = b.inertia(0, 0) * vl - h.cross(w);
    const Vector3 n = h.cross(vl) + I.bottomRightCorner<3, 3>() * w;
    d.pA[i] << w.cross(f), w.cross(n) + vl.cross(f);  // v x* [f; n]
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

// The constraint quantities of step 2 for NC columns, held two columns to a Pair: E row by
// row (E[r][j] = E(r, 2j..2j+1)), G and the columns of M likewise; an odd NC leaves a
// zero lane. Every update of a body is then a handful of pair products per row, the
// same for every column, with no shuffles.
template <int NC>
struct ConstraintColumns {
  static constexpr int NP = (NC + 1) / 2;
  Pair E[6][NP > 0 ? NP : 1], G[NP > 0 ? NP : 1], M[NC > 0 ? NC : 1][NP > 0 ? NP : 1];

  explicit ConstraintColumns(const ConstraintForceMatrix& E0) {
    for (int j = 0; j < NP; ++j) {
      for (int r = 0; r < 6; ++r) E[r][j] = Pair{E0(r, 2 * j), 2 * j + 1 < NC ? E0(r, 2 * j + 1) : 0.0};
      G[j] = splat(0);
      for (int k = 0; k < NC; ++k) M[k][j] = splat(0);
    }
  }

  // Body i, with U = IA S, D, u, c and the shift to its parent:
  //   EZ = E^T S;  E <- E - U EZ^T / D                      (eq. c)
  //   G += E^T c + EZ u / D;  M -= EZ EZ^T / D              (eqs. e, d)
  // then E moves to the parent's origin (rows 3..5 += r x rows 0..2). Writes EZ.
  void update(bool rotational, const Vector3& z, const Pairs& U, double Dinv, double u,
              const Vector6* c, const Shift& s, double* EZ_out) {
    const int o = rotational ? 3 : 0;
    const Pair z0 = splat(z[0]), z1 = splat(z[1]), z2 = splat(z[2]), dinv = splat(Dinv);
    const double Ur[6] = {U.p[0][0], U.p[0][1], U.p[1][0], U.p[1][1], U.p[2][0], U.p[2][1]};
    Pair EZ[NP], EZD[NP];
    for (int j = 0; j < NP; ++j) {
      EZ[j] = (E[o][j] * z0 + E[o + 1][j] * z1) + E[o + 2][j] * z2;
      EZD[j] = EZ[j] * dinv;
      for (int r = 0; r < 6; ++r) E[r][j] -= splat(Ur[r]) * EZD[j];
      Pair g = EZ[j] * splat(u * Dinv);
      if (c)
        for (int r = 0; r < 6; ++r) g += splat((*c)[r]) * E[r][j];
      G[j] += g;
    }
    for (int k = 0; k < NC; ++k) {
      const Pair ezd = splat(EZD[k / 2][k % 2]);
      for (int j = 0; j < NP; ++j) M[k][j] -= EZ[j] * ezd;
    }
    for (int j = 0; j < NP; ++j) {
      E[3][j] += s.r1 * E[2][j] - s.r2 * E[1][j];
      E[4][j] += s.r2 * E[0][j] - s.r0 * E[2][j];
      E[5][j] += s.r0 * E[1][j] - s.r1 * E[0][j];
    }
    for (int k = 0; k < NC; ++k) EZ_out[k] = EZ[k / 2][k % 2];
  }

  // E_0, G_0 and M_0 (symmetric: its lower triangle mirrored).
  void store(Data& d) const {
    for (int k = 0; k < NC; ++k) {
      for (int r = 0; r < 6; ++r) d.E(r, k) = E[r][k / 2][k % 2];
      d.G0[k] = G[k / 2][k % 2];
      for (int l = k; l < NC; ++l) d.M0(l, k) = d.M0(k, l) = M[k][l / 2][l % 2];
    }
  }
};

// Step 2, for i = n-1 .. 0, with nc = NC constraints (a template parameter, so that the
// loops over the constraint columns unroll). Body i's Ia_i = IA_i - U U^T / D is formed
// in locals and added, shifted by r_i, to its parent's IA; the constraint columns roll
// towards the base in locals too (ConstraintColumns).
template <int NC>
void inward_sweep(const Model& model, Data& d, bool moving, bool rotor) {
  ConstraintColumns<NC> cols(d.E);
  for (int i = model.num_joints() - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    const bool rotational = is_rotational(b);
    const Vector3 z = joint_axis(d, i);
    const Matrix6& IA = d.IA[i];
    // U = IA S (the columns 3..5, revolute, or 0..2, prismatic, combined by z),
    // D = S^T IA S + rotor inertia (RBDA 9.28),  u = tau - S^T pA
    const Pairs U = combine_columns(IA, rotational ? 3 : 0, z);
    const Pairs pA = load_pairs(d.pA[i]);
    const double D = subspace_dot(rotational, z, U) + (rotor ? b.rotor_inertia : 0.0);
    const double u = d.tau[i] - subspace_dot(rotational, z, pA);
    if (!(D > 0) || !std::isfinite(D))
      throw Error("joint '" + b.joint_name + "': nothing to move (D = S^T IA S = " +
                  std::to_string(D) + ")");
    store_pairs(d.U[i], U);
    d.D[i] = D;
    d.u[i] = u;
    const double Dinv = 1.0 / D;
    const Shift shift(d.r[i]);
    const int p = b.parent;
    if (p >= 0) {
      // Ia = IA - U U^T / D;  pa = pA + Ia c + U u / D;  the parent adds both, shifted
      Pairs Ia[6];
      minus_rank_one(IA, U, Dinv, Ia);
      Pairs pa = pA + U * splat(u * Dinv);
      if (moving) pa = pa + times(Ia, d.c[i]);
      add_shifted(Ia, shift, d.IA[p]);
      force_to_parent(pa, shift);
      store_pairs(d.pA[p], load_pairs(d.pA[p]) + pa);
    }
    if (NC == 0) continue;
    d.EZ[i].resize(NC);
    cols.update(rotational, z, U, Dinv, u, moving ? &d.c[i] : nullptr, shift, d.EZ[i].data());
  }
  if (NC) cols.store(d);
}

static_assert(kMaxConstraints == 6, "inward_sweep dispatches nc = 0..6");
void inward_sweep(const Model& model, Data& d, int nc, bool moving, bool rotor) {
  switch (nc) {
    case 0: return inward_sweep<0>(model, d, moving, rotor);
    case 1: return inward_sweep<1>(model, d, moving, rotor);
    case 2: return inward_sweep<2>(model, d, moving, rotor);
    case 3: return inward_sweep<3>(model, d, moving, rotor);
    case 4: return inward_sweep<4>(model, d, moving, rotor);
    case 5: return inward_sweep<5>(model, d, moving, rotor);
    default: return inward_sweep<6>(model, d, moving, rotor);
  }
}

// EZ_i^T nu over the nc columns (a loop of at most kMaxConstraints terms).
inline double dot_nc(const ConstraintVector& a, const ConstraintVector& b, int nc) {
  double s = 0;
  for (int k = 0; k < nc; ++k) s += a[k] * b[k];
  return s;
}

// Step 4. a'_i = a_p (shifted) + c_i;  qdd_i = (u_i - U_i^T a'_i - EZ_i^T nu) / D_i;
// a_i = a'_i + S qdd_i.
void outward_accelerations(const Model& model, Data& d, const Vector6& a0, int nc) {
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    Pairs a = load_pairs(b.parent < 0 ? a0 : d.a[b.parent]);
    motion_to_child(a, Shift(d.r[i]));
    a = a + load_pairs(d.c[i]);
    const double ct = -dot_nc(d.EZ[i], d.nu, nc);  // KDL's constraint torque -S^T E nu
    const double qdd = (d.u[i] - dot(load_pairs(d.U[i]), a) + ct) / d.D[i];
    store_pairs(d.a[i], a + subspace_times(is_rotational(b), joint_axis(d, i), qdd));
    d.qdd[i] = qdd;
    d.constraint_torques[i] = ct;
    d.total_torques[i] = d.D[i] * qdd;
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

// The constraint wrench alpha nu at the tip link's origin.
Vector6 constraint_wrench(const Case& c, const ConstraintVector& nu, int nc) {
  Pairs w = kZero;
  for (int k = 0; k < nc; ++k) w = w + load_pairs(c.alpha.col(k).data()) * splat(nu[k]);
  Vector6 out;
  store_pairs(out, w);
  return out;
}

// joint_torques = ff - J^T (alpha nu): the tip wrench w = alpha nu carried from the tip
// link's origin down the chain, tau_i -= S_i^T w (w about body i's origin).
void joint_torques(const Model& model, Data& d, const Case& c, int nc) {
  if (c.ff_torques.size()) d.joint_torques = c.ff_torques;
  else d.joint_torques.setZero();
  if (!nc) return;
  const Link& tip = model.tip();
  Pairs wp = load_pairs(d.constraint_wrench);
  if (!tip.offset.p.isZero()) force_to_parent(wp, Shift(d.X0[tip.body].R * tip.offset.p));  // to the body origin
  for (int i = tip.body; i >= 0; --i) {
    d.joint_torques[i] -= subspace_dot(is_rotational(model.bodies[i]), joint_axis(d, i), wp);
    force_to_parent(wp, Shift(d.r[i]));
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
    // K nu = E_0^T a_0 + G_0 - beta_kdl, with beta_kdl = beta - alpha_lin^T g (physical);
    // a_0 = [-g; 0] when gravity is on.
    const bool physical = o.convention == Convention::Physical;
    d.rhs.resize(nc);
    for (int k = 0; k < nc; ++k) {
      double r = d.G0[k] - c.beta[k];
      if (gravity) {
        const Vector3 e = d.E.col(k).head<3>();
        r -= e.dot(c.gravity);
        if (physical) r += c.alpha.col(k).head<3>().dot(c.gravity);
      }
      d.rhs[k] = r;
    }
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
  d.constraint_wrench = constraint_wrench(c, d.nu, nc);
  joint_torques(model, d, c, nc);
}

}  // namespace achd
