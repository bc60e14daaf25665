#pragma once
// The one exception type of achd: thrown for bad input (URDF, case, options) with a
// message that names the problem (file, field, index). The library never aborts.
#include <stdexcept>
#include <string>

namespace achd {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace achd
