// The Popov-Vereshchagin solver in Featherstone's notation, in four steps:
//   1. outward sweep: body poses, joint subspaces, velocities, velocity-product
//      accelerations, rigid inertias and bias forces;
//   2. inward sweep: articulated inertias IA and bias forces pA (ABA, RBDA 7.3), then the
//      unit constraint forces E and, from them, the coupling K = -M_0 and the bias
//      energy G_0 (Vereshchagin 1989 eqs. a-e, KDL's P_tilde, R_tilde, E, M, G);
//   3. at the base: the constraint magnitudes nu from K nu = E_0^T a_0 + G_0 - beta (eq. f);
//   4. outward sweep: joint and link accelerations (eq. g).
// Every quantity is in base axes, and body i's are taken about its origin p_i: between a
// body and its parent, vectors and inertias move by the shift r_i = p_i - p_parent alone
//   motion:  m_i = [m_p,lin + m_p,ang x r_i; m_p,ang]
//   force:   f_p = [f_i,lin; f_i,ang + r_i x f_i,lin]
// so no transform ever rotates, and each body's rigid inertia is turned into base axes
// once, in step 1. Gravity enters as the fictitious base acceleration a_0 = [-g; 0], so
// the sweeps compute KDL's accelerations a - [g; 0].
//
// Velocity products enter as accelerations: kappa_i = kappa_p (shifted) + c_i, with
// c_i = v_p x S qd_i, is what body i's acceleration would be with qdd = 0 and no gravity.
// Writing a_i = a~_i + kappa_i turns body i's equation of motion
//   f_i = I_i a_i + v_i x* I_i v_i   into   f_i = I_i a~_i + (v_i x* I_i v_i + I_i kappa_i),
// the equations of a chain whose velocity-product accelerations are zero and whose bias
// forces carry I kappa: the sweeps need no Ia c and no E^T c (RBDA 7.3's and
// Vereshchagin's c terms), and the constraint alpha^T a_tip = beta reads
// alpha^T a~_tip = beta - alpha^T kappa_tip.
//
// Prescribed joints (Featherstone's hybrid dynamics, RBDA 9.2; Case::prescribed): a joint
// whose acceleration is given is no degree of freedom of the articulated body. Its body
// passes IA and pA to the parent unreduced (a rigid attachment), pA with the inertial force
// U qdd_given = IA S qdd_given of its known motion; the constraint sweep passes E unreduced
// and counts the known motion in G_0 (EZ qdd_given in place of a free joint's EZ u / D);
// the final sweep takes qdd_given, and the torque it needs is what a free joint's equation
// D qdd = u - U^T a~ - EZ^T nu leaves over. In the code a prescribed joint has Dinv = 0 and
// W = 0, and the sweeps are templated on whether any joint is prescribed, so a solve
// without prescribed joints runs the code it ran before.
#include "achd/hybrid_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "constraint_sweep.hpp"
#include "coupling_solve.hpp"
#include "driver_priorities.hpp"
#include "free_joint.hpp"
#include "joint.hpp"
#include "joint_couplings.hpp"
#include "joint_subspace.hpp"
#include "loop_blocks.hpp"
#include "overflow_error.hpp"
#include "solve_blocks.hpp"
#include "virtual_wrenches.hpp"
#include "yield_to_efforts.hpp"
#include "spatial_pairs.hpp"

