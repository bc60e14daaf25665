#pragma once
// The end of a solve that overflowed: every number a solve returns is finite, or the solve
// fails with an achd::Error naming the first quantity that overflowed, in the user's terms.
// (The solve probes its results itself, as it writes them: hybrid_dynamics.cpp.)
#include "achd/data.hpp"
#include "achd/model.hpp"

namespace achd {

// Called when a solve's finite probe failed: throws achd::Error naming the first quantity
// of the sweeps, in the order they computed them, that is not finite (the joint, link or
// constraint column, and the inputs that feed it).
[[noreturn]] void name_the_first_overflow(const Model& model, const Data& data, const Case& c, int nc);

}  // namespace achd
