// The Popov-Vereshchagin solver on a kinematic tree, written plainly to be read beside
// Featherstone's listings (RBDA table 7.1, the articulated-body algorithm; 9.2 for
// prescribed joints) and spatial_v2's HD.m, with Vereshchagin's constraint sweep (1989)
// carried over to a tree as in spatial_v2's PV_tree.m (Sathya's fork) and Pinocchio's pv:
//
//   pass 1, outward (i = 0 .. n-1):  Xup_i, v_i = Xup_i v_p + S_i qd_i,  c_i = v_i x S_i qd_i,
//           IA_i = I_i,  pA_i = v_i x* I_i v_i - f_ext_i
//   pass 2, inward (i = n-1 .. 0):   U_i = IA_i S_i,  D_i = S_i^T U_i (+ rotor + extra inertia),
//           u_i = tau_i - S_i^T pA_i,
//           Ia = IA_i - U_i U_i^T / D_i,  pa = pA_i + Ia c_i + U_i u_i / D_i,
//           IA_p += Xup_i^T Ia Xup_i,  pA_p += Xup_i^T pa
//   constraint sweep, inward:  E_i (6 x m) holds the unit constraint forces alpha of the
//           blocks in body i's subtree, each column moved from its point to body i's origin
//           (the columns of a block start at its link's body; a parent adds its children's:
//           where branches meet, their columns stand side by side in one E). With
//           EZ_i = E_i^T S_i:
//             E_p += Xup_i^T (E_i - U_i EZ_i^T / D_i)
//             K   += EZ_i EZ_i^T / D_i
//             G   += (E_i - U_i EZ_i^T / D_i)^T c_i + EZ_i u_i / D_i
//   at the root:  K nu = E_0^T a_0 + G - beta'   (the constraint accelerations are
//           E_0^T a_0 + G - K nu, and must equal beta')
//   pass 3, outward:  a_i = Xup_i a_p + c_i + S_i qdd_i,
//           qdd_i = (u_i - U_i^T (Xup_i a_p + c_i) - EZ_i^T nu) / D_i.
//
// Why: with the force E_i nu on body i's articulated body (the robot receives -alpha nu at
// each point), the force through joint i is f_i = IA_i a_i + pA_i + E_i nu, and S_i^T f_i =
// tau_i gives qdd_i as in pass 3. Putting that qdd_i back, f_i = Ia (Xup_i a_p) + pa +
// (E_i - U_i EZ_i^T / D_i) nu: the parent sees an articulated inertia, a bias force and
// constraint columns, passed by Xup_i^T. A column's acceleration alpha^T a_point =
// E^T a_body at its body (power is frame-independent); substituting qdd_i the same way
// turns it into E'^T (Xup_i a_p) + [E'^T c_i + EZ_i u_i / D_i] - [EZ_i EZ_i^T / D_i] nu,
// so the sums G and K collect, body by body, what every column's acceleration owes to the
// bias forces and to nu, and E_0^T a_0 what it owes to the base's acceleration.
//
// A prescribed joint (qdd_i given) is no degree of freedom: Ia = IA_i, pa = pA_i +
// IA_i (c_i + S_i qdd_i), E_i passes unreduced, K gets nothing and G gets
// E_i^T (c_i + S_i qdd_i); its torque is S_i^T f_i.
//
// Conventions (as hybrid_dynamics): vectors linear first, [v; w] and [f; n]; each body's
// quantities in its own coordinates about its origin (the joint frame, z along the
// axis, so S_i = e_z angular or linear); gravity as the fictitious base acceleration
// a_0 = [-g; 0], so the sweeps' accelerations are a - [g; 0]; alpha, f_ext and the outputs
// in base axes about the point they name.
#include "achd/pv_reference.hpp"

#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "achd/error.hpp"
#include "free_joint.hpp"