namespace achd {
namespace {

inline bool is_zero(const Vector3& p) { return p[0] == 0 && p[1] == 0 && p[2] == 0; }

bool any_nonzero(const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (v[i] != 0.0) return true;
  return false;
}

// Joint torques fed to the sweeps: tau = ff - damping qd - friction tanh(qd / v_f); a
// prescribed joint's ff is ignored (its torque is an output), so its tau is the passive part.
void joint_forces(const Model& model, Data& d, const Case& c, const JointInputs& j, const Options& o,
                  bool prescribed) {
  Data::Workspace& w = d.workspace;
  const int n = model.num_rates();
  if (j.ff_torques.size()) w.tau = j.ff_torques;
  else w.tau.setZero(n);
  if (prescribed)
    for (int i = 0; i < n; ++i)
      if (c.prescribed[i]) w.tau[i] = 0;
  if (!j.qd.size()) return;
  if (o.effects & kDamping)
    for (int i = 0; i < n; ++i) w.tau[i] -= model.bodies[i].damping * j.qd[i];
  if (o.effects & kFriction)
    for (int i = 0; i < n; ++i)  // (tanh is the costliest term here: skipped where it has no effect)
      if (model.bodies[i].friction != 0) w.tau[i] -= model.bodies[i].friction * std::tanh(j.qd[i] / o.friction_velocity);
}

const SpatialVector kZero{};

// Step 1. Poses (body_poses: hybrid_dynamics computed them); IA_i = I_i in base axes;
// v_i = v_p (shifted) + S qd_i;  c_i = v_p (shifted) x S qd_i;  kappa_i = kappa_p (shifted) + c_i;
// pA_i = v_i x* I_i v_i + I_i kappa_i,
// with I_i x = [m x_lin - h x x_ang; h x x_lin + C x_ang] for I_i = [m 1, -[h]x; [h]x, C].
void outward_kinematics(const Model& model, Data& d, const double* rates, bool moving) {
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    const int p = b.parent;
    const RigidInertia I = set_rigid_inertia(d.IA[i], d.X0[i].R, b.inertia);
    if (!moving) {
      d.v[i].setZero();
      d.kappa[i].setZero();
      d.pA[i].setZero();
      continue;
    }
    const JointSubspace S = body_subspace(model, d, i);
    const double qd = rates[i];
    SpatialVector vp = kZero, kappa = kZero;  // v_p and kappa_p about body i's origin
    if (p >= 0) {
      const Shift s(d.r[i]);
      vp = load_pairs(d.v[p]);
      motion_to_child(vp, s);
      kappa = load_pairs(d.kappa[p]);
      motion_to_child(kappa, s);
    }
    kappa = kappa + velocity_product_acceleration(vp, S, qd);  // kappa_i = kappa_p + c_i
    const SpatialVector v = vp + S.motion(qd);                 // v_i = v_p + S qd_i
    store_pairs(d.v[i], v);
    store_pairs(d.kappa[i], kappa);
    store_pairs(d.pA[i], bias_force(I, v, kappa));  // pA_i = v_i x* I_i v_i + I_i kappa_i
  }
}

// pA_b -= f_ext of every link on body b, moved from the link origin to the body origin:
// n_b = n + (p_link - p_b) x f.
void add_external_wrenches(const Model& model, Data& d, const Case& c) {
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    const int b = link.body;
    if (b < 0) continue;  // a link fixed to the root: the base takes the wrench
    SpatialVector f = load_pairs(c.f_ext[l]);
    if (!is_zero(link.offset.p)) force_to_parent(f, Shift(d.X0[b].R * link.offset.p));
    store_pairs(d.pA[b], load_pairs(d.pA[b]) - f);
  }
}

constexpr double kMaxDouble = std::numeric_limits<double>::max();

// Why D = S^T IA S cannot be divided by: zero or negative (nothing to move), not finite,
// or so small that 1 / D overflows.
[[noreturn]] void bad_pivot(const Body& b, double D) {
  const std::string where = "joint '" + b.joint_name + "': ";
  std::ostringstream value;
  value << std::setprecision(17) << D;
  if (!(D == D) || D > kMaxDouble)
    throw Error(where + "the articulated inertia about its axis, D = S^T IA S, is not finite (" +
                value.str() + "): the links after it are too heavy or too far away");
  if (!(D > 0)) throw Error(where + "nothing to move (D = S^T IA S = " + value.str() + ")");
  throw Error(where + "the articulated inertia about its axis, D = S^T IA S = " + value.str() +
              ", is too small to invert (1 / D overflows): the links after it are too light");
}

// Step 2 for a prescribed body i: rigidly attached to its parent, moving by S qdd_given
// relative to it (no division: D may even be 0), so the parent adds X^T IA X and
// X^T (pA + U qdd_given). Dinv = 0 and W = 0 make the constraint sweep pass E unreduced and
// add nothing to K.
void prescribed_to_parent(const Model& model, Data& d, int i, const Matrix6& IA, const SpatialVector& U,
                          const SpatialVector& pA, double D, double u, double qdd_given) {
  Data::Workspace& w = d.workspace;
  store_pairs(w.U[i], U);
  w.W[i].setZero();
  w.D[i] = D;
  w.Dinv[i] = 0;
  w.u[i] = u;
  const int p = model.bodies[i].parent;
  if (p < 0) return;
  const Shift shift(d.r[i]);
  add_shifted(IA, shift, d.IA[p]);  // IA_p += X^T IA X
  SpatialVector f = pA + U * qdd_given;  // pA + IA S qdd_given
  force_to_parent(f, shift);
  store_pairs(d.pA[p], load_pairs(d.pA[p]) + f);
}

