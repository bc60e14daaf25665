#pragma once
// URDF loading through urdfdom: the whole tree below a root link, or the chain between
// a root and a tip link with what hangs off it merged into the bodies it hangs from.
#include <map>
#include <string>
#include <vector>

#include "achd/loops.hpp"
#include "achd/model.hpp"

namespace achd {

// How the loader takes the links' <inertial> elements (link_inertia.hpp has the rules):
// Accept (the default) loads every inertia whose dynamics are defined, a moment within
// the file's round-off of zero counting as zero and a violated triangle inequality loaded
// as written, each such link reported in Model::warnings, and holds a joint that moves no
// mass (its link and every link after it without inertia) as `locked` would, at 0 or the
// middle of its limits (a <mimic> group by its leader), reported in Model::warnings;
// Strict refuses all three; Repair makes each inertia physical with the least change and
// gives a body whose joint moves nothing a floor mass, reporting every change in
// Model::warnings.
enum class InertiaPolicy { Accept, Strict, Repair };

// What to do with a movable joint that has a <mimic> element (its position a multiple of
// another joint's, like the second finger of a parallel gripper): Couple (the default)
// holds q = multiplier q_leader + offset in every solve (Model::couplings); Independent
// loads it as a joint of its own, as KDL does; Error refuses the URDF, naming the joint.
enum class MimicJoints { Error, Independent, Couple };

// A chain's side branches (links hanging off the root-to-tip path): merged rigidly into
// the body they hang from, their movable joints locked (Model::locked_joints), so that no
// mass is lost; or ignored, as KDL's chain does (the CLI's --convention kdl).
enum class SideBranches { Merge, Ignore };

struct UrdfOptions {
  MimicJoints mimic = MimicJoints::Couple;
  SideBranches side_branches = SideBranches::Merge;
  // Positions (rad or m) of movable joints held fixed (Model::locked_joints): any joint of
  // the tree or chain named here, the <mimic> joints that follow one (at multiplier * value
  // + offset, unless named too), and a chain's side joints (unless named: locked at 0, or
  // the middle of their limits when 0 is outside them).
  // Naming a joint that is not a movable joint of what is loaded is an error.
  std::map<std::string, double> locked;
  // A floating base: a free joint between the world and the root link (Model::floating),
  // whose inertia then counts.
  bool floating = false;
  InertiaPolicy inertia = InertiaPolicy::Accept;
  // Loop joints closing loops of the tree (loops.hpp: add_loops), in Model::loops.
  std::vector<LoopJointSpec> loops;
};

// The name of a MimicJoints value in the CLI, JS and scene files ("couple",
// "independent", "error"), and back; the latter throws achd::Error naming `field` on another name.
const char* mimic_joints_name(MimicJoints mimic);
MimicJoints mimic_joints_from_name(const std::string& name, const std::string& field);

// The name of an InertiaPolicy value in the CLI, JS and scene files ("accept", "strict",
// "repair"), and back; the latter throws achd::Error naming `field` on another name.
const char* inertia_policy_name(InertiaPolicy policy);
InertiaPolicy inertia_policy_from_name(const std::string& name, const std::string& field);

// Elements nested deeper than this are refused before the XML parser (which recurses
// once per level) sees them; robot descriptions nest 5 to 8 deep.
constexpr int kMaxUrdfNesting = 100;

// Builds the model of the chain root -> tip, or with an empty tip the tree of every link
// below root (an empty root: the URDF's root link), bodies in depth-first order (each
// body's subtree follows it). Throws achd::Error naming the file, link
// or joint on malformed XML, elements nested deeper than kMaxUrdfNesting, unknown links,
// a tip not below the root, unsupported joint types (floating, planar), mimic joints
// (unless options.mimic is Independent), inertias the policy refuses, geometry whose
// numbers overflow, joints that move nothing (those the policy neither holds nor
// repairs), or a tree without a movable joint (unless floating). What it loaded but found
// odd, held, or repaired, is in Model::warnings.
Model load_urdf_file(const std::string& path, const std::string& root, const std::string& tip,
                     const UrdfOptions& options = {});
Model load_urdf_string(const std::string& xml, const std::string& root, const std::string& tip,
                       const UrdfOptions& options = {});

}  // namespace achd
