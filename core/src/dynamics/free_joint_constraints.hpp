#pragma once
// The constraint sweep through a floating base's free joint in one 6-DoF step
// (free_joint_constraints.cpp states the equations). constraint_sweep.cpp calls it.
#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/model.hpp"

namespace achd {

// Whether the step applies: a floating base whose free joint is not prescribed and no driver
// weights (those cases roll through the free joint's six bodies one axis at a time, as any
// joint). Sets d.workspace.free_joint_step. `prescribed`: c.any_prescribed().
bool use_free_joint_step(const Model& model, Data& d, const Case& c, bool prescribed);

// After every block's columns rolled to the root (d.E = F, at the root's origin) and their
// couplings below it: K += F^T IA_r^-1 F and G_0 += F^T IA_r^-1 (w - pA_r). Returns the
// finite probe of what it added.
double free_joint_coupling(Data& d);

// The constraint torques of the free joint's six bodies from the summed force F nu',
// rolled through them one axis at a time.
void free_joint_constraint_torques(const Model& model, Data& d);

}  // namespace achd
