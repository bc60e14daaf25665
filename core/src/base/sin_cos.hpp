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
// first order. The result is within 1 ulp of the exact value (tests/native/kinematics/sin_cos.cpp
// checks it against long double). Beyond |x| = 1e5 rad, where k no longer fits the exact
// products, it falls back to std::sin and std::cos.
//
// The same arithmetic also runs on a Pair of angles (pair.hpp), lane by lane, so that two
// joints cost one evaluation and give the bits of two separate ones.
#include <cmath>

#include "pair.hpp"

namespace achd {
namespace sin_cos_detail {

constexpr double kLimit = 1e5;                       // |k| < 2^17: k * kPio2Hi is exact
constexpr double kTwoOverPi = 0.6366197723675814;
constexpr double kPio2Hi = 0x1.921fb54400000p+0;     // pi/2: the first 33 bits,
constexpr double kPio2Mid = 0x1.0b4611a600000p-34;   // the next 33 bits,
constexpr double kPio2Lo = 0x1.3198a2e037073p-69;    // the rest
constexpr double kRound = 0x1.8p52;                  // adding it rounds to an integer

inline double constant(double c, double) { return c; }
inline Pair constant(double c, Pair) { return splat(c); }

// sin r and cos r of the reduced argument, and k: x = k pi/2 + r, for a double or a Pair
// (|x| < kLimit).
template <typename T>
void reduced_sin_cos(T x, T& sr, T& cr, T& k) {
  auto C = [](double c) { return constant(c, T{}); };
  k = (x * C(kTwoOverPi) + C(kRound)) - C(kRound);  // nearest integer to x / (pi/2)
  // r + r_lo = x - k pi/2: y is exact (Sterbenz), so is t; r_lo gathers the rounding
  // error of y - t (exact for |y| >= |t|) and the last part of pi/2.
  const T y = x - k * C(kPio2Hi), t = k * C(kPio2Mid);
  const T r = y - t;
  const T r_lo = ((y - r) - t) - k * C(kPio2Lo);
  const T z = r * r, z2 = z * z, z4 = z2 * z2;
  // Both series as polynomials in z, evaluated by Estrin's scheme (pairs, then z^2 and
  // z^4) so that the chain of dependent operations stays short.
  // sin r = r + r z (-1/3! + z/5! - z^2/7! + ... + z^7/17!)
  const T ps = (C(-1.0 / 6) + z * C(1.0 / 120)) + z2 * (C(-1.0 / 5040) + z * C(1.0 / 362880)) +
               z4 * ((C(-1.0 / 39916800) + z * C(1.0 / 6227020800)) +
                     z2 * (C(-1.0 / 1307674368000) + z * C(1.0 / 355687428096000)));
  sr = r + (r * z * ps + r_lo * (C(1.0) - C(0.5) * z));  // + cos(r) r_lo
  // cos r = 1 - z/2 + z^2 (1/4! - z/6! + ... - z^7/18!); 1 - z/2 is rounded to w and its
  // rounding error (1 - w) - z/2 added back, so the sum loses no bit to that subtraction.
  const T pc = (C(1.0 / 24) + z * C(-1.0 / 720)) + z2 * (C(1.0 / 40320) + z * C(-1.0 / 3628800)) +
               z4 * ((C(1.0 / 479001600) + z * C(-1.0 / 87178291200)) +
                     z2 * (C(1.0 / 20922789888000) + z * C(-1.0 / 6402373705728000)));
  const T hz = C(0.5) * z;
  const T w = C(1.0) - hz;
  cr = w + (((C(1.0) - w) - hz) + (z2 * pc - r * r_lo));  // - sin(r) r_lo
}

// sin(k pi/2 + r), cos(k pi/2 + r) by the quadrant k mod 4.
inline void quadrant(double k, double sr, double cr, double& s, double& c) {
  switch (static_cast<long>(k) & 3) {
    case 0: s = sr, c = cr; break;
    case 1: s = cr, c = -sr; break;
    case 2: s = -sr, c = -cr; break;
    default: s = -cr, c = sr; break;
  }
}

}  // namespace sin_cos_detail

inline void sin_cos(double x, double& s, double& c) {
  using namespace sin_cos_detail;
  if (!(std::abs(x) < kLimit)) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  double sr, cr, k;
  reduced_sin_cos(x, sr, cr, k);
  quadrant(k, sr, cr, s, c);
}

// Two angles at once: s[j], c[j] = sin x[j], cos x[j], the bits of sin_cos(x[j]).
inline void sin_cos(const double (&x)[2], double (&s)[2], double (&c)[2]) {
  using namespace sin_cos_detail;
  if (!(std::abs(x[0]) < kLimit && std::abs(x[1]) < kLimit)) {
    sin_cos(x[0], s[0], c[0]);
    sin_cos(x[1], s[1], c[1]);
    return;
  }
  Pair sr, cr, k;
  reduced_sin_cos(Pair{x[0], x[1]}, sr, cr, k);
  quadrant(k[0], sr[0], cr[0], s[0], c[0]);
  quadrant(k[1], sr[1], cr[1], s[1], c[1]);
}

}  // namespace achd
