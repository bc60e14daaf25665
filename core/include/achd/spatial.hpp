#pragma once
// Spatial (6D) algebra, linear part first everywhere in achd:
//   motion vector m = [v; w]   (linear velocity of the frame origin, angular velocity)
//   force vector  f = [f; n]   (force, moment about the frame origin)
// Transforms are stored as a rotation plus a translation and applied with cross
// products, never as 6x6 matrices (RBDA ch. 2, Featherstone's "plux" in parts).
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace achd {

using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

inline Matrix3 skew(const Vector3& p) {
  Matrix3 s;
  s << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
  return s;
}

// A rigid transform from frame P (parent) to frame C (child): C's origin is `p` and its
// axes are the columns of `R`, both in P coordinates.
struct Transform {
  Matrix3 R = Matrix3::Identity();
  Vector3 p = Vector3::Zero();

  // Pose composition: (this * c) maps C' coordinates through C to P.
  Transform operator*(const Transform& c) const { return {R * c.R, p + R * c.p}; }

  // Force given in C about C's origin, returned in P about P's origin (X^T f):
  //   f_P = R f,  n_P = R n + p x f_P
  Vector6 force_to_parent(const Vector6& f) const {
    Vector6 r;
    r.head<3>().noalias() = R * f.head<3>();
    r.tail<3>().noalias() = R * f.tail<3>();
    r.tail<3>() += p.cross(r.head<3>());
    return r;
  }
  // Motion vector given in C at C's origin, returned in P at P's origin (X^-1 m):
  //   w_P = R w,  v_P = R v - w_P x p
  Vector6 motion_to_parent(const Vector6& m) const {
    Vector6 r;
    r.tail<3>().noalias() = R * m.tail<3>();
    r.head<3>().noalias() = R * m.head<3>();
    r.head<3>() -= r.tail<3>().cross(p);
    return r;
  }
};

// Moving the reference point, axes unchanged. A motion vector about point P, taken about
// the point P + r:  [v + w x r; w].
inline Vector6 motion_shift(const Vector6& m, const Vector3& r) {
  Vector6 out = m;
  out.head<3>() += m.tail<3>().cross(r);
  return out;
}
// A force about point P + r, taken about P:  [f; n + r x f].
inline Vector6 force_shift(const Vector6& f, const Vector3& r) {
  Vector6 out = f;
  out.tail<3>() += r.cross(f.head<3>());
  return out;
}

// m1 x m2 (spatial motion cross product): [w1 x v2 + v1 x w2; w1 x w2]
inline Vector6 cross_motion(const Vector6& m1, const Vector6& m2) {
  Vector6 r;
  const Vector3 w1 = m1.tail<3>();
  r.head<3>() = w1.cross(m2.head<3>()) + m1.head<3>().cross(m2.tail<3>());
  r.tail<3>() = w1.cross(m2.tail<3>());
  return r;
}

// m x* f (spatial force cross product): [w x f; w x n + v x f]
inline Vector6 cross_force(const Vector6& m, const Vector6& f) {
  Vector6 r;
  const Vector3 w = m.tail<3>();
  r.head<3>() = w.cross(f.head<3>());
  r.tail<3>() = w.cross(f.tail<3>()) + m.head<3>().cross(f.head<3>());
  return r;
}

// Spatial inertia of a rigid body about its frame origin, linear first:
//   I = [ m 1     -m [c]x ]
//       [ m [c]x   I_o    ],   I_o = I_c - m [c]x [c]x   (RBDA eq. 2.63)
Matrix6 spatial_inertia(double mass, const Vector3& com, const Matrix3& inertia_at_com);

// X^T I X: a 6x6 inertia given in C (about C's origin) expressed in P (about P's
// origin), by blocks: rotate, then shift by p (RBDA 2.66 with linear-first order).
Matrix6 inertia_to_parent(const Transform& X, const Matrix6& I_child);
// I_parent += X^T I_child X: rotate the blocks, then add_shifted_inertia.
void add_inertia_to_parent(const Transform& X, const Matrix6& I_child, Matrix6& I_parent);

// The six directions of a spatial vector [v; w] (linear x y z, angular rx ry rz), by the
// names the simulator's held directions and the loop joints use: "x", "y", "z", "rx",
// "ry", "rz" (an achd::Error on an index outside 0..5); index_of_direction returns -1 for
// anything else.
constexpr int kNumDirections = 6;
const char* direction_name(int index);
int index_of_direction(const std::string& name);

}  // namespace achd
