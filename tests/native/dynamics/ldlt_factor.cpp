// The LDL^T factor of a dense coupling matrix K, of run-time size (Ldlt<0>, factorised
// right-looking, two rows to a Pair) and of the fixed sizes the solves use (Ldlt<12>, the
// floating quadruped's and humanoid's K, and Ldlt<15>, the Delta robot's five loops: two
// rows of a column to a Pair), against the left-looking sums written out here: L and the
// pivots equal to the bit (each entry takes the same terms in the same order), for every
// size from 7 to the capacity, odd and even; a K that is not positive definite is refused
// at the same pivot.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>

#include "kernels/ldlt.hpp"

namespace achd {
namespace {

// d_j = K_jj - sum_k L_jk W_jk;  L_ij = (K_ij - sum_k L_ik W_jk) / d_j, W_ik = L_ik d_k, k
// ascending: Ldlt's own equations, in its order. Returns the first pivot that is not
// positive, or n.
int left_looking(const CouplingMatrix& K, double L[][kMaxConstraintColumns], double* Dinv) {
  const int n = static_cast<int>(K.rows());
  double W[kMaxConstraintColumns][kMaxConstraintColumns];
  for (int j = 0; j < n; ++j) {
    double d = K(j, j);
    for (int k = 0; k < j; ++k) d -= L[j][k] * W[j][k];
    if (!(d > 0)) return j;
    Dinv[j] = 1 / d;
    for (int i = j + 1; i < n; ++i) {
      double w = K(i, j);
      for (int k = 0; k < j; ++k) w -= L[i][k] * W[j][k];
      W[i][j] = w;
      L[i][j] = w * Dinv[j];
    }
  }
  return n;
}

bool same_bits(double a, double b) {
  std::uint64_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

// A random dense K = A A^T + 1e-3 I (every entry nonzero), n x n.
CouplingMatrix random_coupling(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd A(n, n + 2);
  for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = u(rng);
  CouplingMatrix K = A * A.transpose();
  K.diagonal().array() += 1e-3;
  return K;
}

// f's L (by columns: f.L[j][i] = L_ij) and pivots against the left-looking sums, bit for
// bit, and f solving K x = b.
template <int N>
void expect_left_looking_factor(const CouplingMatrix& K) {
  const int n = static_cast<int>(K.rows());
  Ldlt<N> f;
  ASSERT_TRUE(f.factor(K)) << "n = " << n;
  double L[kMaxConstraintColumns][kMaxConstraintColumns], Dinv[kMaxConstraintColumns];
  ASSERT_EQ(left_looking(K, L, Dinv), n);
  for (int j = 0; j < n; ++j) {
    EXPECT_TRUE(same_bits(f.Dinv[j], Dinv[j])) << "N = " << N << ", n = " << n << ", pivot " << j;
    for (int i = j + 1; i < n; ++i)
      EXPECT_TRUE(same_bits(f.L[j][i], L[i][j])) << "N = " << N << ", n = " << n << ", L(" << i << ", " << j << ")";
  }
  ConstraintVector b = ConstraintVector::Ones(n), x;
  f.solve(b, x);
  EXPECT_LT((K * x - b).norm(), 1e-8 * (K.norm() * x.norm() + b.norm())) << "N = " << N << ", n = " << n;
}

TEST(LdltFactor, DenseFactorOfEverySizeIsTheLeftLookingFactorToTheBit) {
  std::mt19937_64 rng(7);
  for (int n = 7; n <= kMaxConstraintColumns; ++n)
    for (int trial = 0; trial < 4; ++trial) {
      const CouplingMatrix K = random_coupling(rng, n);
      expect_left_looking_factor<0>(K);
      if (n == 12) expect_left_looking_factor<12>(K);
      if (n == 15) expect_left_looking_factor<15>(K);
    }
}

TEST(LdltFactor, DenseFactorRefusesAKThatIsNotPositiveDefinite) {
  std::mt19937_64 rng(11);
  for (int n : {7, 8, 15, 36})
    for (int bad : {0, 1, n / 2, n - 2, n - 1}) {
      // K_bb lowered by 10 |K|: pivot `bad` (at most K_bb) turns negative, every earlier one
      // is unchanged.
      CouplingMatrix K = random_coupling(rng, n);
      K(bad, bad) -= 10 * K.norm();
      Ldlt<0> f;
      double L[kMaxConstraintColumns][kMaxConstraintColumns], Dinv[kMaxConstraintColumns];
      EXPECT_EQ(left_looking(K, L, Dinv), bad) << "n = " << n;
      EXPECT_FALSE(f.factor(K)) << "n = " << n << ", pivot " << bad;
    }
}

}  // namespace
}  // namespace achd
