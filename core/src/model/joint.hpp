#pragma once
// Joint-type-aware motion subspace products. Every body frame is its joint's frame, with
// z along the joint axis (the URDF loader rotates the frames so), so a revolute joint's
// S is e_z angular, [0 0 0 0 0 1], and a prismatic joint's S is e_z linear,
// [0 0 1 0 0 0] (linear first): S s, S^T f and I S pick one component or one column.
#include "achd/model.hpp"

namespace achd {

inline bool is_rotational(const Body& b) { return b.type != JointType::Prismatic; }

// The component of a spatial vector that the joint's S selects.
inline int joint_component(const Body& b) { return is_rotational(b) ? 5 : 2; }

// S s: the joint's spatial velocity for the joint rate s.
inline Vector6 subspace_times(const Body& b, double s) {
  Vector6 m = Vector6::Zero();
  m[joint_component(b)] = s;
  return m;
}

// S^T f: the generalised force a spatial force f exerts on the joint.
template <typename Derived>
inline double subspace_dot(const Body& b, const Eigen::MatrixBase<Derived>& f) {
  return f[joint_component(b)];
}

// I S for a 6x6 I.
inline Vector6 inertia_times_subspace(const Body& b, const Matrix6& I) {
  return I.col(joint_component(b));
}

}  // namespace achd