namespace achd {
namespace {

using Matrix6X = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// Featherstone's coordinate transforms for a frame C whose axes are the columns of R and
// whose origin is r, both in P coordinates (RBDA 2.24, rows and columns linear first).
// Motion, P -> C:   ^C X_P   = [ R^T  -R^T [r]x ]      force, P -> C:  ^C X_P^* = [ R^T         0  ]
//                             [ 0     R^T       ]                                 [ -R^T [r]x  R^T ]
// and motion, C -> P: ^P X_C = (^C X_P)^-1 = [ R  [r]x R ; 0  R ]. A force goes from C to P
// by (^C X_P)^T.
Matrix6 motion_transform(const Matrix3& R, const Vector3& r) {
  Matrix6 X = Matrix6::Zero();
  X.topLeftCorner<3, 3>() = R.transpose();
  X.topRightCorner<3, 3>() = -R.transpose() * skew(r);
  X.bottomRightCorner<3, 3>() = R.transpose();
  return X;
}

Matrix6 force_transform(const Matrix3& R, const Vector3& r) {
  Matrix6 X = Matrix6::Zero();
  X.topLeftCorner<3, 3>() = R.transpose();
  X.bottomLeftCorner<3, 3>() = -R.transpose() * skew(r);
  X.bottomRightCorner<3, 3>() = R.transpose();
  return X;
}

Matrix6 inverse_motion_transform(const Matrix3& R, const Vector3& r) {
  Matrix6 X = Matrix6::Zero();
  X.topLeftCorner<3, 3>() = R;
  X.topRightCorner<3, 3>() = skew(r) * R;
  X.bottomRightCorner<3, 3>() = R;
  return X;
}

// v x m = crm(v) m  and  v x* f = crf(v) f = -crm(v)^T f  (RBDA 2.31, 2.32):
//   crm([v; w]) = [ [w]x  [v]x ]      crf([v; w]) = [ [w]x   0   ]
//                 [ 0     [w]x ]                    [ [v]x  [w]x ]
Matrix6 crm(const Vector6& v) {
  Matrix6 X = Matrix6::Zero();
  X.topLeftCorner<3, 3>() = skew(v.tail<3>());
  X.topRightCorner<3, 3>() = skew(v.head<3>());
  X.bottomRightCorner<3, 3>() = skew(v.tail<3>());
  return X;
}

Matrix6 crf(const Vector6& v) { return -crm(v).transpose(); }

// The motion subspace of a joint in its own frame: e_z angular (revolute, continuous) or
// e_z linear (prismatic).
Vector6 motion_subspace(const Body& b) {
  Vector6 S = Vector6::Zero();
  S[b.type == JointType::Prismatic ? 2 : 5] = 1;
  return S;
}

// A frame's pose in the base: axes R and origin p in base coordinates.
struct Pose {
  Matrix3 R = Matrix3::Identity();
  Vector3 p = Vector3::Zero();
};

// Body i's frame in its parent's frame at q_i: the tree transform X_tree, then a turn of
// q_i about z (revolute) or a slide of q_i along z (prismatic).
Pose joint_pose(const Body& b, double q) {
  Pose X{b.X_tree.R, b.X_tree.p};
  if (b.type == JointType::Prismatic) X.p += q * b.X_tree.R.col(2);
  else X.R = b.X_tree.R * Eigen::AngleAxisd(q, Vector3::UnitZ()).toRotationMatrix();
  return X;
}

// One constraint column: alpha (base axes, about `point`, base coordinates) on `body`.
struct Column {
  int body;
  Vector3 point;
  Vector6 alpha;
  double beta;
  bool relative = false;  // alpha^T (a_P - a_Q) = beta: the opposite column at Q on body_b
  int body_b = -1;
  Vector3 point_b = Vector3::Zero();
};

// The solve of a validated case (a floating base's in the solver's coordinates).
ReferenceSolution solve(const Model& model, const Case& c, const Options& o) {
  const int n = model.num_rates();
  const bool gravity = o.effects & kGravity;
  const bool wrenches = (o.effects & kExternalWrenches) && !c.f_ext.empty();
  const bool rotor = o.effects & kRotorInertia;
  // The axial inertia each joint's motor side adds: rotor (per Options::effects) plus
  // Case::extra_inertia.
  auto armature = [&](int i) {
    const double r = rotor ? model.bodies[i].rotor_inertia : 0.0;
    return c.extra_inertia.size() ? r + c.extra_inertia[i] : r;
  };
  const bool physical = o.convention == Convention::Physical;
  const Eigen::VectorXd qd = c.qd.size() ? c.qd : Eigen::VectorXd::Zero(n);
  // Without velocity products the dynamics sees the joints at rest (v = 0, c = 0); the
  // passive torques still see qd.
  const Eigen::VectorXd qd_dyn = (o.effects & kVelocityProducts) ? qd : Eigen::VectorXd::Zero(n);
  auto prescribed = [&](int i) { return c.any_prescribed() && c.prescribed[i]; };

  // tau = ff - damping qd - friction tanh(qd / v_f); a prescribed joint's ff is not read.
  Eigen::VectorXd ff = c.ff_torques.size() ? c.ff_torques : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd tau(n), passive = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const Body& b = model.bodies[i];
    if (o.effects & kDamping) passive[i] -= b.damping * qd[i];
    if (o.effects & kFriction) passive[i] -= b.friction * std::tanh(qd[i] / o.friction_velocity);
    tau[i] = (prescribed(i) ? 0.0 : ff[i]) + passive[i];
  }

