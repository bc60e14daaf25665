#pragma once
// URDF loading through urdfdom: the whole tree below a root link, or the chain between
// a root and a tip link with what hangs off it merged into the bodies it hangs from.
#include <map>
#include <string>

#include "achd/model.hpp"

namespace achd {

// What to do with a joint of the chain that has a <mimic> element (its position a
// multiple of another joint's, like the second finger of a parallel gripper): achd has
// no coupled joints, so by default such a URDF is refused, naming the joint; Independent
// loads it as a joint of its own, as KDL does.
enum class MimicJoints { Error, Independent };

// A chain's side branches (links hanging off the root-to-tip path): merged rigidly into
// the body they hang from, their movable joints locked (Model::locked_joints), so that no
// mass is lost; or ignored, as KDL's chain does (the CLI's --convention kdl).
enum class SideBranches { Merge, Ignore };

struct UrdfOptions {
  MimicJoints mimic = MimicJoints::Error;
  SideBranches side_branches = SideBranches::Merge;
  // Positions (rad or m) of the movable side joints of a chain that are locked; a side
  // joint not named here is locked at 0. Naming a joint that is not a movable side joint
  // of the loaded chain is an error.
  std::map<std::string, double> locked;
  // A floating base: a free joint between the world and the root link (Model::floating),
  // whose inertia then counts.
  bool floating = false;
};

// The name of a MimicJoints value in the CLI, JS and scene files ("error",
// "independent"), and back; the latter throws achd::Error naming `field` on another name.
const char* mimic_joints_name(MimicJoints mimic);
MimicJoints mimic_joints_from_name(const std::string& name, const std::string& field);

// Elements nested deeper than this are refused before the XML parser (which recurses
// once per level) sees them; robot descriptions nest 5 to 8 deep.
constexpr int kMaxUrdfNesting = 100;

// Builds the model of the chain root -> tip, or with an empty tip the tree of every link
// below root (an empty root: the URDF's root link), bodies in depth-first order (each
// body's subtree follows it). Throws achd::Error naming the file, link
// or joint on malformed XML, elements nested deeper than kMaxUrdfNesting, unknown links,
// a tip not below the root, unsupported joint types (floating, planar), mimic joints
// (unless options.mimic is Independent), non-physical inertias, geometry whose numbers
// overflow, or joints that move nothing.
Model load_urdf_file(const std::string& path, const std::string& root, const std::string& tip,
                     const UrdfOptions& options = {});
Model load_urdf_string(const std::string& xml, const std::string& root, const std::string& tip,
                       const UrdfOptions& options = {});

}  // namespace achd
