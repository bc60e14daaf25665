#pragma once
// Reference dynamics of the chain, independent of the hybrid solver: inverse dynamics
// (RNEA), the joint-space mass matrix (CRBA). Each in two forms: one that returns a new
// value, and one that writes into caller-owned storage with a ChainWorkspace
// (kinematics.hpp) and allocates nothing.
#include <vector>

#include <Eigen/Core>

#include "achd/kinematics.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

// tau = M(q) qdd + C(q, qd) qd + g(q) - sum_i J_i^T f_ext_i   (RNEA, RBDA table 5.1),
// with the effects of options.effects as the solver has them: rotor inertia adds
// rotor * qdd; damping and friction (F tanh(qd / options.friction_velocity)) add their
// passive torques with the opposite sign (tau is what the actuators supply). f_ext: empty
// or one per link after the root (base orientation, about the link origin). The inputs
// are a state and the accelerations wanted, not a Case: a case's torques, constraints and
// prescribed joints are a forward solve's. An achd::Error names a wrong length or option.
Eigen::VectorXd rnea(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                     const Eigen::VectorXd& qdd, const Vector3& gravity, const std::vector<Vector6>& f_ext = {},
                     const Options& options = {});
// The same with the solver's shape (model, workspace, inputs, options): into `tau`, which
// is resized to num_rates() if it is not that size already; allocates nothing then.
void rnea(const Model& model, ChainWorkspace& ws, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
          const Eigen::VectorXd& qdd, const Vector3& gravity, const std::vector<Vector6>& f_ext,
          const Options& options, Eigen::VectorXd& tau);

// Joint-space mass matrix M(q), composite rigid bodies (RBDA 6.2), plus diag(rotor
// inertia) when options.effects has kRotorInertia (the default).
Eigen::MatrixXd crba(const Model& model, const Eigen::VectorXd& q, const Options& options = {});
// The same into `M`, which is resized to nv x nv if it is not that size already.
void crba(const Model& model, ChainWorkspace& ws, const Eigen::VectorXd& q, const Options& options,
          Eigen::MatrixXd& M);

}  // namespace achd