// Step 2, for i = n-1 .. 0: the articulated-body inertias and bias forces (RBDA 7.3,
// with c = 0: the velocity products are in pA as I kappa). Body i's
// Ia_i = IA_i - U U^T / D and pa_i = pA_i + U u / D are added, shifted by r_i, to its
// parent's IA and pA, as X^T IA X - Us Us^T / D and X^T pA + Us u / D with Us = X^T U.
// A prescribed joint (P: some joint is) passes X^T IA X and X^T pA + Us qdd_given, and
// keeps Dinv = 0, W = 0. X: the case has extra inertia (Case::extra_inertia), added to D
// with the rotor inertia; without it the sweep is the one it was before that input.
template <bool P, bool X>
void inward_sweep(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given, bool rotor) {
  Data::Workspace& w = d.workspace;
  for (int i = model.num_rates() - 1; i >= 0; --i) {
    d.constraint_torques[i] = 0;  // constraint_torques() adds each block's share after the solve
    const Body& b = model.bodies[i];
    const JointSubspace S = body_subspace(model, d, i);
    const Matrix6& IA = d.IA[i];
    // U = IA S,  D = S^T IA S + rotor inertia (+ extra inertia) (RBDA 9.28),  u = tau - S^T pA
    const SpatialVector U = S.inertia_times(IA);
    const SpatialVector pA = load_pairs(d.pA[i]);
    double D;
    if constexpr (X) D = S.project(U) + ((rotor ? b.rotor_inertia : 0.0) + c.extra_inertia[i]);
    else D = S.project(U) + (rotor ? b.rotor_inertia : 0.0);
    const double u = w.tau[i] - S.project(pA);
    if constexpr (P) {
      if (c.prescribed[i]) {
        prescribed_to_parent(model, d, i, IA, U, pA, D, u, qdd_given[i]);
        continue;
      }
    }
    const double Dinv = 1.0 / D;
    if (!(D > 0 && D <= kMaxDouble && Dinv <= kMaxDouble)) bad_pivot(b, D);
    store_pairs(w.U[i], U);
    const Shift shift(d.r[i]);
    SpatialVector Us = U;  // X^T U
    force_to_parent(Us, shift);
    store_pairs(w.W[i], Us * Dinv);  // X^T U / D, for step 4
    w.D[i] = D;
    w.Dinv[i] = Dinv;
    w.u[i] = u;
    const int p = b.parent;
    if (p < 0) continue;
    // Ia = IA - U U^T / D;  pa = pA + U u / D;  the parent adds both, shifted
    add_shifted_minus_rank_one(IA, Us, Dinv, shift, d.IA[p]);  // IA_p += X^T IA X - Us Us^T / D
    SpatialVector pA_shifted = pA;  // X^T pA
    force_to_parent(pA_shifted, shift);
    store_pairs(d.pA[p], load_pairs(d.pA[p]) + (pA_shifted + Us * (u * Dinv)));  // pA_p += X^T pa
  }
}

// Step 4. a~_i = a~_p (shifted), a~ = a - kappa;  qdd_i = (u_i - U_i^T a~_i + ct_i) / D_i;
// a~_i += S qdd_i, with ct_i = -S_i^T E nu the constraint torque (constraint_torques()).
// (A body whose parent is the body before it, as every body of a chain, takes a~_p from
// registers; a body that starts a new branch loads its parent's.)
// Returns the finite probe of the results: a non-finite qdd_i makes every component of
// a~_i non-finite (S qdd_i, with z_i a unit vector: inf or 0 * inf), and a non-finite
// component of a~_p stays non-finite in a~_i (the shift and S qdd_i only add to it), so
// the leaves' a~ are finite exactly when every qdd and a~ is (and with them the
// constraint torques, u and W, which qdd adds); a leaf is a body the next body does not
// hang from. D qdd is probed on its own, and so is a prescribed joint's torque,
// D qdd_given + U^T a~_p (shifted) - u - ct: what tau (with the passive part, which u
// holds) must be for the free joint's equation to give qdd_given.
template <bool P>
double outward_accelerations(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given,
                             const Vector6& a0) {
  Data::Workspace& w = d.workspace;
  const int n = model.num_rates();
  double probe = 0;
  const SpatialVector base = load_pairs(a0);
  SpatialVector a = base;
  for (int i = 0; i < n; ++i) {
    const int p = model.bodies[i].parent;
    if (p != i - 1) a = p < 0 ? base : load_pairs(d.a[p]);
    const double ct = d.constraint_torques[i];
    // U^T a~_i / D = W^T a~_p with W = X^T U / D (from the inward sweep): the product
    // needs only the parent's acceleration, and the shift of a~ runs beside it
    double qdd;
    if constexpr (P) {
      qdd = c.prescribed[i] ? qdd_given[i] : (w.u[i] + ct) * w.Dinv[i] - dot(load_pairs(w.W[i]), a);
    } else {
      qdd = (w.u[i] + ct) * w.Dinv[i] - dot(load_pairs(w.W[i]), a);
    }
    motion_to_child(a, Shift(d.r[i]));
    if constexpr (P) {
      if (c.prescribed[i]) {
        const double torque = w.D[i] * qdd + dot(load_pairs(w.U[i]), a) - w.u[i] - ct;
        d.prescribed_torques[i] = torque;
        probe += torque * 0.0;
      }
    }
    a = a + body_subspace(model, d, i).motion(qdd);
    store_pairs(d.a[i], a);
    d.qdd[i] = qdd;
    d.total_torques[i] = w.D[i] * qdd;
    probe += d.total_torques[i] * 0.0;
    if (i + 1 == n || model.bodies[i + 1].parent != i) probe += finite_probe(a);
  }
  return probe;
}

