#include "achd/kinematics.hpp"

#include "joint.hpp"

namespace achd {

Transform joint_transform(const Body& b, double q) {
  // Revolute: rotate the joint frame by q about the axis; prismatic: slide along it.
  Transform X = b.X_tree;
  if (is_rotational(b)) X.R = b.X_tree.R * Eigen::AngleAxisd(q, b.axis).toRotationMatrix();
  else X.p = b.X_tree.p + b.X_tree.R * (b.axis * q);
  return X;
}

namespace {

// Poses of the bodies in the base frame: X0_i = X0_parent * Xj(q_i).
std::vector<Transform> body_poses(const Model& model, const Eigen::VectorXd& q) {
  std::vector<Transform> X0(model.num_joints());
  for (int i = 0; i < model.num_joints(); ++i) {
    const Transform Xj = joint_transform(model.bodies[i], q[i]);
    const int p = model.bodies[i].parent;
    X0[i] = p < 0 ? Xj : X0[p] * Xj;
  }
  return X0;
}

}  // namespace

std::vector<Transform> forward_kinematics(const Model& model, const Eigen::VectorXd& q) {
  const std::vector<Transform> X0 = body_poses(model, q);
  std::vector<Transform> poses;
  poses.reserve(model.num_links());
  for (const Link& l : model.links) poses.push_back(l.body < 0 ? l.offset : X0[l.body] * l.offset);
  return poses;
}

std::vector<Vector6> link_velocities(const Model& model, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& qd) {
  const std::vector<Transform> X0 = body_poses(model, q);
  // Body velocity in base orientation, at the body origin: v_i = v_p (moved) + S qd.
  std::vector<Vector6> vb(model.num_joints());
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    Vector6 vi = Vector6::Zero();
    if (b.parent >= 0) {
      vi = vb[b.parent];
      // move the reference point from the parent's origin to this body's origin
      vi.head<3>() += vi.tail<3>().cross(X0[i].p - X0[b.parent].p);
    }
    const Vector6 sj = subspace_times(b, qd[i]);
    vi.head<3>() += X0[i].R * sj.head<3>();
    vi.tail<3>() += X0[i].R * sj.tail<3>();
    vb[i] = vi;
  }
  std::vector<Vector6> out;
  out.reserve(model.num_links());
  for (const Link& l : model.links) {
    if (l.body < 0) {
      out.push_back(Vector6::Zero());
      continue;
    }
    Vector6 vl = vb[l.body];
    vl.head<3>() += vl.tail<3>().cross(X0[l.body].R * l.offset.p);
    out.push_back(vl);
  }
  return out;
}

Eigen::MatrixXd tip_jacobian(const Model& model, const Eigen::VectorXd& q) {
  const std::vector<Transform> X0 = body_poses(model, q);
  const Link& tip = model.tip();
  const Vector3 p_tip = tip.body < 0 ? tip.offset.p : (X0[tip.body] * tip.offset).p;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, model.num_joints());
  // Column i: joint i's unit motion seen at the tip. Revolute: [z x (p_tip - p_i); z];
  // prismatic: [z; 0], with z the axis in base orientation.
  for (int i = 0; i <= tip.body; ++i) {
    const Body& b = model.bodies[i];
    const Vector3 z = X0[i].R * b.axis;
    if (is_rotational(b)) {
      J.col(i).head<3>() = z.cross(p_tip - X0[i].p);
      J.col(i).tail<3>() = z;
    } else {
      J.col(i).head<3>() = z;
    }
  }
  return J;
}

}  // namespace achd
