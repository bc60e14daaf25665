// achd::sin_cos against long double sinl/cosl: within 1 ulp over joint-angle ranges up
// to the reduction limit, exact at the quadrant points' signs, and std::sin/std::cos past
// it; the two-angle form against the one-angle form, bit for bit.
#include "sin_cos.hpp"  // achd_internals

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace {

double ulp_error(double got, long double exact) {
  const double e = static_cast<double>(exact);
  const double ulp = std::nextafter(std::abs(e), INFINITY) - std::abs(e);
  return static_cast<double>(std::abs(static_cast<long double>(got) - exact)) / ulp;
}

TEST(SinCos, WithinOneUlpOfLongDouble) {
  for (double range : {0.78, 4.0, 100.0, 1e4, 99999.0}) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> angle(-range, range);
    double worst_s = 0, worst_c = 0;
    for (int i = 0; i < 200000; ++i) {
      const double x = angle(rng);
      double s, c;
      achd::sin_cos(x, s, c);
      worst_s = std::max(worst_s, ulp_error(s, sinl(static_cast<long double>(x))));
      worst_c = std::max(worst_c, ulp_error(c, cosl(static_cast<long double>(x))));
    }
    EXPECT_LT(worst_s, 1.0) << "sin, |x| < " << range;
    EXPECT_LT(worst_c, 1.0) << "cos, |x| < " << range;
  }
}

TEST(SinCos, TinyAnglesAndQuadrants) {
  double s, c;
  achd::sin_cos(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  achd::sin_cos(1e-300, s, c);
  EXPECT_EQ(s, 1e-300);
  EXPECT_EQ(c, 1.0);
  // k pi/2 for k = 1..4 and negatives: the signs of the quadrant table.
  const double pi = 3.14159265358979323846;
  achd::sin_cos(pi / 2, s, c);
  EXPECT_NEAR(s, 1.0, 1e-16);
  EXPECT_NEAR(c, 0.0, 1e-16);
  achd::sin_cos(pi, s, c);
  EXPECT_NEAR(s, 0.0, 1e-15);
  EXPECT_NEAR(c, -1.0, 1e-16);
  achd::sin_cos(-pi / 2, s, c);
  EXPECT_NEAR(s, -1.0, 1e-16);
  EXPECT_NEAR(c, 0.0, 1e-16);
  achd::sin_cos(3 * pi / 2, s, c);
  EXPECT_NEAR(s, -1.0, 1e-16);
  EXPECT_NEAR(c, 0.0, 1e-15);
}

TEST(SinCos, LargeAnglesFallBackToLibm) {
  for (double x : {1e5, -2.5e5, 1e9, 1e300}) {
    double s, c;
    achd::sin_cos(x, s, c);
    EXPECT_EQ(s, std::sin(x)) << x;
    EXPECT_EQ(c, std::cos(x)) << x;
  }
}

// The two-angle form (body_poses evaluates joints two at a time) gives the bits of two
// one-angle calls, in every quadrant, at 0, and when either angle needs the libm fallback.
TEST(SinCos, TwoAnglesGiveTheBitsOfTwoCalls) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-50.0, 50.0);
  std::vector<double> xs = {0.0, -0.0, 1e-300, 1e5, -3e5, 1e300};
  for (int i = 0; i < 10000; ++i) xs.push_back(angle(rng));
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    const double x[2] = {xs[i], xs[i + 1]};
    double s[2], c[2], s1, c1;
    achd::sin_cos(x, s, c);
    for (int j = 0; j < 2; ++j) {
      achd::sin_cos(x[j], s1, c1);
      ASSERT_EQ(std::memcmp(&s[j], &s1, sizeof s1), 0) << "sin " << x[j];
      ASSERT_EQ(std::memcmp(&c[j], &c1, sizeof c1), 0) << "cos " << x[j];
    }
  }
}

}  // namespace
