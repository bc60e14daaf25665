#pragma once
// The argument check shared by the workspace forms of kinematics.hpp and dynamics.hpp.
#include <Eigen/Core>

#include "achd/kinematics.hpp"

namespace achd {

// Throws achd::Error, naming `function`, when q does not hold num_rates() values or the
// workspace was made for a model with another number of joints.
void check_workspace_call(const char* function, const Model& model, const ChainWorkspace& ws,
                          const Eigen::VectorXd& q);

}  // namespace achd
