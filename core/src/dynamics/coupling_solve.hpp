#pragma once
// The constraint solve at the base: K nu = rhs for the nc x nc coupling matrix
// K = -M_0 (symmetric positive semi-definite), by the singularity policy of Options.
#include "achd/data.hpp"
#include "achd/options.hpp"

namespace achd {

// Writes data.nu, data.rank, data.dropped (and for variable_damping data.damped*) from
// data.K and data.workspace.rhs (and has_force: which columns have a force part, for
// variable_damping). No allocation: every matrix has at most kMaxConstraintColumns rows.
void solve_coupling(Data& data, const Options& options);

// nu (scaled columns, as data.nu) with the columns j where given_up[j] is true given up:
// nu_j = 0 there, and the others H solve K_HH nu_H = rhs_H by variable_damping (the
// eigen-decomposition of K_HH scaled by kind, as solve_coupling's). Reads data.K,
// data.workspace.rhs and has_force; no allocation.
void solve_coupling_without(const Data& data, const Options& options, const bool* given_up, ConstraintVector& nu);

}  // namespace achd
