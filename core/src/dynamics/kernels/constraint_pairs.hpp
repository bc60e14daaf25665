#pragma once
// The constraint part of the sweeps on pairs (pair.hpp), for nc = NC constraints (a
// template parameter, so that the loops over the columns unroll; constraint_count.hpp
// dispatches). Two constraint columns share a Pair: column pair j holds columns 2j and
// 2j + 1, so that a row of a column pair is one Pair, every update is the same pair
// product for every row, and the column pairs are independent chains the processor
// overlaps. When NC is odd the second lane of the last pair is 0, and every update keeps
// it 0; the EZ_i that the inward pass writes therefore have a 0 in that slot, which
// ConstraintMagnitudes::dot relies on.
#include "achd/case.hpp"
#include "joint_subspace.hpp"

namespace achd {

// Where a block of NC columns keeps its EZ_i: 2 NP doubles per body (the last pair's
// second lane 0 when NC is odd).
template <int NC>
constexpr int ez_stride() {
  return 2 * ((NC + 1) / 2);
}

// The unit constraint forces E (6 x NC) of one block, rolled from its body to the base.
template <int NC>
struct UnitConstraintForces {
  static constexpr int NP = (NC + 1) / 2;
  Pair E[NP][6];  // E[j][row] = (E(row, 2j), E(row, 2j + 1))

  // M: the block's columns, 6 x NC column-major (a column is 6 doubles).
  explicit UnitConstraintForces(const double* M) {
    for (int j = 0; j < NP; ++j)
      for (int row = 0; row < 6; ++row)
        E[j][row] = Pair{M[12 * j + row], 2 * j + 1 < NC ? M[12 * j + 6 + row] : 0.0};
  }

  void store(double* M) const {
    for (int j = 0; j < NP; ++j)
      for (int row = 0; row < 6; ++row) {
        M[12 * j + row] = E[j][row][0];
        if (2 * j + 1 < NC) M[12 * j + 6 + row] = E[j][row][1];
      }
  }

  // A relative block's columns at its second point from those at its first: the opposite
  // forces, their moments taken about a point `d` further (rows 3..5 += d x rows 0..2):
  //   E_b = -[f; n + d x f],  d = arm_b - arm (both bodies' origins in base axes).
  UnitConstraintForces opposite_moved(const Vector3& d) const {
    UnitConstraintForces o = *this;
    const Pair d0 = splat(d[0]), d1 = splat(d[1]), d2 = splat(d[2]), minus = splat(-1);
    for (int j = 0; j < NP; ++j) {
      Pair* e = o.E[j];
      e[3] += d1 * e[2] - d2 * e[1];
      e[4] += d2 * e[0] - d0 * e[2];
      e[5] += d0 * e[1] - d1 * e[0];
      for (int row = 0; row < 6; ++row) e[row] = e[row] * minus;
    }
    return o;
  }

  // Where a relative block's two legs meet: their forces at one origin add up.
  void add(const UnitConstraintForces& other) {
    for (int j = 0; j < NP; ++j)
      for (int row = 0; row < 6; ++row) E[j][row] += other.E[j][row];
  }

  // One body of Vereshchagin's eq. (c), with U = IA S and Dinv = 1 / D of the body and r
  // its shift from the parent's origin:
  //   EZ = E^T S (written to ez, 2 NP doubles);  E <- E - U EZ^T / D;
  // then E moves to the parent's origin (rows 3..5 += r x rows 0..2). Always inlined: with
  // a relative block's legs it has three callers, and a call per body would cost more
  // than its body.
  __attribute__((always_inline)) void pass_to_parent(const JointSubspace& S, const Vector6& U, double Dinv,
                                                    const Vector3& r, double* ez) {
    const int o = S.first_row();
    const Pair z0 = splat(S.z[0]), z1 = splat(S.z[1]), z2 = splat(S.z[2]), Dinv2 = splat(Dinv);
    const Pair r0 = splat(r[0]), r1 = splat(r[1]), r2 = splat(r[2]);
    // (U read once for three pairs and more: ez may alias it, so each read after a store to
    // ez is repeated; with two pairs the register pressure of holding it costs more)
    Pair u[6];
    if constexpr (NP >= 3)
      for (int row = 0; row < 6; ++row) u[row] = splat(U[row]);
    for (int j = 0; j < NP; ++j) {
      Pair* e = E[j];
      const Pair e_z = (e[o] * z0 + e[o + 1] * z1) + e[o + 2] * z2;
      store_pair(ez + 2 * j, e_z);
      const Pair ezd = e_z * Dinv2;
      for (int row = 0; row < 6; ++row) e[row] -= (NP >= 3 ? u[row] : splat(U[row])) * ezd;
      e[3] += r1 * e[2] - r2 * e[1];
      e[4] += r2 * e[0] - r0 * e[2];
      e[5] += r0 * e[1] - r1 * e[0];
    }
  }
};

// The sums of Vereshchagin's eqs. (d) and (e) over the bodies, from each body's EZ:
//   K = -M_0 = sum_i EZ_i EZ_i^T / D_i,   G_0 = sum_i EZ_i known_i,
// known_i = u_i / D_i (a free joint's acceleration at a~_p = 0, nu = 0) or a prescribed
// joint's given qdd; two rows to a Pair; K's lower triangle only (it is symmetric).
template <int NC>
struct CouplingSums {
  static constexpr int NP = (NC + 1) / 2;
  Pair K[NC][NP], G[NP];  // K[k][j] = (K(k, 2j), K(k, 2j + 1)), G[j] = (G(2j), G(2j + 1))

  CouplingSums() {
    for (int j = 0; j < NP; ++j) {
      G[j] = splat(0);
      for (int k = 0; k < NC; ++k) K[k][j] = splat(0);
    }
  }

  void add(const double* ez, double Dinv, double known) {
    for (int k = 0; k < NC; ++k) {
      const Pair s = splat(ez[k] * Dinv);
      for (int j = k / 2; j < NP; ++j) K[k][j] += load_pair(ez + 2 * j) * s;
    }
    const Pair s = splat(known);
    for (int j = 0; j < NP; ++j) G[j] += load_pair(ez + 2 * j) * s;
  }

  // Writes the block's diagonal block of K (both triangles), rows and columns from `at`,
  // and its G_0; returns the block's finite probe (finite_probe.hpp).
  double store(CouplingMatrix& K_out, ConstraintVector& G_out, int at) const {
    Pair probe = splat(0);
    for (int k = 0; k < NC; ++k) {
      G_out[at + k] = G[k / 2][k % 2];
      for (int l = k; l < NC; ++l) K_out(at + l, at + k) = K_out(at + k, at + l) = K[k][l / 2][l % 2];
      for (int j = k / 2; j < NP; ++j) probe += K[k][j] * splat(0);
    }
    return probe[0] + probe[1];
  }
};

// A block's NC constraint values (such as its magnitudes nu), two to a Pair, 0 past NC.
template <int NC>
struct ConstraintMagnitudes {
  static constexpr int NP = (NC + 1) / 2;
  Pair x[NP];

  explicit ConstraintMagnitudes(const double* v) {
    for (int k = 0; k < NC; k += 2) x[k / 2] = Pair{v[k], k + 1 < NC ? v[k + 1] : 0.0};
  }

  // ez^T x for a body's EZ (two columns at a time: ez's last pair has 0 in its second lane
  // when NC is odd, as x has).
  double dot(const double* ez) const {
    Pair s = splat(0);
    for (int j = 0; j < NP; ++j) s += load_pair(ez + 2 * j) * x[j];
    return s[0] + s[1];
  }
};

}  // namespace achd
