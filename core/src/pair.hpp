#pragma once
// Two doubles operated on together (SSE2 natively, wasm's f64x2 or plain scalars in the
// wasm build), through the vector extension that gcc and clang share. Every operation is
// lane by lane, so the rounding is that of the scalar code: native and wasm results
// agree to the bit whether or not a build uses SIMD.
#include <cstring>

namespace achd {

typedef double Pair __attribute__((vector_size(16)));

inline Pair splat(double x) { return Pair{x, x}; }

inline Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store_pair(double* p, Pair v) { std::memcpy(p, &v, sizeof v); }

// (a[1], a[0])
inline Pair swapped(Pair a) { return __builtin_shufflevector(a, a, 1, 0); }
// (a[0], b[0]) and (a[1], b[1])
inline Pair low_lanes(Pair a, Pair b) { return __builtin_shufflevector(a, b, 0, 2); }
inline Pair high_lanes(Pair a, Pair b) { return __builtin_shufflevector(a, b, 1, 3); }

}  // namespace achd
