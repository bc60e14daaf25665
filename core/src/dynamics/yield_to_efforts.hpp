#pragma once
// Columns that give way to the joints' efforts (ConstraintBlock::yields), under the
// variable_damping policy (truncate and damped solve every column as asked): a pushed
// direction asks the robot to move, and at the edge of its workspace following it would
// take unbounded torques and speeds. With tau_c = -sum_k J_k^T alpha_k nu_k the torques
// the solve's constraint forces take from the joints and
//   r = max_i |tau_c,i| / effort_i
// over the joints with an effort limit (not the floating base's free joint, not
// prescribed joints; a joint without a limit gives no bound), the solve is kept while
// r <= 1. From r = 1 to 2 it moves to nu_w, the solve with the yielding columns given up
// (nu_Y = 0, the others from K_HH nu_H = rhs_H), by
//   nu = nu + s (nu_w - nu),  s = x^2 (3 - 2 x),  x = r - 1,
// continuous with its derivative, so the adaptive step sees no jump; from r = 2, nu_w
// stands. r is measured on the solve with the yielding columns, so the push is followed
// again as soon as its torques fall back within the efforts. On a model with coupled
// joints, whose solve superposes several (joint_couplings.hpp), nothing yields.
#include <cstdint>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

// The columns that may yield, in nu's order (the case's tip columns, which never yield,
// then each block's; ConstraintBlock::yields): bit j for column j. Kept by hybrid_dynamics
// in Data::workspace.yielding under variable_damping, where they also give way first
// (coupling_solve.cpp).
std::uint64_t yielding_columns(const Case& c);

// After the variable_damping coupling solve (data.nu in the scaled columns): applies the
// rule above and sets data.effort_ratio and data.yielded (both 0 when no column yields).
// No allocation.
void yield_to_efforts(const Model& model, Data& data, const Case& c, const Options& options);

}  // namespace achd
