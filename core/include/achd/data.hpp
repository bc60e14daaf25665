#pragma once
// The workspace of the algorithms, sized once from a Model: solves write here and
// never allocate. Outputs are the public members in the "results" block.
#include <array>
#include <vector>

#include "achd/case.hpp"
#include "achd/model.hpp"

namespace achd {

using ConstraintForceMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxConstraints>;
using CouplingMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraints, kMaxConstraints>;

struct Data {
  explicit Data(const Model& model);

  // ---- results of the last hybrid_dynamics() ----
  Eigen::VectorXd qdd;                 // joint accelerations
  Eigen::VectorXd constraint_torques;  // KDL's -S^T E nu
  Eigen::VectorXd total_torques;       // KDL's D qdd
  Eigen::VectorXd joint_torques;       // ff - J^T alpha nu = RNEA(q, qd, qdd)
  ConstraintVector nu;                 // constraint force magnitudes
  Vector6 constraint_wrench;           // alpha nu: what the tip exerts on the constraint
  std::vector<Vector6> link_accelerations;  // root link first, then Model::links
  int rank = 0;                  // of the coupling matrix K = -M_0 (nc x nc); its
                                 // smallest singular value: sigma_min(data)
  CouplingMatrix dropped;        // nc x k: constraint-space directions truncated/damped

  // ---- per body workspace (Featherstone's names; index = body) ----
  // The sweeps use base axes everywhere, and express body i's vectors and inertias about
  // the body's origin p_i (the "mixed" representation KDL reports link accelerations in):
  // passing them between a body and its parent is a shift by r_i, never a rotation, and
  // nothing is taken about a far-away point (the base origin), which would cost digits.
  // The joint subspace is S_i = [0; z_i] (revolute) or [z_i; 0] (prismatic), z_i the
  // body's z axis, X0_i.R.col(2).
  std::vector<Transform> X0;     // body pose in the base (axes R, origin p)
  std::vector<Vector3> r;        // p_i - p_parent, base axes (kinematics.hpp's body_poses)
  std::vector<Vector6> v;        // velocity
  std::vector<Vector6> kappa;    // velocity-product acceleration, summed from the base
  std::vector<Vector6> a;        // acceleration less kappa (a - kappa)
  std::vector<Matrix6> IA;       // rigid inertia in base axes, then articulated inertia
  std::vector<Vector6> pA;       // bias force (with I kappa), then articulated bias force
  std::vector<Vector6> U;        // IA S
  std::vector<Vector6> W;        // U / D about the parent's origin (X^T U / D)
  std::vector<double> D, Dinv, u;  // S^T IA S (+ rotor), 1 / D, tau - S^T pA
  std::vector<std::array<double, kMaxConstraints>> EZ;  // E^T S at each body
  ConstraintForceMatrix E;               // unit constraint forces alpha_k s_k, rolled
                                         // from the tip to the base (after the sweep: E_0)
  CouplingMatrix M0;                     // K = -M_0, the coupling of the columns alpha_k s_k
                                         // at the base (sigma_min() reads it)
  ConstraintVector G0;                   // acceleration energy of the bias terms
  ConstraintVector alpha_scale;          // s_k: the sweeps use the columns alpha_k s_k
  ConstraintVector rhs;                  // E_0^T a_0 + G_0 - beta
  Eigen::VectorXd tau;                   // joint torques fed to the sweeps
};

}  // namespace achd
