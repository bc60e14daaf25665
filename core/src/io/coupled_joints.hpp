#pragma once
// The loader's message for a coupled joint (URDF <mimic>) that moves nothing.
#include "achd/model.hpp"

namespace achd {

// Called after validate() refused the model: throws achd::Error naming the coupled group
// of the joint that moves nothing, if that joint is coupled; returns otherwise (the
// caller rethrows validate()'s error).
void check_coupled_joints_move_something(const Model& model);

}  // namespace achd
