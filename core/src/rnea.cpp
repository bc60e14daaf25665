// Recursive Newton-Euler inverse dynamics (RBDA table 5.1), linear-first spatial vectors.
#include <cmath>

#include "achd/dynamics.hpp"
#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "joint.hpp"

namespace achd {

Eigen::VectorXd rnea(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                     const Eigen::VectorXd& qdd, const Vector3& gravity,
                     const std::vector<Vector6>& f_ext, std::uint32_t effects,
                     double friction_velocity) {
  const int n = model.num_joints();
  if (q.size() != n || qd.size() != n || qdd.size() != n)
    throw Error("rnea: q, qd and qdd must have " + std::to_string(n) + " values");
  if (!f_ext.empty() && static_cast<int>(f_ext.size()) != model.num_links())
    throw Error("rnea: f_ext must have " + std::to_string(model.num_links()) + " wrenches");
  std::vector<Transform> Xup(n), X0(n);
  std::vector<Vector6> v(n), f(n);
  std::vector<Vector6> a(n);
  Vector6 a0 = Vector6::Zero();  // gravity as the base accelerating at -g
  if (effects & kGravity) a0.head<3>() = -gravity;
  const bool products = effects & kVelocityProducts;
  // Outward: v_i = X v_p + S qd;  a_i = X a_p + S qdd + v_i x S qd;
  //          f_i = I a_i + v_i x* I v_i
  for (int i = 0; i < n; ++i) {
    const Body& b = model.bodies[i];
    Xup[i] = joint_transform(b, q[i]);
    X0[i] = b.parent < 0 ? Xup[i] : X0[b.parent] * Xup[i];
    const Vector6 vJ = subspace_times(b, qd[i]);
    v[i] = (b.parent < 0 ? Vector6::Zero().eval() : Xup[i].motion_to_child(v[b.parent])) + vJ;
    a[i] = Xup[i].motion_to_child(b.parent < 0 ? a0 : a[b.parent]) + subspace_times(b, qdd[i]);
    if (products) a[i] += cross_motion(v[i], vJ);
    f[i] = b.inertia * a[i];
    if (products) f[i] += cross_force(v[i], b.inertia * v[i]);
  }
  // f_i -= f_ext of its links, moved to the body origin in body coordinates.
  if ((effects & kExternalWrenches) && !f_ext.empty())
    for (int l = 0; l < model.num_links(); ++l) {
      const Link& link = model.links[l];
      if (link.body < 0) continue;
      const Matrix3& R0 = X0[link.body].R;
      const Vector3 fl = R0.transpose() * f_ext[l].head<3>();
      f[link.body].head<3>() -= fl;
      f[link.body].tail<3>() -= R0.transpose() * f_ext[l].tail<3>() + link.offset.p.cross(fl);
    }
  // Inward: tau_i = S^T f_i (+ rotor qdd, + damping qd, + friction);  f_p += X^T f_i
  Eigen::VectorXd tau(n);
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    tau[i] = subspace_dot(b, f[i]);
    if (effects & kRotorInertia) tau[i] += b.rotor_inertia * qdd[i];
    if (effects & kDamping) tau[i] += b.damping * qd[i];
    if (effects & kFriction) tau[i] += b.friction * std::tanh(qd[i] / friction_velocity);
    if (b.parent >= 0) f[b.parent] += Xup[i].force_to_parent(f[i]);
  }
  return tau;
}

}  // namespace achd