// Spatial acceleration of link l (Model::links index, -1: the root link) at its origin,
// base orientation, in the sweeps' convention: its body's a~ + kappa moved from the body
// origin to the link origin (`base`, the base's, for a link fixed to the root; with a
// floating base the root link rides on the free joint's last body).
SpatialVector link_acceleration(const Model& model, const Data& d, int l, const SpatialVector& base) {
  const int b = l < 0 ? (model.floating ? kFreeJointBodies - 1 : -1) : model.links[l].body;
  if (b < 0) return base;
  SpatialVector out = load_pairs(d.a[b]) + load_pairs(d.kappa[b]);
  if (l >= 0 && !is_zero(model.links[l].offset.p)) motion_to_child(out, Shift(d.X0[b].R * model.links[l].offset.p));
  return out;
}

// link_accelerations (below) for the links of Data::link_outputs() alone: a link not
// asked for is not visited, so a solve costs nothing for it.
double asked_link_accelerations(const Model& model, Data& d, const Vector6& a0, const Vector6& shift) {
  const SpatialVector s = load_pairs(shift), base = load_pairs(a0);
  double probe = 0;
  for (const int l : d.link_outputs()) {
    const SpatialVector out = link_acceleration(model, d, l, base) + s;
    store_pairs(d.link_accelerations[l + 1], out);
    probe += finite_probe(out);
  }
  return probe;
}

// Spatial acceleration of every link at its origin, base orientation: the body's
// (a~ + kappa), moved from the body origin to the link origin. `shift` = [g; 0] turns the
// sweeps' KDL accelerations into physical ones. Returns their finite probe.
double link_accelerations(const Model& model, Data& d, const Vector6& a0, const Vector6& shift) {
  const SpatialVector s = load_pairs(shift), base = load_pairs(a0);
  // The root link: the base, or with a floating base the free joint's last body.
  const int root = model.floating ? kFreeJointBodies - 1 : -1;
  const SpatialVector root_acceleration = root < 0 ? base : load_pairs(d.a[root]) + load_pairs(d.kappa[root]);
  store_pairs(d.link_accelerations[0], root_acceleration + s);
  double probe = finite_probe(root_acceleration + s);
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    const int b = link.body;
    SpatialVector out = base;
    if (b >= 0) {
      out = load_pairs(d.a[b]) + load_pairs(d.kappa[b]);
      if (!is_zero(link.offset.p)) motion_to_child(out, Shift(d.X0[b].R * link.offset.p));
    }
    out = out + s;
    store_pairs(d.link_accelerations[l + 1], out);
    probe += finite_probe(out);
  }
  return probe;
}

