#include "achd/spatial.hpp"

#include "spatial_pairs.hpp"

namespace achd {

Matrix6 spatial_inertia(double mass, const Vector3& com, const Matrix3& inertia_at_com) {
  const Matrix3 cx = skew(com);
  Matrix6 I;
  I.topLeftCorner<3, 3>() = mass * Matrix3::Identity();
  I.topRightCorner<3, 3>() = -mass * cx;
  I.bottomLeftCorner<3, 3>() = mass * cx;
  I.bottomRightCorner<3, 3>() = inertia_at_com - mass * cx * cx;
  return I;
}

void add_inertia_to_parent(const Transform& X, const Matrix6& Ic, Matrix6& Ip) {
  // Rotate the blocks [A B; B^T C] into P's orientation: A' = R A R^T, B' = R B R^T, C';
  // then shift the reference point from C's origin to P's origin.
  const Matrix3& R = X.R;
  Matrix6 I;
  I.topLeftCorner<3, 3>() = rotate_symmetric(R, Ic.topLeftCorner<3, 3>());
  I.topRightCorner<3, 3>() = R * Ic.topRightCorner<3, 3>() * R.transpose();
  I.bottomLeftCorner<3, 3>() = I.topRightCorner<3, 3>().transpose();
  I.bottomRightCorner<3, 3>() = rotate_symmetric(R, Ic.bottomRightCorner<3, 3>());
  add_shifted(I, Shift(X.p), Ip);
}

Matrix6 inertia_to_parent(const Transform& X, const Matrix6& Ic) {
  Matrix6 I = Matrix6::Zero();
  add_inertia_to_parent(X, Ic, I);
  return I;
}

}  // namespace achd
