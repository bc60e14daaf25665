#pragma once
// The URDF-loading options of `achd solve`, `achd bench` and `achd info`: --mimic
// error|independent, --lock JOINT=VALUE (repeatable: a chain's side joint held at VALUE),
// --floating (a free joint between the world and the root link) and --convention kdl,
// which loads a chain as KDL does (side branches ignored).
#include <set>
#include <string>

#include "achd/urdf.hpp"
#include "args.hpp"

namespace achd::cli {

// The option names urdf_options() reads (besides --convention, a solver option).
extern const std::set<std::string> kUrdfValued;
extern const std::set<std::string> kUrdfFlags;  // --floating

UrdfOptions urdf_options(const Args& args);

}  // namespace achd::cli
