#pragma once
// A plain reference implementation of the Popov-Vereshchagin solver on kinematic trees:
// Featherstone's articulated-body algorithm on trees (RBDA ch. 7) with Vereshchagin's
// constraint sweep, written in the book's notation with 6x6 matrices in each body's own
// coordinates, loops over parent[i], scalar Eigen. It is the oracle of the fast path
// (hybrid_dynamics) in the tests and the place to learn the algorithm; it allocates and is
// not fast. Of what hybrid_dynamics solves it solves q, qd, ff_torques, gravity, f_ext, the
// tip's alpha/beta and Case::constraints blocks, prescribed joints, damping, friction and
// rotor inertia per Options::effects, Case::extra_inertia, both conventions; the coupling
// matrix by the truncated pseudo-inverse (Options::tolerance, relative to sigma_max unless
// absolute_tolerance).
#include <vector>

#include <Eigen/Core>

#include "achd/case.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

struct ReferenceSolution {
  Eigen::VectorXd qdd;                // joint accelerations
  Eigen::VectorXd nu;                 // constraint magnitudes: the tip's columns, then each
                                      // block's in order (as Data::nu)
  Eigen::VectorXd joint_torques;      // ff - sum_k J_k^T alpha_k nu_k, a prescribed joint's
                                      // prescribed torque as its ff (as Data::joint_torques)
  Eigen::VectorXd prescribed_torques;  // per joint: the torque a prescribed joint needs, 0
                                       // for the others (as Data::prescribed_torques)
  std::vector<Vector6> link_accelerations;  // root link first, then Model::links; base axes
                                            // at each link origin, per the convention
  Vector6 constraint_wrench = Vector6::Zero();  // alpha nu of the tip's columns at the tip
                                                // link's origin (as Data::constraint_wrench)
  std::vector<Vector6> constraint_wrenches;  // per Case::constraints block: alpha nu at its
                                             // point, base axes
  int rank = 0;                              // of the coupling matrix K
};

// Validates the case and the options (achd::Error, as hybrid_dynamics); throws
// achd::Error unless options.policy is Truncate (the reference has no other policy). What
// hybrid_dynamics solves and the reference does not is refused by name, never ignored:
// coupled joints (Model::couplings), driver weights below 1 (w_fext, w_ff: weights of 1
// are solved, being the plain solve) and nonzero virtual wrenches (f_virtual).
ReferenceSolution pv_reference(const Model& model, const Case& c, const Options& options = {});

}  // namespace achd
