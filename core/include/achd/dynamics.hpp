#pragma once
// Reference dynamics of the chain, independent of the hybrid solver: inverse dynamics
// (RNEA), the joint-space mass matrix (CRBA). Each in two forms: one that returns a new
// value, and one that writes into caller-owned storage with a ChainWorkspace
// (kinematics.hpp) and allocates nothing.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "achd/kinematics.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

// tau = M(q) qdd + C(q, qd) qd + g(q) - sum_i J_i^T f_ext_i   (RNEA, RBDA table 5.1).
// Rotor inertia adds rotor * qdd when kRotorInertia is on; damping and friction add
// their passive torques with the opposite sign (tau is what the actuators supply).
// f_ext: empty or one per link after the root (base orientation, about the link origin).
Eigen::VectorXd rnea(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                     const Eigen::VectorXd& qdd, const Vector3& gravity,
                     const std::vector<Vector6>& f_ext = {},
                     std::uint32_t effects = kDefaultEffects, double friction_velocity = 0.05);
// The same into `tau`, which is resized to num_rates() if it is not that size already.
void rnea(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
          const Eigen::VectorXd& qdd, const Vector3& gravity, const std::vector<Vector6>& f_ext,
          std::uint32_t effects, double friction_velocity, ChainWorkspace& ws, Eigen::VectorXd& tau);

// Joint-space mass matrix M(q) (+ diag(rotor inertia)), composite rigid bodies (RBDA 6.2).
Eigen::MatrixXd crba(const Model& model, const Eigen::VectorXd& q, bool rotor_inertia = true);
// The same into `M`, which is resized to nj x nj if it is not that size already.
void crba(const Model& model, const Eigen::VectorXd& q, bool rotor_inertia, ChainWorkspace& ws,
          Eigen::MatrixXd& M);

}  // namespace achd
