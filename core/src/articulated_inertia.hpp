#pragma once
// The sweeps' operations on spatial inertias held by blocks, I = [A B; B^T C]
// (SymmetricInertia, linear first), written out so that symmetric blocks are computed on
// one triangle and mirrored and no product touches a block the structure makes zero.
#include "achd/spatial.hpp"

namespace achd {

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

// A rigid body's inertia about its origin, given in its own axes as the 6x6
// I_b = [m 1, -[h]x; [h]x, I_o] (h = m c), in the axes of a frame where the body's axes
// are the columns of R: A = m 1, B = -[R h]x, C = R I_o R^T. Also returns h' = R h.
inline Vector3 set_rigid_inertia(SymmetricInertia& I, const Matrix3& R, const Matrix6& Ib) {
  const double m = Ib(0, 0);
  const Vector3 h = R * Vector3(Ib(5, 1), Ib(3, 2), Ib(4, 0));  // [h]x = Ib(3:6, 0:3)
  I.A = m * Matrix3::Identity();
  I.B = -skew(h);
  I.C = rotate_symmetric(R, Ib.bottomRightCorner<3, 3>());
  return h;
}

// I x = [A x_lin + B x_ang; B^T x_lin + C x_ang]
inline Vector6 times(const SymmetricInertia& I, const Vector6& x) {
  Vector6 y;
  y.head<3>().noalias() = I.A * x.head<3>() + I.B * x.tail<3>();
  y.tail<3>().noalias() = I.B.transpose() * x.head<3>() + I.C * x.tail<3>();
  return y;
}

// I -= U U^T / D, by blocks: A -= U_l k_l^T, B -= U_l k_a^T, C -= U_a k_a^T with k = U / D
// (A and C on the lower triangle, mirrored).
inline void subtract_rank_one(SymmetricInertia& I, const Vector6& U, double Dinv) {
  const Vector6 k = U * Dinv;
  for (int j = 0; j < 3; ++j) {
    for (int i = j; i < 3; ++i) {
      I.A(i, j) = I.A(j, i) = I.A(i, j) - U[i] * k[j];
      I.C(i, j) = I.C(j, i) = I.C(i, j) - U[3 + i] * k[3 + j];
    }
    I.B.col(j) -= U.head<3>() * k[3 + j];
  }
}

// P += I moved from a point at r from P's reference point to that point, axes unchanged
// (X^T I X for the translation X by r; x = [r]x, x^T = -x):
//   A_P = A,  B_P = B - A x = B + V^T,  C_P = C - B^T x + x B - x A x = C + W + W^T + V x^T
// with V = x A and W = x B (columns r x a), written out entry by entry.
inline void add_shifted(const SymmetricInertia& I, const Vector3& r, SymmetricInertia& P) {
  const double x = r[0], y = r[1], z = r[2];
  // V = x A, W = x B: column j is r x (column j).
  double V[3][3], W[3][3];  // [row][column]
  for (int j = 0; j < 3; ++j) {
    const double a0 = I.A(0, j), a1 = I.A(1, j), a2 = I.A(2, j);
    V[0][j] = y * a2 - z * a1;
    V[1][j] = z * a0 - x * a2;
    V[2][j] = x * a1 - y * a0;
    const double b0 = I.B(0, j), b1 = I.B(1, j), b2 = I.B(2, j);
    W[0][j] = y * b2 - z * b1;
    W[1][j] = z * b0 - x * b2;
    W[2][j] = x * b1 - y * b0;
  }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      P.A(i, j) += I.A(i, j);
      P.B(i, j) += I.B(i, j) + V[j][i];
    }
  // (V x^T)_ij = (r x V.row(i))_j on the lower triangle.
  for (int i = 0; i < 3; ++i) {
    const double v0 = V[i][0], v1 = V[i][1], v2 = V[i][2];
    const double vx[3] = {y * v2 - z * v1, z * v0 - x * v2, x * v1 - y * v0};
    for (int j = 0; j <= i; ++j)
      P.C(i, j) = P.C(j, i) = P.C(i, j) + (I.C(i, j) + (W[i][j] + W[j][i]) + vx[j]);
  }
}

}  // namespace achd
