#include "reference_kinematics.hpp"

#include <Eigen/Geometry>

namespace achd::test {
namespace {

bool is_prismatic(const Body& b) { return b.type == JointType::Prismatic; }

// Every body's frame motion, root to tip: X_i = X_p X_tree,i X_joint(q_i).
std::vector<FrameMotion> body_motion(const Model& model, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) {
  std::vector<FrameMotion> m(model.num_rates());
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    const FrameMotion parent = b.parent < 0 ? FrameMotion() : m[b.parent];
    FrameMotion& f = m[i];
    const Matrix3 R_tree = parent.R * b.X_tree.R;
    const Vector3 s = R_tree.col(2);  // the joint axis (the body frame's z) in the base frame
    f.p = parent.p + parent.R * b.X_tree.p;
    if (is_prismatic(b)) {
      f.R = R_tree;
      f.p += s * q[i];
    } else {
      f.R = R_tree * Eigen::AngleAxisd(q[i], Vector3::UnitZ()).toRotationMatrix();
    }
    const Vector3 r = f.p - parent.p;
    f.w = parent.w;
    f.wdot = parent.wdot;
    f.v = parent.v + parent.w.cross(r);
    f.vdot = parent.vdot + parent.wdot.cross(r) + parent.w.cross(parent.w.cross(r));
    if (is_prismatic(b)) {
      f.v += s * qd[i];
      f.vdot += 2 * parent.w.cross(s) * qd[i] + s * qdd[i];
    } else {
      f.w += s * qd[i];
      f.wdot += parent.w.cross(s) * qd[i] + s * qdd[i];
    }
  }
  return m;
}

// A frame rigidly attached to `body` at `offset` (body coordinates).
FrameMotion attached(const FrameMotion& body, const Transform& offset) {
  FrameMotion f = body;
  const Vector3 r = body.R * offset.p;
  f.p = body.p + r;
  f.R = body.R * offset.R;
  f.v = body.v + body.w.cross(r);
  f.vdot = body.vdot + body.wdot.cross(r) + body.w.cross(body.w.cross(r));
  return f;
}

}  // namespace

Vector6 FrameMotion::spatial_acceleration() const {
  Vector6 a;
  a << vdot - w.cross(v), wdot;
  return a;
}

std::vector<FrameMotion> reference_motion(const Model& model, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) {
  const std::vector<FrameMotion> bodies = body_motion(model, q, qd, qdd);
  std::vector<FrameMotion> links;
  for (const Link& l : model.links)
    links.push_back(attached(l.body < 0 ? FrameMotion() : bodies[l.body], l.offset));
  return links;
}

Eigen::MatrixXd reference_link_jacobian(const Model& model, const Eigen::VectorXd& q, int link) {
  const int n = model.num_rates();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const std::vector<FrameMotion> bodies = body_motion(model, q, zero, zero);
  const Link& l = model.links[link];
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, n);
  if (l.body < 0) return J;
  const Vector3 p = attached(bodies[l.body], l.offset).p;
  for (int j = l.body; j >= 0; j = model.bodies[j].parent) {
    const Body& b = model.bodies[j];
    const Matrix3 R_tree = (b.parent < 0 ? Matrix3::Identity() : bodies[b.parent].R) * b.X_tree.R;
    const Vector3 s = R_tree.col(2);
    if (is_prismatic(b)) J.col(j).head<3>() = s;
    else J.col(j) << s.cross(p - bodies[j].p), s;
  }
  return J;
}

}  // namespace achd::test
