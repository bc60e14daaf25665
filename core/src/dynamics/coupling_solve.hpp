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

// variable_damping's held-first solve: a yielding column (a pushed direction) gives way in
// place of a damped eigen-direction's largest component when its own component is at
// least this share of it. The damped direction is measured on K, which mixes the mass
// distribution into the kinematics: at a workspace boundary the lost combination along
// the push has, in K, its largest components in held wrist angles (light links move
// easily), the push carrying a third to a half of the largest. Giving the push way
// first, the held ones are then tested on their own (K_HH clear of 4 eps, or more
// columns give way), so a hold gives way only where it is lost without the push.
constexpr double kPushShare = 0.2;

// nu (scaled columns, as data.nu) with the columns j where given_up[j] is true given up:
// nu_j = 0 there, and the others H solve K_HH nu_H = rhs_H by variable_damping (the
// eigen-decomposition of K_HH scaled by kind, as solve_coupling's). Reads data.K,
// data.workspace.rhs and has_force; no allocation.
void solve_coupling_without(const Data& data, const Options& options, const bool* given_up, ConstraintVector& nu);

}  // namespace achd
