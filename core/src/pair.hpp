#pragma once
// Two doubles operated on together. Natively (x86-64's SSE2, which every 64-bit x86 has)
// a Pair is the vector type that gcc and clang share. In the wasm build it is two plain
// doubles, which clang's own vectoriser maps onto wasm SIMD (-msimd128): Emscripten
// 3.1.6 miscompiled the vector-type version there (the Node parity tests caught it).
// Every operation is lane by lane, so the rounding is the scalar code's either way:
// native and wasm agree to the bit.
#include <cstring>

namespace achd {

#if defined(__SSE2__)

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

#else

struct Pair {
  double lane[2];
  double operator[](int k) const { return lane[k]; }
};
inline Pair operator+(Pair a, Pair b) { return {{a.lane[0] + b.lane[0], a.lane[1] + b.lane[1]}}; }
inline Pair operator-(Pair a, Pair b) { return {{a.lane[0] - b.lane[0], a.lane[1] - b.lane[1]}}; }
inline Pair operator*(Pair a, Pair b) { return {{a.lane[0] * b.lane[0], a.lane[1] * b.lane[1]}}; }
inline Pair& operator+=(Pair& a, Pair b) { return a = a + b; }
inline Pair& operator-=(Pair& a, Pair b) { return a = a - b; }
inline Pair& operator*=(Pair& a, Pair b) { return a = a * b; }
inline Pair load_pair(const double* p) { return {{p[0], p[1]}}; }
inline void store_pair(double* p, Pair v) { p[0] = v.lane[0], p[1] = v.lane[1]; }
inline Pair swapped(Pair a) { return {{a.lane[1], a.lane[0]}}; }
inline Pair low_lanes(Pair a, Pair b) { return {{a.lane[0], b.lane[0]}}; }
inline Pair high_lanes(Pair a, Pair b) { return {{a.lane[1], b.lane[1]}}; }

#endif

inline Pair splat(double x) { return Pair{x, x}; }

}  // namespace achd
