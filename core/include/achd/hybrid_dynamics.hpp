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

// The smallest singular value of the last solve's coupling matrix K (its smallest
// eigenvalue: K is symmetric positive semi-definite), 0 without constraints: how close
// the constraint set is to singular. Computed when called, from the K kept in `data`
// (data.M0): exactly, by a tridiagonal reduction and Laguerre's iteration, which costs
// about a third of a six-constraint solve, so a solve alone does not pay for it.
double sigma_min(const Data& data);

}  // namespace achd
