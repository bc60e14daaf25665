#pragma once
// The Popov-Vereshchagin hybrid dynamics solver (ACHD): joint accelerations of a chain
// driven by joint torques, link wrenches and tip acceleration constraints
// alpha^T a_tip = beta, resolved by Gauss's principle of least constraint in O(n).
#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

// Solves the case and writes the results into `data`. Validates the case (throws
// achd::Error naming the field); does not allocate.
void hybrid_dynamics(const Model& model, Data& data, const Case& c, const Options& options = {});

}  // namespace achd
