#pragma once
// The constraint part of the Popov-Vereshchagin solve on a tree: blocks of constraint
// columns on any links (the tip's, Case::alpha, Case::constraints and the loop joints'
// blocks, solve_blocks.hpp), each rolled from
// its link to the base, their coupling K and bias energy G_0, and what follows from the
// forces nu (constraint torques, wrenches, joint torques). constraint_sweep.cpp states
// the equations; hybrid_dynamics.cpp calls these in order.
#include "achd/data.hpp"
#include "achd/options.hpp"

namespace achd {

// Calls f(i) for every body i >= last on source s's path to the base: a relative block's
// two legs up to where they meet, then the trunk from there (a block on one link: the
// trunk from its body).
template <class F>
inline void for_each_on_path(const Model& model, const ConstraintSource& s, int last, F f) {
  if (s.relative) {
    for (int i = s.body; i > s.meet && i >= last; i = model.bodies[i].parent) f(i);
    for (int i = s.body_b; i > s.meet && i >= last; i = model.bodies[i].parent) f(i);
  }
  for (int i = s.meet; i >= last; i = model.bodies[i].parent) f(i);
}

// After the poses: the blocks with columns into data.workspace.sources (the tip's first),
// each column scaled by its power of two (alpha_scale), and E = alpha s moved from each
// block's point to its body's origin. Returns the number of columns, m. `tip`: whether
// the tip's columns count (Options::effects has kConstraints).
int constraint_sources(const Model& model, Data& d, const Case& c);

// After the articulated-body sweep: every block's E rolled to the base (d.E = E_0, the
// EZ_i kept), K (m x m) and G_0 (qdd_given: the case's, in the solver's coordinates,
// JointInputs). Returns K's finite probe.
double constraint_sweep(const Model& model, Data& d, const Case& c, const Eigen::VectorXd& qdd_given,
                        bool prescribed);

// The right-hand side of K nu' = rhs (scaled columns): G_0 - beta' + E_0^T a_0, with
// beta' = beta - alpha^T kappa at each block's point, and the physical convention's
// alpha_lin^T g, into d.workspace.rhs.
void constraint_rhs(Data& d, const Case& c, const Options& o, bool moving);

// The constraint torque of every joint, -S_i^T E nu' = -sum over the blocks whose path
// holds body i of EZ_i^T nu', added to d.constraint_torques (which the inward sweep sets
// to 0: it stays 0 off every path).
void constraint_torques(const Model& model, Data& d);

// nu_k = s_k nu'_k, and the dropped and damped directions as unit combinations of the
// user's columns.
void unscale_constraint_forces(Data& d);

// The wrenches alpha nu (the tip's into constraint_wrench, one per Case::constraints block
// and per loop joint into constraint_wrenches, at their points) and joint_torques = ff + virtual_torques -
// sum_k J_k^T alpha_k nu_k (a prescribed joint's prescribed_torques in place of the first
// two; ff: the case's ff_torques in the solver's coordinates, JointInputs). Returns their
// finite probe.
double constraint_wrenches_and_joint_torques(const Model& model, Data& d, const Case& c,
                                             const Eigen::VectorXd& ff_torques, bool prescribed);

// d.joint_torques = -sum_k J_k^T alpha_k s_k nu_k for forces nu given in the scaled columns
// (before unscale_constraint_forces): the torques the joints give the constraint forces nu
// (d.joint_torques as scratch: constraint_wrenches_and_joint_torques writes it after).
void constraint_force_torques(const Model& model, Data& d, const Case& c, const ConstraintVector& nu);

}  // namespace achd
