#pragma once
// Two doubles operated on together: the vector type that gcc and clang share, on SSE2
// natively (every x86-64 has it) and on wasm SIMD in the wasm build (-msimd128); two
// plain doubles where neither is available. Every operation is lane by lane, so the
// rounding is the scalar code's either way: native and wasm agree to the bit (the Node
// parity tests check it, which matters: Emscripten 3.1.6's clang has miscompiled code
// around these, see spatial.cpp).
#include <cstring>

namespace achd {

#if defined(__SSE2__) || defined(__wasm_simd128__)

typedef double Pair __attribute__((vector_size(16)));

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
// (a[0], b[1]) and (a[1], b[0])
inline Pair blend(Pair a, Pair b) { return __builtin_shufflevector(a, b, 0, 3); }
inline Pair cross_lanes(Pair a, Pair b) { return __builtin_shufflevector(a, b, 1, 2); }

#else

struct Pair {
  double lane[2];
  double operator[](int k) const { return lane[k]; }
};
inline Pair operator+(Pair a, Pair b) { return {{a.lane[0] + b.lane[0], a.lane[1] + b.lane[1]}}; }
inline Pair operator-(Pair a, Pair b) { return {{a.lane[0] - b.lane[0], a.lane[1] - b.lane[1]}}; }
inline Pair operator*(Pair a, Pair b) { return {{a.lane[0] * b.lane[0], a.lane[1] * b.lane[1]}}; }
inline Pair operator/(Pair a, Pair b) { return {{a.lane[0] / b.lane[0], a.lane[1] / b.lane[1]}}; }
inline Pair& operator+=(Pair& a, Pair b) { return a = a + b; }
inline Pair& operator-=(Pair& a, Pair b) { return a = a - b; }
inline Pair& operator*=(Pair& a, Pair b) { return a = a * b; }
inline Pair load_pair(const double* p) { return {{p[0], p[1]}}; }
inline void store_pair(double* p, Pair v) { p[0] = v.lane[0], p[1] = v.lane[1]; }
inline Pair swapped(Pair a) { return {{a.lane[1], a.lane[0]}}; }
inline Pair low_lanes(Pair a, Pair b) { return {{a.lane[0], b.lane[0]}}; }
inline Pair high_lanes(Pair a, Pair b) { return {{a.lane[1], b.lane[1]}}; }
inline Pair blend(Pair a, Pair b) { return {{a.lane[0], b.lane[1]}}; }
inline Pair cross_lanes(Pair a, Pair b) { return {{a.lane[1], b.lane[0]}}; }

#endif

inline Pair splat(double x) { return Pair{x, x}; }

}  // namespace achd
