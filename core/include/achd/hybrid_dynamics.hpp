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
// achd::Error naming the field); does not allocate. Every result is finite: a solve
// whose numbers overflow (velocities near 1e155, torques near 1e308, links so light that
// the articulated inertia cannot be inverted) throws achd::Error naming the joint, link
// or constraint column where it happened. Each constraint column is solved scaled by the
// power of two (exact) that brings its length into [2^-1/2, 2^1/2), so a column's scale
// changes only its nu: the rank decision and, for conflicting columns, the least-squares
// compromise weigh every column alike.
void hybrid_dynamics(const Model& model, Data& data, const Case& c, const Options& options = {});

// The smallest singular value of the last solve's coupling matrix K = A M^-1 A^T of the
// alpha columns as given (its smallest eigenvalue: K is symmetric positive
// semi-definite), 0 without constraints: how close the constraint set is to singular.
// Throws achd::Error if K is beyond the range of a double (columns of length ~1e154). Computed when called, from the K kept in `data`
// (data.K): exactly, by a tridiagonal reduction and Laguerre's iteration, which costs
// about a third of a six-constraint solve, so a solve alone does not pay for it.
double sigma_min(const Data& data);

}  // namespace achd
