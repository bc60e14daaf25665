#pragma once
// 3-vectors and 3x3 matrices on pairs (pair.hpp): a 3-vector is the pair (x, y) and the
// double z, and a 3x3 matrix (Eigen's column-major Matrix3) is its three columns. A
// matrix product is then a sum of columns scaled by entries, the same pair products for
// every column, summed in Eigen's order ((a0 b0 + a1 b1) + a2 b2).
#include "achd/spatial.hpp"
#include "pair.hpp"

namespace achd {

struct Vec3p {
  Pair xy;
  double z;
};

inline Vec3p load3(const double* x) { return {load_pair(x), x[2]}; }
inline void store3(double* x, const Vec3p& v) {
  store_pair(x, v.xy);
  x[2] = v.z;
}
inline Vec3p operator+(const Vec3p& a, const Vec3p& b) { return {a.xy + b.xy, a.z + b.z}; }
inline Vec3p operator-(const Vec3p& a, const Vec3p& b) { return {a.xy - b.xy, a.z - b.z}; }
inline Vec3p operator*(const Vec3p& a, double s) { return {a.xy * splat(s), a.z * s}; }

// The columns of a column-major 3x3 matrix.
struct Mat3p {
  Vec3p col[3];
};

inline Mat3p load_columns(const Matrix3& M) {
  const double* m = M.data();
  return {{load3(m), load3(m + 3), load3(m + 6)}};
}
inline void store_columns(Matrix3& M, const Mat3p& c) {
  double* m = M.data();
  for (int k = 0; k < 3; ++k) store3(m + 3 * k, c.col[k]);
}

// M x = M.col(0) x0 + M.col(1) x1 + M.col(2) x2.
inline Vec3p times(const Mat3p& M, double x0, double x1, double x2) {
  return (M.col[0] * x0 + M.col[1] * x1) + M.col[2] * x2;
}
inline Vec3p times(const Mat3p& M, const double* x) { return times(M, x[0], x[1], x[2]); }

// A B, column by column: (A B).col(j) = A B.col(j), B column-major with columns
// `stride` doubles apart.
inline Mat3p product(const Mat3p& A, const double* B, int stride = 3) {
  return {{times(A, B), times(A, B + stride), times(A, B + 2 * stride)}};
}

// R S R^T for a symmetric S (column-major, columns `stride` apart), as R (R S)^T: with
// W = R S, (R W^T).col(j) = R W.row(j)^T. Exactly symmetric: the upper triangle is the
// lower one.
inline Mat3p rotate_symmetric(const Mat3p& R, const double* S, int stride = 3) {
  const Mat3p W = product(R, S, stride);
  Vec3p c0 = times(R, W.col[0].xy[0], W.col[1].xy[0], W.col[2].xy[0]);
  Vec3p c1 = times(R, W.col[0].xy[1], W.col[1].xy[1], W.col[2].xy[1]);
  Vec3p c2 = times(R, W.col[0].z, W.col[1].z, W.col[2].z);
  // (C01, C11) <- (C10, C11);  (C02, C12) <- (C20, C21)
  c1.xy = high_lanes(c0.xy, c1.xy);
  c2.xy = Pair{c0.z, c1.z};
  return {{c0, c1, c2}};
}

}  // namespace achd
