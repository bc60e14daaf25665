#pragma once
// Virtual wrenches (Case::f_virtual): the joint torques J^T f_virtual that apply them.
#include "achd/data.hpp"

namespace achd {

// After the poses: d.virtual_torques = J^T f_virtual, summed inward (each body's subtree's
// wrenches, moved to its origin, projected on its joint: tau_i = S_i^T F_i,
// F_p += X_i^T F_i), O(n). Returns nothing to probe: finite wrenches and poses give
// finite torques unless they overflow, which the solve's probe of joint_torques sees.
void virtual_torques(const Model& model, Data& d, const Case& c);

}  // namespace achd
