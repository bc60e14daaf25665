#pragma once
// A joint's motion subspace in base axes, for the sweeps (hybrid_dynamics.cpp): every body
// frame is its joint frame, with z along the joint axis, so body i's subspace is
// S_i = [0; z_i] (revolute) or [z_i; 0] (prismatic), z_i the body's z axis in base axes.
// (joint.hpp holds the same products in the body's own axes, where S picks one component.)
#include "achd/data.hpp"
#include "achd/model.hpp"
#include "joint.hpp"
#include "spatial_pairs.hpp"

namespace achd {

struct JointSubspace {
  Vector3 z;        // the joint axis in base axes
  bool rotational;  // S = [0; z], else [z; 0]

  // S s: the spatial motion (velocity or acceleration) of joint rate s.
  SpatialVector motion(double s) const {
    const Vector3 zs = z * s;
    if (rotational) return {{Pair{0, 0}, Pair{0, zs[0]}, Pair{zs[1], zs[2]}}};
    return {{Pair{zs[0], zs[1]}, Pair{zs[2], 0}, Pair{0, 0}}};
  }

  // S^T f: the component along the joint of a spatial force f (or of a column I S).
  double project(const SpatialVector& f) const { return z.dot(rotational ? angular_part(f) : linear_part(f)); }

  // I S: I's columns 3..5 (revolute) or 0..2 (prismatic) combined by z.
  SpatialVector inertia_times(const Matrix6& I) const { return combine_columns(I, rotational ? 3 : 0, z); }

  // The first row of the part of a 6-vector that S spans (3, angular, or 0, linear).
  int first_row() const { return rotational ? 3 : 0; }
};

// The velocity-product acceleration c = v_p x S qd of a body whose parent moves with v_p
// (about the body's origin): [v_lin x zq; w x zq] (revolute) or [w x zq; 0] (prismatic),
// zq = z qd.
inline SpatialVector velocity_product_acceleration(const SpatialVector& v_parent, const JointSubspace& S, double qd) {
  const Vector3& z = S.z;
  const Pair zq[3] = {splat(z[0] * qd), splat(z[1] * qd), splat(z[2] * qd)};
  const Vec3Pair vxz = cross(linear_angular(v_parent), zq);  // rows (v_lin x zq, w x zq)
  if (S.rotational) return from_linear_angular(vxz);
  return {{high_lanes(vxz.r[0], vxz.r[1]), Pair{vxz.r[2][1], 0}, Pair{0, 0}}};
}

// Body i's joint subspace S_i = [0; z_i] (revolute) or [z_i; 0] (prismatic), z_i the
// body's z axis (once the sweeps have set the poses).
inline JointSubspace body_subspace(const Model& model, const Data& d, int i) {
  return {d.X0[i].R.col(2), is_rotational(model.bodies[i])};
}

}  // namespace achd
