#pragma once
// Joint-type-aware motion subspace products. A revolute joint's S is [0; axis] and a
// prismatic joint's S is [axis; 0] (linear first), so S^T f and IA S touch only the
// half of a spatial vector or the three columns of a 6x6 that the joint moves.
#include "achd/model.hpp"

namespace achd {

inline bool is_rotational(const Body& b) { return b.type != JointType::Prismatic; }

// S s: the joint's spatial velocity for the joint rate s.
inline Vector6 subspace_times(const Body& b, double s) {
  Vector6 m = Vector6::Zero();
  if (is_rotational(b)) m.tail<3>() = b.axis * s;
  else m.head<3>() = b.axis * s;
  return m;
}

// S^T f: the generalised force a spatial force f exerts on the joint.
template <typename Derived>
inline double subspace_dot(const Body& b, const Eigen::MatrixBase<Derived>& f) {
  return is_rotational(b) ? b.axis.dot(f.template tail<3>()) : b.axis.dot(f.template head<3>());
}

// I S for a 6x6 I.
inline Vector6 inertia_times_subspace(const Body& b, const Matrix6& I) {
  return is_rotational(b) ? Vector6(I.rightCols<3>() * b.axis) : Vector6(I.leftCols<3>() * b.axis);
}

}  // namespace achd
