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

}  // namespace achd
