#pragma once
// Force-included (-include) into the wasm build of urdfdom and of achd's loader in place
// of urdfdom-headers' urdf_model/utils.h, whose include guard it takes: the same two
// functions, with strToDouble reading numbers as native urdfdom does (urdf_number.hpp).
// wasm/urdfdom.cmake adds it; the native build uses Debian's urdfdom as it is.
#define URDF_INTERFACE_UTILS_H

// The headers utils.h includes, which urdfdom's sources may rely on.
#include <locale>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "urdf_number.hpp"

namespace urdf {

// Appends to `result` the pieces of `input` between the characters of `separators`,
// empty ones included, the last one only if not empty (boost::split's replacement).
inline void split_string(std::vector<std::string>& result, const std::string& input,
                         const std::string& separators) {
  std::string::size_type start = 0;
  for (std::string::size_type end; (end = input.find_first_of(separators, start)) != std::string::npos;
       start = end + 1)
    result.push_back(input.substr(start, end - start));
  if (start < input.size()) result.push_back(input.substr(start));
}

// The number in `text`; throws std::runtime_error when it is not one.
inline double strToDouble(const char* text) {
  double value;
  if (!achd::parse_urdf_number(text, value)) throw std::runtime_error("Failed converting string to double");
  return value;
}

}  // namespace urdf
