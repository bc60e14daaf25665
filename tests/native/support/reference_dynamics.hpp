#pragma once
// A second, independent inverse dynamics (RNEA) and mass matrix (CRBA) for the tests,
// written from Featherstone's listings (RBDA tables 5.1 and 6.2) with plain 6x6 Eigen
// matrices in each body's own coordinates: joint transforms Xup_i = XJ(q_i) XT_i built
// from the Model's X_tree with std::sin/cos, spatial cross products as matrices, forces
// carried inward by Xup^T. It calls no achd kernel (no body_poses, joint_transform,
// inertia_to_parent or pair arithmetic); it reads only the Model's data. Vectors are
// linear first, as in achd.
#include <cstdint>
#include <vector>

#include "achd/achd.hpp"

namespace achd::test {

// tau = M qdd + C qd + g - sum_l J_l^T f_ext_l (+ rotor qdd, + damping qd, + friction
// tanh(qd / v_f)), with the same meaning of every argument and effect bit as achd::rnea.
Eigen::VectorXd reference_rnea(const Model& model, const Eigen::VectorXd& q,
                               const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                               const Vector3& gravity, const std::vector<Vector6>& f_ext = {},
                               std::uint32_t effects = kDefaultEffects,
                               double friction_velocity = 0.05);

// The joint-space mass matrix (+ diag(rotor inertia) when rotor_inertia).
Eigen::MatrixXd reference_crba(const Model& model, const Eigen::VectorXd& q, bool rotor_inertia = true);

}  // namespace achd::test
