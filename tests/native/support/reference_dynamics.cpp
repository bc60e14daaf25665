#include "reference_dynamics.hpp"

#include <cmath>

namespace achd::test {
namespace {

Matrix3 cross_matrix(const Vector3& p) {
  Matrix3 s;
  s << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
  return s;
}

// The motion transform from frame P to frame C, where C has axes E (columns, in P) and
// origin p (in P): [v_C; w_C] = X [v_P; w_P] with w_C = E^T w, v_C = E^T (v - p x w).
Matrix6 motion_transform(const Matrix3& E, const Vector3& p) {
  Matrix6 X = Matrix6::Zero();
  X.topLeftCorner<3, 3>() = E.transpose();
  X.topRightCorner<3, 3>() = -E.transpose() * cross_matrix(p);
  X.bottomRightCorner<3, 3>() = E.transpose();
  return X;
}

// The force transform from P to C, X^-T: f_C = E^T f, n_C = E^T (n - p x f).
Matrix6 force_transform(const Matrix3& E, const Vector3& p) {
  Matrix6 X = Matrix6::Zero();
  X.topLeftCorner<3, 3>() = E.transpose();
  X.bottomLeftCorner<3, 3>() = -E.transpose() * cross_matrix(p);
  X.bottomRightCorner<3, 3>() = E.transpose();
  return X;
}

// crm(m) = m x (motion), linear first: [[w]x [v]x; 0 [w]x].  crf(m) = -crm(m)^T.
Matrix6 crm(const Vector6& m) {
  Matrix6 c = Matrix6::Zero();
  c.topLeftCorner<3, 3>() = cross_matrix(m.tail<3>());
  c.topRightCorner<3, 3>() = cross_matrix(m.head<3>());
  c.bottomRightCorner<3, 3>() = cross_matrix(m.tail<3>());
  return c;
}
Matrix6 crf(const Vector6& m) { return -crm(m).transpose(); }

// S: the body frame's z axis is the joint axis (model.hpp), angular for revolute and
// continuous joints, linear for prismatic ones.
Vector6 motion_subspace(const Body& b) {
  Vector6 S = Vector6::Zero();
  S[b.type == JointType::Prismatic ? 2 : 5] = 1;
  return S;
}

// XJ(q): the joint's own motion about or along z, as a transform of the frame.
Matrix6 joint_motion_transform(const Body& b, double q) {
  if (b.type == JointType::Prismatic) return motion_transform(Matrix3::Identity(), Vector3(0, 0, q));
  Matrix3 Rz;
  Rz << std::cos(q), -std::sin(q), 0, std::sin(q), std::cos(q), 0, 0, 0, 1;
  return motion_transform(Rz, Vector3::Zero());
}

// Xup_i = XJ(q_i) XT_i, XT_i from X_tree (parent body frame -> body frame at q = 0).
std::vector<Matrix6> parent_to_body(const Model& model, const Eigen::VectorXd& q) {
  std::vector<Matrix6> Xup;
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    Xup.push_back(joint_motion_transform(b, q[i]) * motion_transform(b.X_tree.R, b.X_tree.p));
  }
  return Xup;
}

// A frame's pose in the base: axes E and origin p, composed outward from X_tree and q
// (the pose form of Xup, for moving the caller's base-oriented wrenches into bodies).
struct Pose {
  Matrix3 E = Matrix3::Identity();
  Vector3 p = Vector3::Zero();
  Pose then(const Matrix3& E_rel, const Vector3& p_rel) const { return {E * E_rel, p + E * p_rel}; }
};

std::vector<Pose> body_poses_in_base(const Model& model, const Eigen::VectorXd& q) {
  std::vector<Pose> pose;
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    const Pose parent = b.parent < 0 ? Pose{} : pose[b.parent];
    const Pose at_zero = parent.then(b.X_tree.R, b.X_tree.p);
    if (b.type == JointType::Prismatic) {
      pose.push_back(at_zero.then(Matrix3::Identity(), Vector3(0, 0, q[i])));
    } else {
      Matrix3 Rz;
      Rz << std::cos(q[i]), -std::sin(q[i]), 0, std::sin(q[i]), std::cos(q[i]), 0, 0, 0, 1;
      pose.push_back(at_zero.then(Rz, Vector3::Zero()));
    }
  }
  return pose;
}

}  // namespace