  // ---- pass 1, outward: transforms, poses, velocities, bias terms ----
  std::vector<Matrix6> Xup(n), IA(n);
  std::vector<Pose> X0(n);  // body poses in the base, for points given in base coordinates
  std::vector<Vector6> S(n), v(n), cc(n), pA(n);  // cc: the c_i above (c is the case)
  for (int i = 0; i < n; ++i) {
    const Body& b = model.bodies[i];
    const int p = b.parent;
    // A floating base: the free joint's bodies placed from q[0..6] (free_joint.hpp), each
    // relative to the one before; then body i's angle is q[i + 1].
    Pose Xj;
    if (model.floating && i < kFreeJointBodies) {
      Transform F[kFreeJointBodies];
      Vector3 r_unused[kFreeJointBodies];
      free_joint_poses(c.q.data(), F, r_unused);
      const Transform prev = i == 0 ? Transform{} : F[i - 1];
      Xj = Pose{prev.R.transpose() * F[i].R, prev.R.transpose() * (F[i].p - prev.p)};
    } else {
      Xj = joint_pose(b, c.q[model.floating ? i + 1 : i]);
    }
    Xup[i] = motion_transform(Xj.R, Xj.p);  // ^i X_p
    X0[i] = p < 0 ? Xj : Pose{X0[p].R * Xj.R, X0[p].p + X0[p].R * Xj.p};
    S[i] = motion_subspace(b);
    const Vector6 vJ = S[i] * qd_dyn[i];
    v[i] = (p < 0 ? Vector6::Zero().eval() : Vector6(Xup[i] * v[p])) + vJ;  // v_i = Xup v_p + S qd
    cc[i] = crm(v[i]) * vJ;                                                  // c_i = v_i x S qd
    IA[i] = b.inertia;
    pA[i] = crf(v[i]) * (b.inertia * v[i]);                                  // v x* I v
  }
  // f_ext of each link, at its origin in base axes, moved to its body (in body coordinates):
  // the body's frame seen from (base axes, origin at the link) has axes R0 and origin
  // p0 - p_link.
  if (wrenches)
    for (int l = 0; l < model.num_links(); ++l) {
      const Link& link = model.links[l];
      const int b = link.body;
      if (b < 0) continue;  // fixed to the root: the base takes it
      const Vector3 p_link = X0[b].p + X0[b].R * link.offset.p;
      pA[b] -= force_transform(X0[b].R, X0[b].p - p_link) * c.f_ext[l];
    }

