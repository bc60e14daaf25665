#pragma once
// Driver priorities: per constraint column, how far the constraint resists the external
// wrenches and the feed-forward torques (Case::w_fext, Case::w_ff and the blocks' own);
// driver_priorities.cpp derives the law.
#include "achd/data.hpp"
#include "achd/options.hpp"

namespace achd {

// True when some column has a weight other than 1 (else the solve skips all of this).
bool has_driver_weights(const Case& c);

// After constraint_rhs (the EZ_i, U_i, D_i of the sweeps in place): moves each column's
// target by the shares of the drivers that pass through,
// rhs_k -= (1 - w_fext,k) y_f,k + (1 - w_ff,k) y_ff,k.
// ff_torques: the case's, in the solver's coordinates (JointInputs).
void weigh_drivers(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& ff_torques, const Options& o,
                   bool prescribed);

}  // namespace achd
