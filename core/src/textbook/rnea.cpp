// Recursive Newton-Euler inverse dynamics (RBDA table 5.1), linear-first spatial vectors.
#include <cmath>

#include "achd/dynamics.hpp"
#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "check_workspace.hpp"
#include "free_joint.hpp"
#include "joint.hpp"
#include "spatial_pairs.hpp"

namespace achd {

void rnea(const Model& model, ChainWorkspace& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
          const Eigen::VectorXd& qdd, const Vector3& gravity, const std::vector<Vector6>& f_ext,
          const Options& options, Eigen::VectorXd& tau) {
  validate(options);
  const std::uint32_t effects = options.effects;
  const int n = model.num_rates();
  check_workspace_call("rnea", model, ws, q);
  if (qd.size() != n || qdd.size() != n)
    throw Error("rnea: q, qd and qdd must have " + std::to_string(n) + " values");
  if (!f_ext.empty() && static_cast<int>(f_ext.size()) != model.num_links())
    throw Error("rnea: f_ext must have " + std::to_string(model.num_links()) + " wrenches");
  // The solver's representation (hybrid_dynamics.cpp): base axes, body i's vectors about
  // its origin, passed between bodies by the shift r_i; the same poses as the solver.
  std::vector<Transform>& X0 = ws.X0;
  std::vector<Vector3>& r = ws.r;
  std::vector<Vector6>& v = ws.v;
  std::vector<Vector6>& a = ws.a;
  std::vector<Vector6>& f = ws.f;
  body_poses(model, q, X0, r);
  // A floating base's rates and accelerations in the solver's form (free_joint.hpp).
  double free_qd[kFreeJointBodies], free_qdd[kFreeJointBodies];
  const bool floating = model.floating;
  if (floating) {
    const Matrix3& R = X0[kFreeJointBodies - 1].R;
    free_joint_rates(R, qd.data(), free_qd);
    free_joint_accelerations_to_solver(R, free_qd, qdd.data(), free_qdd);
  }
  auto rate = [&](int i) { return floating && i < kFreeJointBodies ? free_qd[i] : qd[i]; };
  auto acceleration = [&](int i) { return floating && i < kFreeJointBodies ? free_qdd[i] : qdd[i]; };
  Vector6 a0 = Vector6::Zero();  // gravity as the base accelerating at -g
  if (effects & kGravity) a0.head<3>() = -gravity;
  const bool products = effects & kVelocityProducts;
  // Outward: v_i = v_p (shifted) + S qd;  a_i = a_p (shifted) + S qdd + v_p (shifted) x S qd;
  //          f_i = I a_i + v_i x* I v_i   (S = the body's z axis, angular or linear)
  Matrix6 I;
  for (int i = 0; i < n; ++i) {
    const Body& b = model.bodies[i];
    const Vector3 z = X0[i].R.col(2);
    Vector6 S = Vector6::Zero();
    if (is_rotational(b)) S.tail<3>() = z;
    else S.head<3>() = z;
    const Vector6 vp = b.parent < 0 ? Vector6::Zero().eval() : motion_shift(v[b.parent], r[i]);
    v[i] = vp + S * rate(i);
    a[i] = motion_shift(b.parent < 0 ? a0 : a[b.parent], r[i]) + S * acceleration(i);
    if (products) a[i] += cross_motion(vp, S * rate(i));
    set_rigid_inertia(I, X0[i].R, b.inertia);
    store_pairs(f[i], times(I, a[i]));
    if (products) {
      Vector6 Iv;
      store_pairs(Iv, times(I, v[i]));
      f[i] += cross_force(v[i], Iv);
    }
  }
  // f_i -= f_ext of its links, moved from the link origin to the body origin.
  if ((effects & kExternalWrenches) && !f_ext.empty())
    for (int l = 0; l < model.num_links(); ++l) {
      const Link& link = model.links[l];
      if (link.body < 0) continue;
      f[link.body] -= force_shift(f_ext[l], X0[link.body].R * link.offset.p);
    }
  // Inward: tau_i = S^T f_i (+ rotor qdd, + damping qd, + friction);  f_p += f_i (shifted)
  tau.resize(n);
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    const Vector3 z = X0[i].R.col(2);
    tau[i] = is_rotational(b) ? z.dot(f[i].tail<3>()) : z.dot(f[i].head<3>());
    if (effects & kRotorInertia) tau[i] += b.rotor_inertia * qdd[i];
    if (effects & kDamping) tau[i] += b.damping * qd[i];
    if (effects & kFriction) tau[i] += b.friction * std::tanh(qd[i] / options.friction_velocity);
    if (b.parent >= 0) f[b.parent] += force_shift(f[i], r[i]);
  }
  if (floating) free_joint_torques_to_public(X0[kFreeJointBodies - 1].R, tau.data(), tau.data());
  // Finite inputs can still overflow (gravity of 1e308 times a mass): a named error, never
  // an Inf or NaN handed on.
  if (!tau.allFinite()) throw Error("rnea: the torques are not finite (the inputs overflow)");
}

Eigen::VectorXd rnea(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                     const Eigen::VectorXd& qdd, const Vector3& gravity, const std::vector<Vector6>& f_ext,
                     const Options& options) {
  ChainWorkspace ws(model);
  Eigen::VectorXd tau(model.num_rates());
  rnea(model, ws, q, qd, qdd, gravity, f_ext, options, tau);
  return tau;
}

}  // namespace achd