// variable_damping damps the eigen-directions of K in its singular region. Where the
// exact solve nu_e = K^-1 rhs (data.workspace.exact_nu) asks of every joint at most half
// its effort limit,
//   r = max_i |tau_e,i| / effort_i <= 1/2,   tau_e = -sum_k J_k^T alpha_k nu_e,k,
// the motion the holds ask is possible, and the exact solve is kept: nothing is damped.
// From r = 1/2 to 1 the solve moves to the damped nu_d by nu = nu_e + s (nu_d - nu_e),
// s = x^2 (3 - 2 x), x = 2 r - 1 (continuous with its derivative, so the adaptive step
// sees no jump); from r = 1 the damped solve stands. The joints counted are those the
// constraint forces load, but not the floating base's free joint or prescribed joints
// (not driven by efforts); one without an effort limit (Model: 0, not given) gives no
// bound, r = inf. (The joints' speed limits are no test: an undamped arm's free swing
// beside its stretched pose passes them while the exact solve holds it.) With coupled joints, whose solves are superposed, the damped
// solve stands too.
void keep_the_exact_solve_within_efforts(const Model& model, Data& d, const Case& c) {
  if (!model.couplings.empty()) return;
  constraint_force_torques(model, d, c, d.workspace.exact_nu);
  const bool prescribed = c.any_prescribed();
  double r = 0;
  for (int i = 0; i < model.num_rates(); ++i) {
    const double tau = d.joint_torques[i];
    if (tau == 0 || i < model.free_joint_rates() || (prescribed && c.prescribed[i])) continue;
    const double effort = model.bodies[i].limits.effort;
    if (!(effort > 0)) return;
    r = std::max(r, std::abs(tau) / effort);
  }
  if (!(r < 1)) return;
  if (r > 0.5) {
    const double x = 2 * r - 1, s = x * x * (3 - 2 * x);
    d.nu = d.workspace.exact_nu + s * (d.nu - d.workspace.exact_nu);
    return;
  }
  const int nc = static_cast<int>(d.nu.size());
  d.nu = d.workspace.exact_nu;
  d.rank = nc;
  d.dropped.resize(nc, 0);
  d.damped.resize(nc, 0);
  d.damped_sigma.resize(0);
  d.damped_lambda.resize(0);
}

// The variable_damping coupling solve: the columns that may yield give way first where
// the solve must give way (Data::workspace.yielding), the exact solve is kept where the
// joints' efforts allow it, and the yielding columns give way to the efforts. Not inlined:
// the other policies' solve does not carry it.
[[gnu::noinline]] void solve_variably_damped(const Model& model, Data& d, const Case& c, const Options& o) {
  d.workspace.yielding = yielding_columns(c);
  solve_coupling(d, o);
  if (d.workspace.exact_nu.size()) keep_the_exact_solve_within_efforts(model, d, c);
  yield_to_efforts(model, d, c, o);
}

