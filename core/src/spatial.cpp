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

namespace {

// p x M, column by column: [p]x M without forming [p]x.
inline Matrix3 cross_columns(const Vector3& p, const Matrix3& M) {
  Matrix3 r;
  for (int j = 0; j < 3; ++j) r.col(j) = p.cross(M.col(j));
  return r;
}

// R S R^T for a symmetric S: the lower triangle computed, the upper mirrored.
inline Matrix3 rotate_symmetric(const Matrix3& R, const Matrix3& S) {
  const Matrix3 RS = R * S;
  Matrix3 r;
  for (int j = 0; j < 3; ++j)
    for (int i = j; i < 3; ++i) r(i, j) = r(j, i) = RS.row(i).dot(R.row(j));
  return r;
}

}  // namespace

void add_inertia_to_parent(const Transform& X, const Matrix6& Ic, Matrix6& Ip) {
  // Rotate the blocks [A B; B^T C] into P's orientation: A' = R A R^T, B' = R B R^T, C'.
  const Matrix3& R = X.R;
  const Matrix3 A = rotate_symmetric(R, Ic.topLeftCorner<3, 3>());
  const Matrix3 B = R * Ic.topRightCorner<3, 3>() * R.transpose();
  const Matrix3 C = rotate_symmetric(R, Ic.bottomRightCorner<3, 3>());
  // Shift the reference point from C's origin to P's origin (x = [p]x, x^T = -x):
  //   A_P = A,  B_P = B - A x = B + (x A)^T,  C_P = C - B^T x + x B - x A x
  //   = C + x B_P + (x B)^T  (symmetric: lower triangle computed, upper mirrored)
  const Matrix3 Bp = B + cross_columns(X.p, A).transpose();
  const Matrix3 xBp = cross_columns(X.p, Bp);
  const Matrix3 xB = cross_columns(X.p, B);
  Ip.topLeftCorner<3, 3>() += A;
  Ip.topRightCorner<3, 3>() += Bp;
  Ip.bottomLeftCorner<3, 3>() += Bp.transpose();
  for (int j = 0; j < 3; ++j)
    for (int i = j; i < 3; ++i) {
      const double cij = C(i, j) + xBp(i, j) + xB(j, i);
      Ip(3 + i, 3 + j) += cij;
      if (i != j) Ip(3 + j, 3 + i) += cij;
    }
}

Matrix6 inertia_to_parent(const Transform& X, const Matrix6& Ic) {
  Matrix6 I = Matrix6::Zero();
  add_inertia_to_parent(X, Ic, I);
  return I;
}

}  // namespace achd
