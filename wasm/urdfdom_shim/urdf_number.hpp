#pragma once
// The numbers a URDF may contain, as Debian's native urdfdom reads them, for the wasm
// build to read the same ones. urdfdom reads every number with urdf::strToDouble
// (urdf_model/utils.h): `std::stringstream >> double` in the C locale, all of the text
// read. Natively that is libstdc++'s num_get: white space, then an optional sign, digits
// with at most one '.', at least one digit, an optional exponent ('e' or 'E', optional
// sign, digits); the value is strtod's; a value that overflows is refused, one that
// underflows (to a denormal such as 4e-320, or to 0) is kept. Emscripten's libc++ refuses
// underflow too (errno ERANGE) and accepts "nan", "inf" and hex floats: the same URDF
// loaded in one build and not in the other. tests/native/io/urdf_number.cpp checks this
// function against the native urdf::strToDouble.
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace achd {

// True, with the value in `out`, when native urdfdom accepts `text` as a number.
inline bool parse_urdf_number(const char* text, double& out) {
  auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  const char* p = text;
  while (std::isspace(static_cast<unsigned char>(*p))) ++p;
  const char* number = p;
  if (*p == '+' || *p == '-') ++p;
  bool mantissa = false;
  for (; digit(*p); ++p) mantissa = true;
  if (*p == '.')
    for (++p; digit(*p); ++p) mantissa = true;
  if (!mantissa) return false;
  if (*p == 'e' || *p == 'E') {
    ++p;
    if (*p == '+' || *p == '-') ++p;
    if (!digit(*p)) return false;
    while (digit(*p)) ++p;
  }
  if (*p) return false;
  out = std::strtod(number, nullptr);
  return std::isfinite(out);
}

}  // namespace achd