  // ---- pass 2, inward: articulated inertias and bias forces ----
  std::vector<Vector6> U(n);
  std::vector<double> D(n), u(n);
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    U[i] = IA[i] * S[i];
    D[i] = S[i].dot(U[i]) + armature(i);
    u[i] = tau[i] - S[i].dot(pA[i]);
    Matrix6 Ia;
    Vector6 pa;
    if (prescribed(i)) {
      Ia = IA[i];
      pa = pA[i] + IA[i] * (cc[i] + S[i] * c.qdd_given[i]);
    } else {
      if (!(D[i] > 0) || !std::isfinite(1 / D[i]))
        throw Error("pv_reference: joint '" + b.joint_name + "': D = S^T IA S is not positive");
      Ia = IA[i] - U[i] * U[i].transpose() / D[i];
      pa = pA[i] + Ia * cc[i] + U[i] * (u[i] / D[i]);
    }
    if (b.parent >= 0) {
      IA[b.parent] += Xup[i].transpose() * Ia * Xup[i];
      pA[b.parent] += Xup[i].transpose() * pa;
    }
  }

  // ---- the constraint columns: the tip's, then each block's ----
  std::vector<Column> columns;
  if (o.effects & kConstraints) {
    // a point of a link in base coordinates
    auto at = [&](int link, const Vector3& point) {
      const Link& l = model.links[link];
      const Pose X = l.body < 0 ? Pose{} : X0[l.body];
      return Vector3(X.p + X.R * (l.offset.p + l.offset.R * point));
    };
    auto add_block = [&](int link, const Vector3& point, const ConstraintMatrix& alpha,
                         const ConstraintVector& beta, int link_b, const Vector3& point_b) {
      for (Eigen::Index k = 0; k < alpha.cols(); ++k) {
        Column col{model.links[link].body, at(link, point), alpha.col(k), beta[k]};
        if (link_b >= 0) {
          col.relative = true;
          col.body_b = model.links[link_b].body;
          col.point_b = at(link_b, point_b);
        }
        columns.push_back(col);
      }
    };
    if (c.alpha.cols()) add_block(model.num_links() - 1, Vector3::Zero(), c.alpha, c.beta, -1, Vector3::Zero());
    for (const ConstraintBlock& b : c.constraints) add_block(b.link, b.point, b.alpha, b.beta, b.link_b, b.point_b);
  }
  const int m = static_cast<int>(columns.size());

  // E0_i: the columns on body i itself, moved from their points to its origin; E_i: E0_i
  // plus the children's reduced columns (filled by the sweep). Columns of blocks outside
  // the subtree stay zero. E_base collects the columns at the base's origin. A relative
  // column stands at both of its points: alpha at P, -alpha at Q.
  std::vector<Matrix6X> E0(n, Matrix6X::Zero(6, m));
  Matrix6X E_base = Matrix6X::Zero(6, m);
  auto place = [&](int j, int body, const Vector3& point, const Vector6& alpha) {
    if (body < 0)  // a link fixed to the root: the column is on the base
      E_base.col(j) += force_transform(Matrix3::Identity(), -point) * alpha;
    else
      E0[body].col(j) += force_transform(X0[body].R, X0[body].p - point) * alpha;
  };
  for (int j = 0; j < m; ++j) {
    const Column& col = columns[j];
    place(j, col.body, col.point, col.alpha);
    if (col.relative) place(j, col.body_b, col.point_b, -col.alpha);
  }

  // ---- the constraint sweep, inward (nothing to sweep without columns) ----
  std::vector<Matrix6X> E = E0;
  std::vector<Eigen::VectorXd> EZ(n);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd G = Eigen::VectorXd::Zero(m);
  for (int i = n - 1; m > 0 && i >= 0; --i) {
    EZ[i] = E[i].transpose() * S[i];  // EZ_i = E_i^T S_i
    Matrix6X E_reduced;               // what the parent sees: E_i - U_i EZ_i^T / D_i
    if (prescribed(i)) {
      E_reduced = E[i];
      G += E[i].transpose() * (cc[i] + S[i] * c.qdd_given[i]);
    } else {
      E_reduced = E[i] - U[i] * EZ[i].transpose() / D[i];
      K += EZ[i] * EZ[i].transpose() / D[i];
      G += E_reduced.transpose() * cc[i] + EZ[i] * (u[i] / D[i]);
    }
    const int p = model.bodies[i].parent;
    (p >= 0 ? E[p] : E_base) += Xup[i].transpose() * E_reduced;
  }

