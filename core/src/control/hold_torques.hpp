#pragma once
// The joint torques that keep a robot at rest at a pose: a feed-forward for the joint PD
// controller (JointControl::hold), so that the PD answers only disturbances.
#include <Eigen/Core>

#include "achd/case.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

// The prescribed_torques of one solve at q = pose, qd = 0, with every actuated joint
// prescribed to qdd = 0 (a floating base's free joint stays free) under `gravity`, the
// wrenches f_ext (empty: none) and the constraint blocks `held` with beta = 0:
// the torques tau that, applied as ff_torques, leave qdd = 0 with the constraint forces
// balancing the rest. Where the held directions over-determine the forces (four feet held
// in x, y, z on a rigid pose: 12 columns, 6 independent), the truncate policy picks the
// least-norm forces. Per joint (Model::num_rates()); the free joint's six are 0.
Eigen::VectorXd hold_torques(const Model& model, const Eigen::VectorXd& pose, const Vector3& gravity,
                             const std::vector<Vector6>& f_ext, const std::vector<ConstraintBlock>& held,
                             const Options& options);

}  // namespace achd
