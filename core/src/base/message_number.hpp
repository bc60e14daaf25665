#pragma once
// Numbers in the simulator's error messages: up to 15 significant digits, so that
// 2183 * 0.001 reads 2.183.
#include <cmath>
#include <cstdio>
#include <string>

namespace achd {

inline std::string message_number(double x) {
  if (std::isnan(x)) return "NaN";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", x);
  return buf;
}

}  // namespace achd