// Steps 1 to 4 on a validated case whose joint inputs j are in the solver's coordinates
// (a floating base's converted); `prescribed`: c.any_prescribed().
void solve(const Model& model, Data& d, const Case& c, const JointInputs& j, const Options& o, bool prescribed) {
  const int nc = (o.effects & kConstraints) ? num_solve_columns(c, d) : 0;
  const bool gravity = o.effects & kGravity;
  // Skipped by themselves when their inputs are zero: the result is identical.
  const bool moving = (o.effects & kVelocityProducts) && any_nonzero(j.qd);
  const bool wrenches = (o.effects & kExternalWrenches) && !c.f_ext.empty();

  joint_forces(model, d, c, j, o, prescribed);
  outward_kinematics(model, d, j.qd.data(), moving);
  if (!c.f_virtual.empty()) {
    virtual_torques(model, d, c);  // added to the ff torques (a prescribed joint ignores both)
    for (int i = 0; i < model.num_rates(); ++i)
      if (!prescribed || !c.prescribed[i]) d.workspace.tau[i] += d.virtual_torques[i];
  } else {
    d.virtual_torques.setZero();
  }
  if (wrenches) add_external_wrenches(model, d, c);

  const bool rotor = o.effects & kRotorInertia;
  if (!c.extra_inertia.size()) {
    if (prescribed) inward_sweep<true, false>(model, d, c, j.qdd_given, rotor);
    else inward_sweep<false, false>(model, d, c, j.qdd_given, rotor);
  } else {
    if (prescribed) inward_sweep<true, true>(model, d, c, j.qdd_given, rotor);
    else inward_sweep<false, true>(model, d, c, j.qdd_given, rotor);
  }
  if (nc) {
    constraint_sources(model, d, c);
    // K must be finite before it is factored (an infinite pivot would pass for a zero).
    const double K_probe = constraint_sweep(model, d, c, j.qdd_given, prescribed);
    if (K_probe != 0) name_the_first_overflow(model, d, c, nc);
  }

  Vector6 a0 = Vector6::Zero();  // base acceleration: [-g; 0]
  if (gravity) a0.head<3>() = -c.gravity;
  d.nu.setZero(nc);
  if (nc) {
    // K nu = E_0^T a_0 + G_0 - beta' (constraint_sweep.hpp), in the scaled columns.
    constraint_rhs(d, c, o, moving);
    if (has_driver_weights(c)) weigh_drivers(model, d, c, j.ff_torques, o, prescribed);
    if (o.policy == SingularityPolicy::VariableDamping) {
      solve_variably_damped(model, d, c, o);
    } else {
      solve_coupling(d, o);
      d.effort_ratio = d.yielded = 0;
    }
  } else {
    d.effort_ratio = 0;
    d.yielded = 0;
    d.workspace.sources.clear();
    d.workspace.free_joint_step = false;
    d.workspace.shared_body = -1;
    d.E.resize(6, 0);
    d.rank = 0;
    d.K.resize(0, 0);
    d.dropped.resize(0, 0);
    d.damped.resize(0, 0);
    d.damped_sigma.resize(0);
    d.damped_lambda.resize(0);
    d.workspace.gave_way = 0;
  }
  // Each step returns the finite probe of what it wrote (0, or NaN if a number is not
  // finite): checked once, at the end, and named only if it fails.
  d.prescribed_torques.setZero();
  constraint_torques(model, d);  // with the scaled columns' nu'
  double probe = prescribed ? outward_accelerations<true>(model, d, c, j.qdd_given, a0)
                            : outward_accelerations<false>(model, d, c, j.qdd_given, a0);
  unscale_constraint_forces(d);

  Vector6 shift = Vector6::Zero();
  if (o.convention == Convention::Physical && gravity) shift.head<3>() = c.gravity;
  // every link's acceleration, or those the Data asks for (Data::set_link_outputs)
  probe += d.all_link_outputs() ? link_accelerations(model, d, a0, shift)
                                : asked_link_accelerations(model, d, a0, shift);
  probe += constraint_wrenches_and_joint_torques(model, d, c, j.ff_torques, prescribed);
  if (probe != 0) name_the_first_overflow(model, d, c, nc);
}

// A floating base's solve: in the free joint's solver coordinates (free_joint.hpp).
void solve_floating(const Model& model, Data& d, const Case& c, const Options& o, bool prescribed) {
  Data::Workspace& w = d.workspace;
  const Matrix3& R = d.X0[kFreeJointBodies - 1].R;  // (the poses are computed before any solve)
  const JointInputs j = free_joint_inputs(R, c, prescribed, w.free_qd, w.free_ff_torques, w.free_qdd_given);
  solve(model, d, c, j, o, prescribed);
  free_joint_results(j.qd, d);
}

// One solve of a validated case, without the couplings. (Inlined into hybrid_dynamics:
// called there, it cost a chain's solve 30 instructions of calls and register saves.)
[[gnu::always_inline]] inline void solve_uncoupled(const Model& model, Data& d, const Case& c, const Options& o) {
  const bool prescribed = c.any_prescribed();
  if (model.floating) return solve_floating(model, d, c, o, prescribed);
  solve(model, d, c, {c.qd, c.ff_torques, c.qdd_given}, o, prescribed);
}

}  // namespace

void hybrid_dynamics(const Model& model, Data& d, const Case& given, const Options& o) {
  const bool poses_given = std::exchange(d.workspace.poses_given, false);  // (cleared even if a check throws)
  validate(model, given, d.constraint_capacity());
  validate(o);
  // Step 1's poses, once for every solve below (the coupled joints' solves are all at this
  // q; a floating base's solver case has the same q).
  if (!poses_given) body_poses(model, given.q, d.X0, d.r);
  if (!model.loops.empty()) set_loop_blocks(model, d);  // held after the case's blocks
  const Case& c = given;
  if (model.couplings.empty()) return solve_uncoupled(model, d, c, o);
  if (d.coupling_forces.size() != static_cast<Eigen::Index>(model.couplings.size()))
    throw Error("the Data was made for a model with another number of coupled joints");
  if (c.coupling_beta.size() && c.coupling_beta.size() != d.coupling_forces.size())
    throw Error("coupling_beta: expected " + std::to_string(d.coupling_forces.size()) +
                " values (one per coupled joint) or none, got " + std::to_string(c.coupling_beta.size()));
  coupled_dynamics(model, d, c, o, solve_uncoupled);
}

}  // namespace achd
