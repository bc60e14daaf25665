#include "achd/spatial.hpp"

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

Matrix6 inertia_to_parent(const Transform& X, const Matrix6& Ic) {
  // Rotate the blocks [A B; B^T C] into P's orientation: A' = R A R^T, etc.
  const Matrix3& R = X.R;
  const Matrix3 A = R * Ic.topLeftCorner<3, 3>() * R.transpose();
  const Matrix3 B = R * Ic.topRightCorner<3, 3>() * R.transpose();
  const Matrix3 C = R * Ic.bottomRightCorner<3, 3>() * R.transpose();
  // Shift the reference point from C's origin to P's origin (x = [p]x):
  //   A_P = A,  B_P = B - A x,  C_P = C - B^T x + x B - x A x
  const Matrix3 px = skew(X.p);
  const Matrix3 Bp = B - A * px;
  Matrix6 I;
  I.topLeftCorner<3, 3>() = A;
  I.topRightCorner<3, 3>() = Bp;
  I.bottomLeftCorner<3, 3>() = Bp.transpose();
  I.bottomRightCorner<3, 3>() = C - B.transpose() * px + px * Bp;
  return I;
}

}  // namespace achd
