#pragma once
// Forward kinematics and the tip Jacobian.
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

// Pose in the root frame of every link after the root (Model::links order).
std::vector<Transform> forward_kinematics(const Model& model, const Eigen::VectorXd& q);

// Spatial velocity of every link after the root: linear velocity of the link origin and
// angular velocity, both in base orientation.
std::vector<Vector6> link_velocities(const Model& model, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& qd);

// Tip Jacobian (6 x nj): rows [linear; angular] of the tip link's origin, base
// orientation, so that [v_tip; w_tip] = J qd.
Eigen::MatrixXd tip_jacobian(const Model& model, const Eigen::VectorXd& q);

// Joint transform of one body at q: parent body frame -> body frame.
Transform joint_transform(const Body& body, double q);

// Every body's pose at q, the one computation of it that the solver, RNEA and the
// kinematics share (so that they see the same rounded geometry): X0_i = X0_parent Xup_i,
// the pose in the base, with R_i = (R_parent R_tree) Rz(q_i) for a revolute joint, and
// r_i = p_i - p_parent in base axes, computed as R_parent p_tree (+ q_i z_i, prismatic)
// rather than as a difference. The vectors must hold num_joints() entries; nothing is
// allocated.
void body_poses(const Model& model, const Eigen::VectorXd& q, std::vector<Transform>& X0,
                std::vector<Vector3>& r);

}  // namespace achd
