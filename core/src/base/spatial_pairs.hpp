#pragma once
// The sweeps' spatial algebra on pairs (pair.hpp). A spatial 6-vector, linear first, is
// held as three pairs of rows (0,1), (2,3), (4,5); a 6x6 inertia (symmetric, both
// triangles stored) as Eigen's column-major Matrix6, each column three such pairs. All
// quantities share base axes, so moving one from a body to its parent is a change of
// reference point alone (Shift).
#include "achd/spatial.hpp"
#include "matrix3_pairs.hpp"
#include "pair.hpp"

namespace achd {

// A spatial vector (a motion or a force, linear part first) as the three pairs of rows
// (0,1), (2,3), (4,5): the sweeps' working form of a Vector6 (load_pairs, store_pairs).
struct SpatialVector {
  Pair p[3];
};

inline SpatialVector load_pairs(const double* x) { return {{load_pair(x), load_pair(x + 2), load_pair(x + 4)}}; }
inline SpatialVector load_pairs(const Vector6& v) { return load_pairs(v.data()); }
inline void store_pairs(double* x, const SpatialVector& v) {
  for (int k = 0; k < 3; ++k) store_pair(x + 2 * k, v.p[k]);
}
inline void store_pairs(Vector6& v, const SpatialVector& x) { store_pairs(v.data(), x); }
inline SpatialVector column(const Matrix6& M, int j) { return load_pairs(M.data() + 6 * j); }

inline SpatialVector operator+(const SpatialVector& a, const SpatialVector& b) { return {{a.p[0] + b.p[0], a.p[1] + b.p[1], a.p[2] + b.p[2]}}; }
inline SpatialVector operator-(const SpatialVector& a, const SpatialVector& b) { return {{a.p[0] - b.p[0], a.p[1] - b.p[1], a.p[2] - b.p[2]}}; }
inline SpatialVector operator*(const SpatialVector& a, Pair s) { return {{a.p[0] * s, a.p[1] * s, a.p[2] * s}}; }
inline SpatialVector operator*(const SpatialVector& a, double s) { return a * splat(s); }

// x + A y for the m columns A (column-major, six numbers a column), the columns added in
// order.
inline SpatialVector add_columns_times(SpatialVector x, const double* A, const double* y, int m) {
  for (int j = 0; j < m; ++j) x = x + load_pairs(A + 6 * j) * y[j];
  return x;
}

// a . b, summed as (pairs 0 + 1) + 2, then the two lanes.
inline double dot(const SpatialVector& a, const SpatialVector& b) {
  const Pair s = (a.p[0] * b.p[0] + a.p[1] * b.p[1]) + a.p[2] * b.p[2];
  return s[0] + s[1];
}

// |a|^2 = a . a (in dot's order).
inline double squared_norm(const SpatialVector& a) { return dot(a, a); }

// x * 0 summed over x's six numbers: 0 when every one is finite, NaN otherwise
// (finite_probe.hpp).
inline double finite_probe(const SpatialVector& x) {
  const Pair zero = splat(0);
  const Pair probe = x.p[0] * zero + x.p[1] * zero + x.p[2] * zero;
  return probe[0] + probe[1];
}

// The rows 0..2 (linear) and 3..5 (angular) of a 6-vector as 3-vectors.
inline Vector3 linear_part(const SpatialVector& v) { return Vector3(v.p[0][0], v.p[0][1], v.p[1][0]); }
inline Vector3 angular_part(const SpatialVector& v) { return Vector3(v.p[1][1], v.p[2][0], v.p[2][1]); }

// Two 3-vectors a and b held component by component: row k is the Pair (a_k, b_k), so
// that one pair operation acts on both (two cross products with one vector cost one).
struct Vec3Pair {
  Pair r[3];
};

inline Vec3Pair operator+(const Vec3Pair& a, const Vec3Pair& b) { return {{a.r[0] + b.r[0], a.r[1] + b.r[1], a.r[2] + b.r[2]}}; }
inline Vec3Pair operator-(const Vec3Pair& a, const Vec3Pair& b) { return {{a.r[0] - b.r[0], a.r[1] - b.r[1], a.r[2] - b.r[2]}}; }
inline Vec3Pair operator*(const Vec3Pair& a, Pair s) { return {{a.r[0] * s, a.r[1] * s, a.r[2] * s}}; }

// The linear and angular parts of a 6-vector x as rows (x_k, x_{3+k}), and back.
inline Vec3Pair linear_angular(const SpatialVector& x) {
  return {{blend(x.p[0], x.p[1]), cross_lanes(x.p[0], x.p[2]), blend(x.p[1], x.p[2])}};
}
inline SpatialVector from_linear_angular(const Vec3Pair& t) {
  return {{low_lanes(t.r[0], t.r[1]), blend(t.r[2], t.r[0]), high_lanes(t.r[1], t.r[2])}};
}

// u x t and t x u for a 3-vector u given as its splatted components, row by row:
//   u x t = (u1 t2 - u2 t1, u2 t0 - u0 t2, u0 t1 - u1 t0)
inline Vec3Pair cross(const Pair (&u)[3], const Vec3Pair& t) {
  return {{u[1] * t.r[2] - u[2] * t.r[1], u[2] * t.r[0] - u[0] * t.r[2], u[0] * t.r[1] - u[1] * t.r[0]}};
}
inline Vec3Pair cross(const Vec3Pair& t, const Pair (&u)[3]) {
  return {{t.r[1] * u[2] - t.r[2] * u[1], t.r[2] * u[0] - t.r[0] * u[2], t.r[0] * u[1] - t.r[1] * u[0]}};
}

// A change of reference point by r (from a parent's origin to a child's), axes unchanged,
// with r's components in the lane arrangements that the cross products need. Each member
// is named by its two lanes: xx = (r_x, r_x), zx = (r_z, r_x), zero_y = (0, r_y), ...
struct Shift {
  explicit Shift(const Vector3& r)
      : xx(splat(r[0])), yy(splat(r[1])), zz(splat(r[2])), zx{r[2], r[0]}, xy{r[0], r[1]},
        yz{r[1], r[2]}, zero_y{0, r[1]}, zero_z{0, r[2]}, y_zero{r[1], 0}, x_zero{r[0], 0} {}
  Pair xx, yy, zz, zx, xy, yz, zero_y, zero_z, y_zero, x_zero;
};

// A force f = [f; n] about the child's origin, taken about the parent's: n += r x f.
//   row 3 (p[1][1]) += r_y f_z - r_z f_y;  rows 4, 5 (p[2]) += (r_z f_x - r_x f_z, r_x f_y - r_y f_x)
inline void force_to_parent(SpatialVector& f, const Shift& s) {
  const Pair f_zx = low_lanes(f.p[1], f.p[0]);  // (f_z, f_x)
  f.p[2] += s.zx * f.p[0] - s.xy * f_zx;
  f.p[1] += s.zero_y * swapped(f.p[1]) - s.zero_z * f.p[0];
}

// A motion m = [v; w] about the parent's origin, taken about the child's: v += w x r.
//   rows 0, 1 (p[0]) += (w_y r_z - w_z r_y, w_z r_x - w_x r_z);  row 2 (p[1][0]) += w_x r_y - w_y r_x
inline void motion_to_child(SpatialVector& m, const Shift& s) {
  const Pair w_zx = high_lanes(m.p[2], m.p[1]);  // (w_z, w_x)
  m.p[0] += s.zx * m.p[2] - s.yz * w_zx;
  m.p[1] += s.y_zero * swapped(m.p[1]) - s.x_zero * m.p[2];
}

// A rigid body's inertia I = [m 1, -[h]x; [h]x, C] about its origin by its parts.
struct RigidInertia {
  double m;
  Vec3p h;  // m c
  Mat3p C;  // rotational inertia about the origin
};

// I applied to two 6-vectors x and y at once, given as rows: lin row k = (x_k, y_k),
// ang row k = (x_{3+k}, y_{3+k}). I x = [m x_lin - h x x_ang; h x x_lin + C x_ang].
inline void rigid_times(const RigidInertia& I, const Vec3Pair& lin, const Vec3Pair& ang, Vec3Pair& f, Vec3Pair& n) {
  const Pair h[3] = {splat(I.h.xy[0]), splat(I.h.xy[1]), splat(I.h.z)};
  f = lin * splat(I.m) - cross(h, ang);
  const Vec3p* C = I.C.col;
  Vec3Pair Ca;  // C ang: row r is sum_k C(r, k) ang_k
  for (int r = 0; r < 3; ++r) {
    const double c0 = r < 2 ? C[0].xy[r] : C[0].z, c1 = r < 2 ? C[1].xy[r] : C[1].z,
                 c2 = r < 2 ? C[2].xy[r] : C[2].z;
    Ca.r[r] = (splat(c0) * ang.r[0] + splat(c1) * ang.r[1]) + splat(c2) * ang.r[2];
  }
  n = cross(h, lin) + Ca;
}

// The rigid body's bias force with the velocity products as accelerations (the
// hybrid_dynamics.cpp header): p = v x* I v + I kappa. I acts on v and kappa at once
// (rows (v_k, kappa_k)), and v x* [f; n] = [w x f; w x n + v_lin x f] on f and n at once
// (rows (f_k, n_k)).
inline SpatialVector bias_force(const RigidInertia& I, const SpatialVector& v, const SpatialVector& kappa) {
  const Vec3Pair lin = {{low_lanes(v.p[0], kappa.p[0]), high_lanes(v.p[0], kappa.p[0]), low_lanes(v.p[1], kappa.p[1])}};
  const Vec3Pair ang = {{high_lanes(v.p[1], kappa.p[1]), low_lanes(v.p[2], kappa.p[2]), high_lanes(v.p[2], kappa.p[2])}};
  Vec3Pair f, n;  // lanes: (I v, I kappa)
  rigid_times(I, lin, ang, f, n);
  Vec3Pair fn, Ikappa;  // rows (f_k, n_k) of I v, and I kappa as rows (linear, angular)
  for (int k = 0; k < 3; ++k) {
    fn.r[k] = low_lanes(f.r[k], n.r[k]);
    Ikappa.r[k] = high_lanes(f.r[k], n.r[k]);
  }
  const Pair w[3] = {splat(v.p[1][1]), splat(v.p[2][0]), splat(v.p[2][1])};
  const Pair vl[3] = {splat(v.p[0][0]), splat(v.p[0][1]), splat(v.p[1][0])};
  const Vec3Pair wx = cross(w, fn), vx = cross(vl, fn);  // (w x f, w x n), (v_lin x f, -)
  Vec3Pair bias = wx + Ikappa;
  for (int k = 0; k < 3; ++k) bias.r[k] += low_lanes(Pair{0, 0}, vx.r[k]);  // ang += v_lin x f
  return from_linear_angular(bias);
}

// A rigid body's inertia about its origin, given in its own axes as the 6x6
// I_b = [m 1, -[h]x; [h]x, I_o] (h = m c), in the axes of a frame where the body's axes
// are the columns of R: [m 1, -[R h]x; [R h]x, R I_o R^T], written to I and returned by
// its parts.
inline RigidInertia set_rigid_inertia(Matrix6& I, const Matrix3& R, const Matrix6& Ib) {
  const Mat3p Rc = load_columns(R);
  const double m = Ib(0, 0);
  const Vec3p h = times(Rc, Ib(5, 1), Ib(3, 2), Ib(4, 0));  // [h]x = Ib(3:6, 0:3)
  const Mat3p C = rotate_symmetric(Rc, Ib.data() + 6 * 3 + 3, 6);
  const double h0 = h.xy[0], h1 = h.xy[1], h2 = h.z;
  const Vec3p* c = C.col;
  // Written as the pairs of rows (0,1), (2,3), (4,5) that the sweeps load (a load that
  // spans two separate stores could not be forwarded from them).
  const SpatialVector columns[6] = {{{Pair{m, 0}, Pair{0, 0}, Pair{h2, -h1}}},
                            {{Pair{0, m}, Pair{0, -h2}, Pair{0, h0}}},
                            {{Pair{0, 0}, Pair{m, h1}, Pair{-h0, 0}}},
                            {{Pair{0, -h2}, Pair{h1, c[0].xy[0]}, Pair{c[0].xy[1], c[0].z}}},
                            {{Pair{h2, 0}, Pair{-h0, c[1].xy[0]}, Pair{c[1].xy[1], c[1].z}}},
                            {{Pair{-h1, h0}, Pair{0, c[2].xy[0]}, Pair{c[2].xy[1], c[2].z}}}};
  for (int j = 0; j < 6; ++j) store_pairs(I.data() + 6 * j, columns[j]);
  return {m, h, C};
}

// M.col(first) z0 + M.col(first + 1) z1 + M.col(first + 2) z2: I S for S = [0; z]
// (first = 3) or [z; 0] (first = 0).
inline SpatialVector combine_columns(const Matrix6& M, int first, const Vector3& z) {
  return (column(M, first) * splat(z[0]) + column(M, first + 1) * splat(z[1])) +
         column(M, first + 2) * splat(z[2]);
}

// M x, column by column.
inline SpatialVector times(const Matrix6& M, const Vector6& x) {
  SpatialVector y = column(M, 0) * splat(x[0]);
  for (int j = 1; j < 6; ++j) y = y + column(M, j) * splat(x[j]);
  return y;
}

// M moved from the child's origin to the parent's, M given by its columns (overwritten):
// X^T M X for the translation X = [1, -x; 0, 1], x = [r]x.
//   N = M X:  N.col(j) = M.col(j), N.col(3 + j) = M.col(3 + j) - (M.col(0:3) x).col(j)
//   X^T N:    every column's rows 3..5 gain r x (its rows 0..2), as force_to_parent
inline void shift_inertia(SpatialVector (&n)[6], const Shift& s) {
  // (M.col(0:3) x).col(0) = r_z M.col(1) - r_y M.col(2), col(1) = r_x M.col(2) - r_z M.col(0),
  // col(2) = r_y M.col(0) - r_x M.col(1)
  n[3] = n[3] - (n[1] * s.zz - n[2] * s.yy);
  n[4] = n[4] - (n[2] * s.xx - n[0] * s.zz);
  n[5] = n[5] - (n[0] * s.yy - n[1] * s.xx);
  for (int j = 0; j < 6; ++j) force_to_parent(n[j], s);
}

// P += X^T (M - U U^T / D) X for M given by its columns (overwritten), computed as
// X^T M X - Us Us^T / D with Us = X^T U: the shift of M does not wait for D, which keeps
// the division off the path from one body's articulated inertia to its parent's.
inline void add_shifted_minus_rank_one(SpatialVector (&n)[6], const SpatialVector& Us, double Dinv, const Shift& s,
                                       Matrix6& P) {
  const double us[6] = {Us.p[0][0], Us.p[0][1], Us.p[1][0], Us.p[1][1], Us.p[2][0], Us.p[2][1]};
  shift_inertia(n, s);
  for (int j = 0; j < 6; ++j) store_pairs(P.data() + 6 * j, column(P, j) + (n[j] - Us * splat(us[j] * Dinv)));
}

// The same for M given as a matrix (its columns loaded first).
inline void add_shifted_minus_rank_one(const Matrix6& M, const SpatialVector& Us, double Dinv, const Shift& s,
                                       Matrix6& P) {
  SpatialVector n[6];
  for (int j = 0; j < 6; ++j) n[j] = column(M, j);
  add_shifted_minus_rank_one(n, Us, Dinv, s, P);
}

// P += X^T M X (shift_inertia) for M given as a matrix.
inline void add_shifted(const Matrix6& M, const Shift& s, Matrix6& P) {
  SpatialVector n[6];
  for (int j = 0; j < 6; ++j) n[j] = column(M, j);
  shift_inertia(n, s);
  for (int j = 0; j < 6; ++j) store_pairs(P.data() + 6 * j, column(P, j) + n[j]);
}

}  // namespace achd
