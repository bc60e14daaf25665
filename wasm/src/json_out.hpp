#pragma once
// JSON text the module hands to JS (the robot's description and links): a string quoted
// and escaped, and a finite number with 17 significant digits (a number that is not
// finite cannot be handed to JS: an achd::Error instead).
#include <cmath>
#include <cstdio>
#include <string>

#include "achd/error.hpp"

namespace achd::wasm {

inline std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", ch);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

inline std::string number(double x) {
  if (!std::isfinite(x)) throw Error("a number that is not finite");
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace achd::wasm
