#pragma once
// The free joint's 6-DoF step (free_joint_constraints.cpp) two columns at a time: with
// IA_r = L L^T, the columns y = L^-1 x of the blocks' forces at the root and of the bias
// wrench by forward substitution, and the dot products y_s . y_t of K and G_0. Each lane
// takes the scalar code's operations in the scalar code's order, so the results are the
// scalar code's to the bit (native and wasm alike).
#include "achd/case.hpp"
#include "pair.hpp"

namespace achd {

// Y[i][c]: component i of column c, for up to kMaxConstraintColumns + 2 columns (the
// blocks' m, the bias wrench, and a zero column that makes the count even).
struct RootColumns {
  static constexpr int kCapacity = kMaxConstraintColumns + 2;
  double Y[6][kCapacity];
  int count = 0;  // even

  // Y[i][s] = F(i, s) for the 6 x m columns F (column-major, 6 numbers a column): two
  // columns at a time, each pair of rows of the two taken apart into Y's rows.
  void set_columns(const double* F, int m) {
    int s = 0;
    for (; s + 1 < m; s += 2)
      for (int i = 0; i < 6; i += 2) {
        const Pair a = load_pair(F + 6 * s + i), b = load_pair(F + 6 * s + 6 + i);
        store_pair(&Y[i][s], low_lanes(a, b));
        store_pair(&Y[i + 1][s], high_lanes(a, b));
      }
    if (s < m)
      for (int i = 0; i < 6; ++i) Y[i][s] = F[6 * s + i];
  }

  // y_c = L^-1 y_c for every column, in place, L lower triangular (6 x 6, row-major):
  //   y_i = (x_i - sum_{k<i} L_ik y_k) / L_ii.
  void forward(const double (&L)[6][6]) {
    for (int c = 0; c < count; c += 2) {
      Pair y[6];
      for (int i = 0; i < 6; ++i) {
        Pair x = load_pair(&Y[i][c]);
        for (int k = 0; k < i; ++k) x -= splat(L[i][k]) * y[k];
        y[i] = x / splat(L[i][i]);
        store_pair(&Y[i][c], y[i]);
      }
    }
  }

  // (y_s . y_t, y_s . y_t+1), summed from component 0 to 5.
  Pair dots(int s, int t) const {
    Pair sum = splat(Y[0][s]) * load_pair(&Y[0][t]);
    for (int i = 1; i < 6; ++i) sum += splat(Y[i][s]) * load_pair(&Y[i][t]);
    return sum;
  }
  // (y_s . y_b, y_s+1 . y_b), b a column.
  Pair dots_with(int s, int b) const {
    Pair sum = load_pair(&Y[0][s]) * splat(Y[0][b]);
    for (int i = 1; i < 6; ++i) sum += load_pair(&Y[i][s]) * splat(Y[i][b]);
    return sum;
  }
};

}  // namespace achd
