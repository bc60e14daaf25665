#pragma once
// sin and cos of one joint angle, computed together by the same arithmetic on every
// platform. glibc's and musl's (wasm) sin and cos differ in the last bit for some
// arguments, so a joint rotation built from them differs between the native and the wasm
// build; this one gives identical bits on both, and costs a few nanoseconds instead of
// the ~30 ns of a libm sin + cos pair here.
//
// Method (Cody and Waite): x = k pi/2 + r + r_lo with |r| <= pi/4, from pi/2 split into
// parts whose products with k are exact; then the Taylor series of sin r and cos r,
// which on |r| <= pi/4 are truncated past the last ulp: (pi/4)^19 / 19! < 1e-19 for sin
// (terms to r^17), (pi/4)^20 / 20! < 4e-21 for cos (terms to r^18), with r_lo added to
// first order. The result is within 1 ulp of the exact value (tests/native/sin_cos.cpp
// checks it against long double). Beyond |x| = 1e5 rad, where k no longer fits the exact
// products, it falls back to std::sin and std::cos.
#include <cmath>

namespace achd {

inline void sin_cos(double x, double& s, double& c) {
  constexpr double kLimit = 1e5;                       // |k| < 2^17: k * kPio2Hi is exact
  constexpr double kTwoOverPi = 0.6366197723675814;
  constexpr double kPio2Hi = 0x1.921fb54400000p+0;     // pi/2: the first 33 bits,
  constexpr double kPio2Mid = 0x1.0b4611a600000p-34;   // the next 33 bits,
  constexpr double kPio2Lo = 0x1.3198a2e037073p-69;    // the rest
  constexpr double kRound = 0x1.8p52;                  // adding it rounds to an integer
  if (!(std::abs(x) < kLimit)) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  const double k = (x * kTwoOverPi + kRound) - kRound;  // nearest integer to x / (pi/2)
  // r + r_lo = x - k pi/2: y is exact (Sterbenz), so is t; r_lo gathers the rounding
  // error of y - t (exact for |y| >= |t|) and the last part of pi/2.
  const double y = x - k * kPio2Hi, t = k * kPio2Mid;
  const double r = y - t;
  const double r_lo = ((y - r) - t) - k * kPio2Lo;
  const double z = r * r, z2 = z * z, z4 = z2 * z2;
  // Both series as polynomials in z, evaluated by Estrin's scheme (pairs, then z^2 and
  // z^4) so that the chain of dependent operations stays short.
  // sin r = r + r z (-1/3! + z/5! - z^2/7! + ... + z^7/17!)
  const double ps = (-1.0 / 6 + z * (1.0 / 120)) + z2 * (-1.0 / 5040 + z * (1.0 / 362880)) +
                    z4 * ((-1.0 / 39916800 + z * (1.0 / 6227020800)) +
                          z2 * (-1.0 / 1307674368000 + z * (1.0 / 355687428096000)));
  const double sr = r + (r * z * ps + r_lo * (1.0 - 0.5 * z));  // + cos(r) r_lo
  // cos r = 1 - z/2 + z^2 (1/4! - z/6! + ... - z^7/18!); 1 - z/2 is rounded to w and its
  // rounding error (1 - w) - z/2 added back, so the sum loses no bit to that subtraction.
  const double pc = (1.0 / 24 + z * (-1.0 / 720)) + z2 * (1.0 / 40320 + z * (-1.0 / 3628800)) +
                    z4 * ((1.0 / 479001600 + z * (-1.0 / 87178291200)) +
                          z2 * (1.0 / 20922789888000 + z * (-1.0 / 6402373705728000)));
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  const double cr = w + (((1.0 - w) - hz) + (z2 * pc - r * r_lo));  // - sin(r) r_lo
  // sin(k pi/2 + r), cos(k pi/2 + r) by the quadrant k mod 4.
  switch (static_cast<long>(k) & 3) {
    case 0: s = sr, c = cr; break;
    case 1: s = cr, c = -sr; break;
    case 2: s = -sr, c = -cr; break;
    default: s = -cr, c = sr; break;
  }
}

}  // namespace achd
