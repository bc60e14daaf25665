#pragma once
// A second, independent kinematics of a Model for the tests: poses, velocities and
// classical accelerations of every body and link, computed in the base frame with
// point-velocity formulas (not spatial algebra), and link Jacobians from joint axes.
#include <vector>

#include "achd/achd.hpp"

namespace achd::test {

// Motion of one frame in the base frame: origin p, orientation R, velocity v of the
// origin, angular velocity w, and their time derivatives (classical, no gravity).
struct FrameMotion {
  Vector3 p = Vector3::Zero();
  Matrix3 R = Matrix3::Identity();
  Vector3 v = Vector3::Zero(), w = Vector3::Zero();
  Vector3 vdot = Vector3::Zero(), wdot = Vector3::Zero();

  // The spatial acceleration of docs/design.md section 4.1 (derivative of the body
  // twist, base orientation): [vdot - w x v; wdot].
  Vector6 spatial_acceleration() const;
};

// Every link after the root (Model::links order). For revolute joints (axis s through the
// body origin) and prismatic joints:
//   w_i = w_p + s qd,  wdot_i = wdot_p + w_p x s qd + s qdd          (revolute)
//   v_i = v_p + w_p x r,  vdot_i = vdot_p + wdot_p x r + w_p x (w_p x r)
//         + prismatic: s qd in v_i and 2 w_p x s qd + s qdd in vdot_i,  r = p_i - p_p.
std::vector<FrameMotion> reference_motion(const Model& model, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd);

// Jacobian (6 x nj, [linear; angular], base orientation) of link `link` (Model::links
// index) at its origin: column j = [s_j x (p_link - p_j); s_j] (revolute), [s_j; 0]
// (prismatic), 0 for joints not between the root and the link.
Eigen::MatrixXd reference_link_jacobian(const Model& model, const Eigen::VectorXd& q, int link);

}  // namespace achd::test
