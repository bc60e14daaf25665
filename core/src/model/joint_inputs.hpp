#pragma once
// The joint vectors of a case that a solve reads, in the solver's coordinates: the case's
// own (a fixed base), or with a floating base copies whose free-joint entries are converted
// (free_joint_inputs, free_joint.hpp). Everything else a solve reads from the case itself,
// so a floating base's solve copies nothing but these.
#include <Eigen/Core>

namespace achd {

struct JointInputs {
  const Eigen::VectorXd& qd;          // empty = zero
  const Eigen::VectorXd& ff_torques;  // empty = zero
  const Eigen::VectorXd& qdd_given;   // read only where Case::prescribed says so
};

}  // namespace achd
