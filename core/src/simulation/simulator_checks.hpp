#pragma once
// What the Simulator checks before a step or a reset, and how it names a state that is
// not finite.
#include <string>

#include "achd/model.hpp"
#include "achd/simulator_options.hpp"

namespace achd {

// v holds n finite numbers; else an achd::Error naming `field` ("q[3] is not finite").
void check_state(const Eigen::VectorXd& v, int n, const char* field);
// A floating base's orientation in q (q[3..6]) is not the zero quaternion, which is no
// orientation (any other length is normalised).
void check_orientation(const Model& model, const Eigen::VectorXd& q, const char* field);
// The options step() reads, each a positive finite number (rtol, atol: >= 0, one > 0).
void check_simulator_options(const SimulatorOptions& o);
// The first joint whose q or qd is not finite, as "joint 'elbow': qd = inf"; "" if none
// (a floating base's free joint: its seven positions and six rates).
std::string non_finite_joint(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
// A loop index of the model; else an achd::Error naming `what` and the range.
void check_loop(const Model& model, int loop, const char* what);
// "the acceleration to enforce along direction x of loop 'pin' is not finite (beta = inf)"
// for loop column `column` (Case::loop_beta's order).
std::string loop_beta_not_finite(const Model& model, int column, double beta);

}  // namespace achd
