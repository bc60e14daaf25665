#pragma once
// The URDF-loading options of `achd solve`, `achd bench` and `achd info`: --mimic
// error|independent, --inertia accept|strict|repair, --lock JOINT=VALUE (repeatable: a
// joint held at VALUE), --floating (a free joint between the world and the root link),
// --loops FILE (loop joints, loops_json.hpp)
// and --convention kdl, which loads a chain as KDL does (side branches ignored).
#include <set>
#include <string>

#include "achd/urdf.hpp"
#include "args.hpp"

namespace achd::cli {

// The option names urdf_options() reads (besides --convention, a solver option).
extern const std::set<std::string> kUrdfValued;
extern const std::set<std::string> kUrdfFlags;  // --floating

UrdfOptions urdf_options(const Args& args);

// Loads the URDF at `path` with the root, tip and loading options of `args`, printing
// each of the loader's warnings (Model::warnings) on stderr as "achd: warning: ...".
Model load_robot(const std::string& path, const Args& args);

// Prints a model's warnings on stderr, one "achd: warning: PATH: ..." line each.
void print_warnings(const Model& model, const std::string& path);

}  // namespace achd::cli
