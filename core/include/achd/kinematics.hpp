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

}  // namespace achd
