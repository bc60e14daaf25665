#pragma once
// The constraint sweep (constraint_sweep.hpp) for relative blocks that all end on one
// second body b: the loop joints of a parallel robot, every one closing on its platform.
// shared_second_body.cpp states the equations.
#include "achd/case.hpp"
#include "achd/data.hpp"

namespace achd {

// The second body every source of d.workspace.sources ends on, when there are at least two
// sources, every one relative, and their forces at b are better rolled through b's path
// once as six unit wrenches than once per block; -1 otherwise (the constraint sweep takes
// each block's two legs). `last`: the last body a column passes one axis at a time.
int shared_second_body(const Data& d, int last);

// d.E = E_0, K, G_0 as constraint_sweep computes them, the sources all ending on body b
// (shared_second_body). Keeps each block's EZ_i along its first leg's path, the unit
// wrenches' along b's path and the blocks' forces at b for shared_constraint_torques.
// Returns K's finite probe. (qdd_given: the case's, in the solver's coordinates.)
double shared_second_body_sweep(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given,
                                bool prescribed, int b);

// The constraint torques (constraint_sweep.hpp's constraint_torques) after
// shared_second_body_sweep.
void shared_constraint_torques(const Model& model, Data& d);

}  // namespace achd