  // ---- at the root: K nu = E_0^T a_0 + G - beta' ----
  // beta' is what the columns constrain in the sweeps' accelerations a - [g; 0]:
  // beta - alpha_lin^T g in the physical convention, beta itself in KDL's.
  Vector6 a0 = Vector6::Zero();
  if (gravity) a0.head<3>() = -c.gravity;
  Eigen::VectorXd rhs = G;
  for (int j = 0; j < m; ++j) {
    rhs[j] += E_base.col(j).dot(a0);
    double beta = columns[j].beta;
    // (a relative column sees g at both points: it cancels)
    if (gravity && physical && !columns[j].relative) beta -= columns[j].alpha.head<3>().dot(c.gravity);
    rhs[j] -= beta;
  }
  // nu = K^+ rhs, the pseudo-inverse by K's eigen-decomposition (K is symmetric positive
  // semi-definite), eigenvalues at or below the tolerance dropped.
  ReferenceSolution out;
  out.nu = Eigen::VectorXd::Zero(m);
  if (m) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
    const Eigen::VectorXd sigma = eig.eigenvalues().cwiseMax(0.0);
    const double threshold = o.absolute_tolerance ? o.tolerance : o.tolerance * sigma.maxCoeff();
    for (int k = 0; k < m; ++k) {
      if (!(sigma[k] > threshold)) continue;
      ++out.rank;
      out.nu += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(rhs) / sigma[k]);
    }
  }

  // The constraint forces on each articulated body, E_i nu, and on each body itself,
  // E0_i nu (the wrenches alpha nu at its points, moved to its origin).
  std::vector<Vector6> E_nu(n, Vector6::Zero()), E0_nu(n, Vector6::Zero());
  for (int i = 0; m > 0 && i < n; ++i) {
    E_nu[i] = E[i] * out.nu;
    E0_nu[i] = E0[i] * out.nu;
  }

  // ---- pass 3, outward: accelerations ----
  out.qdd.resize(n);
  out.prescribed_torques = Eigen::VectorXd::Zero(n);
  std::vector<Vector6> a(n);
  for (int i = 0; i < n; ++i) {
    const int p = model.bodies[i].parent;
    const Vector6 a_in = Xup[i] * (p < 0 ? a0 : a[p]) + cc[i];  // a_i with qdd_i = 0
    if (prescribed(i)) {
      out.qdd[i] = c.qdd_given[i];
      a[i] = a_in + S[i] * out.qdd[i];
      // S^T f_i, f_i = IA_i a_i + pA_i + E_i nu (+ armature qdd), less the passive torques
      out.prescribed_torques[i] = S[i].dot(IA[i] * a[i] + pA[i] + E_nu[i]) + armature(i) * out.qdd[i] - passive[i];
    } else {
      // EZ_i^T nu = S_i^T E_i nu
      out.qdd[i] = (u[i] - U[i].dot(a_in) - S[i].dot(E_nu[i])) / D[i];
      a[i] = a_in + S[i] * out.qdd[i];
    }
  }

  // ---- outputs in base axes ----
  // Link accelerations at each link origin: a_body seen from (base axes, origin at the
  // link), plus [g; 0] in the physical convention (a - [g; 0] + [g; 0]).
  Vector6 shift = Vector6::Zero();
  if (gravity && physical) shift.head<3>() = c.gravity;
  out.link_accelerations.assign(model.num_links() + 1, a0 + shift);
  if (model.floating) {  // the root link rides on the free joint's last body
    const int b = kFreeJointBodies - 1;
    out.link_accelerations[0] = inverse_motion_transform(X0[b].R, Vector3::Zero()) * a[b] + shift;
  }
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    const int b = link.body;
    if (b < 0) continue;
    const Vector3 p_link = X0[b].p + X0[b].R * link.offset.p;
    out.link_accelerations[l + 1] = inverse_motion_transform(X0[b].R, X0[b].p - p_link) * a[b] + shift;
  }
  // The wrenches alpha nu: the tip's, and each block's.
  int j = 0;
  for (; j < c.alpha.cols() && j < m; ++j) out.constraint_wrench += columns[j].alpha * out.nu[j];
  for (const ConstraintBlock& b : c.constraints) {
    Vector6 w = Vector6::Zero();
    for (Eigen::Index k = 0; k < b.alpha.cols() && j < m; ++k, ++j) w += columns[j].alpha * out.nu[j];
    out.constraint_wrenches.push_back(w);
  }
  // joint_torques = ff - sum_k J_k^T alpha_k nu_k: the wrenches E0_i nu on each body, rolled
  // inward; joint i takes S_i^T of the wrenches of its subtree.
  out.joint_torques = ff;
  for (int i = 0; i < n; ++i)
    if (prescribed(i)) out.joint_torques[i] = out.prescribed_torques[i];
  std::vector<Vector6> F = E0_nu;
  for (int i = n - 1; i >= 0; --i) {
    out.joint_torques[i] -= S[i].dot(F[i]);
    const int p = model.bodies[i].parent;
    if (p >= 0) F[p] += Xup[i].transpose() * F[i];
  }

  bool finite = out.qdd.allFinite() && out.nu.allFinite() && out.joint_torques.allFinite() &&
                out.prescribed_torques.allFinite() && out.constraint_wrench.allFinite();
  for (const Vector6& x : out.link_accelerations) finite = finite && x.allFinite();
  for (const Vector6& x : out.constraint_wrenches) finite = finite && x.allFinite();
  if (!finite) throw Error("pv_reference: a result is not finite (the inputs overflow)");
  return out;
}

}  // namespace

