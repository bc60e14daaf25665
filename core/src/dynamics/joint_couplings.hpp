#pragma once
// Coupled joints (Model::couplings, URDF <mimic>): the solve with the couplings as
// joint-space constraints, q_f = k q_l + c for follower f and leader l.
#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

// Each coupling j is one row C_j of a joint-space constraint C qdd = beta_c:
//   C_j = e_f - k e_l   (qdd_f - k qdd_l = beta_c,j; 0 in a plain solve: differentiating
//                        q_f = k q_l + c twice; the simulator's stabilisation otherwise),
// held by the torques -C^T nu_c (the robot receives -C_j^T nu_c,j, as it receives
// -alpha nu at a constrained link). For a given state the solve is affine in the applied
// joint torques, qdd(tau) = qdd(0) + A tau with A the inverse inertia of the robot under
// its other constraints (which A includes: their forces adjust), so with R = A C^T
//   C (qdd_0 - R nu_c) = beta_c  =>  (C R) nu_c = C qdd_0 - beta_c.
// R's columns come from solves of the same state with the unit torques C_j^T and every
// other input zero (no velocity, gravity, wrench, constraint acceleration or prescribed
// acceleration), qdd_0 from the plain solve; the last solve applies ff - C^T nu_c, so that
// every result (joint_torques = RNEA(q, qd, qdd) included) is a solve's own. p couplings
// cost p + 2 solves. `solve_one` is the uncoupled hybrid dynamics; c is validated.
using SolveOne = void (*)(const Model&, Data&, const Case&, const Options&);
void coupled_dynamics(const Model& model, Data& d, const Case& c, const Options& o, SolveOne solve_one);

// The coupling rows' rates: C qd (per coupling, follower minus multiplier times leader),
// and C q - c at the positions (the coupling's position error).
double coupling_rate_error(const Model& model, const JointCoupling& j, const Eigen::VectorXd& qd);
double coupling_position_error(const Model& model, const JointCoupling& j, const Eigen::VectorXd& q);

}  // namespace achd
