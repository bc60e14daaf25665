#pragma once
// The URDF-loading options of `achd solve` and `achd bench`: --mimic error|independent.
#include <set>
#include <string>

#include "achd/urdf.hpp"
#include "args.hpp"

namespace achd::cli {

// The option names urdf_options() reads.
extern const std::set<std::string> kUrdfValued;

UrdfOptions urdf_options(const Args& args);

}  // namespace achd::cli