ReferenceSolution pv_reference(const Model& model, const Case& c, const Options& o) {
  validate(model, c);
  validate(o);
  if (o.policy != SingularityPolicy::Truncate)
    throw Error("pv_reference: only the truncate singularity policy is implemented");
  if (!model.couplings.empty())
    throw Error("pv_reference: coupled joints (Model::couplings) are not implemented; load with the mimic option "
                "'independent'");
  // Driver weights of 1 are the plain solve; below 1 they split the right-hand side per
  // driver (driver_priorities.cpp), which the reference does not.
  const auto all_ones = [](const ConstraintVector& w) { return (w.array() == 1.0).all(); };
  bool weighted = !all_ones(c.w_fext) || !all_ones(c.w_ff);
  for (const ConstraintBlock& b : c.constraints) weighted = weighted || !all_ones(b.w_fext) || !all_ones(b.w_ff);
  if (weighted)
    throw Error("pv_reference: driver weights below 1 (w_fext, w_ff) are not implemented");
  for (const Vector6& f : c.f_virtual)
    if (!f.isZero(0)) throw Error("pv_reference: virtual wrenches (f_virtual) are not implemented");
  if (!model.floating) return solve(model, c, o);
  // A floating base: solved in the free joint's solver coordinates, results converted back.
  Case s = c;  // its joint inputs in the solver's coordinates, all else as given
  const bool prescribed = c.any_prescribed();
  s.qd.resize(model.num_rates());
  s.ff_torques.resize(model.num_rates());
  if (prescribed) s.qdd_given.resize(model.num_rates());
  free_joint_inputs(free_joint_rotation(c.q.data() + 3), c, prescribed, s.qd, s.ff_torques, s.qdd_given);
  ReferenceSolution out = solve(model, s, o);
  const Matrix3 R = free_joint_rotation(c.q.data() + 3);
  free_joint_accelerations_to_public(R, s.qd.data(), out.qdd.data());
  free_joint_torques_to_public(R, out.joint_torques.data(), out.joint_torques.data());
  free_joint_torques_to_public(R, out.prescribed_torques.data(), out.prescribed_torques.data());
  return out;
}

}  // namespace achd