Eigen::VectorXd reference_rnea(const Model& model, const Eigen::VectorXd& q,
                               const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                               const Vector3& gravity, const std::vector<Vector6>& f_ext,
                               std::uint32_t effects, double friction_velocity) {
  const int n = model.num_rates();
  const std::vector<Matrix6> Xup = parent_to_body(model, q);
  const bool products = effects & kVelocityProducts;
  // a_0 = -a_g: gravity as the base accelerating upward.
  Vector6 a0 = Vector6::Zero();
  if (effects & kGravity) a0.head<3>() = -gravity;
  std::vector<Vector6> v(n), a(n), f(n);
  for (int i = 0; i < n; ++i) {
    const Body& b = model.bodies[i];
    const Vector6 S = motion_subspace(b);
    const Vector6 vp = b.parent < 0 ? Vector6::Zero().eval() : v[b.parent];
    const Vector6 ap = b.parent < 0 ? a0 : a[b.parent];
    v[i] = Xup[i] * vp + S * qd[i];
    a[i] = Xup[i] * ap + S * qdd[i];
    if (products) a[i] += crm(v[i]) * S * qd[i];
    f[i] = b.inertia * a[i];
    if (products) f[i] += crf(v[i]) * b.inertia * v[i];
  }
  // External wrenches: given in base orientation about each link's origin; moved to the
  // base origin ([f; n + p_link x f]), then into the body by the base -> body force
  // transform.
  if ((effects & kExternalWrenches) && !f_ext.empty()) {
    const std::vector<Pose> pose = body_poses_in_base(model, q);
    for (int l = 0; l < model.num_links(); ++l) {
      const Link& link = model.links[l];
      if (link.body < 0) continue;
      const Vector3 p_link = pose[link.body].then(link.offset.R, link.offset.p).p;
      Vector6 at_base = f_ext[l];
      at_base.tail<3>() += p_link.cross(f_ext[l].head<3>());
      f[link.body] -= force_transform(pose[link.body].E, pose[link.body].p) * at_base;
    }
  }
  Eigen::VectorXd tau(n);
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    tau[i] = motion_subspace(b).dot(f[i]);
    if (effects & kRotorInertia) tau[i] += b.rotor_inertia * qdd[i];
    if (effects & kDamping) tau[i] += b.damping * qd[i];
    if (effects & kFriction) tau[i] += b.friction * std::tanh(qd[i] / friction_velocity);
    if (b.parent >= 0) f[b.parent] += Xup[i].transpose() * f[i];
  }
  return tau;
}

Eigen::MatrixXd reference_crba(const Model& model, const Eigen::VectorXd& q, bool rotor_inertia) {
  const int n = model.num_rates();
  const std::vector<Matrix6> Xup = parent_to_body(model, q);
  std::vector<Matrix6> Ic(n);
  for (int i = 0; i < n; ++i) Ic[i] = model.bodies[i].inertia;
  for (int i = n - 1; i >= 0; --i)
    if (model.bodies[i].parent >= 0) Ic[model.bodies[i].parent] += Xup[i].transpose() * Ic[i] * Xup[i];
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    Vector6 F = Ic[i] * motion_subspace(model.bodies[i]);
    H(i, i) = motion_subspace(model.bodies[i]).dot(F) + (rotor_inertia ? model.bodies[i].rotor_inertia : 0.0);
    for (int j = i; model.bodies[j].parent >= 0;) {
      F = Xup[j].transpose() * F;
      j = model.bodies[j].parent;
      H(i, j) = H(j, i) = motion_subspace(model.bodies[j]).dot(F);
    }
  }
  return H;
}

}  // namespace achd::test
