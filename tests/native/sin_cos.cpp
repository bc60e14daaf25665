// achd::sin_cos against long double sinl/cosl: within 1 ulp over joint-angle ranges up
// to the reduction limit, exact at the quadrant points' signs, and std::sin/std::cos past it.
#include "../../core/src/sin_cos.hpp"

#include <cmath>
#include <random>

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

}  // namespace
