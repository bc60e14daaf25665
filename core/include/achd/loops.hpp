#pragma once
// Loop joints: the joints a tree cannot hold (a four-bar's fourth pivot, a parallel
// robot's platform joints, a hand closed on an object), described beside the URDF and
// held as relative constraint columns (Model::loops). The loader takes them in
// UrdfOptions::loops; a model built in code takes them with add_loops().
#include <string>
#include <vector>

#include "achd/model.hpp"

namespace achd {

// The name of a LoopType in the loops files, CLI, JS and scenes ("revolute",
// "prismatic", "spherical", "fixed"), and back; the latter throws achd::Error naming
// `field` on another name.
const char* loop_type_name(LoopType type);
LoopType loop_type_from_name(const std::string& name, const std::string& field);

// A loop joint as the user describes it: by link names, its frame on each link (the two
// frames coincide while the loop is closed), its type and, for a revolute or prismatic
// joint, its axis in frame a.
struct LoopJointSpec {
  std::string name;
  std::string link_a, link_b;  // links of the model; the root link of a fixed base is the world
  Transform origin_a, origin_b;  // the joint frame in link a's and in link b's frame
  LoopType type = LoopType::Fixed;
  Vector3 axis = Vector3::UnitZ();  // revolute, prismatic: in the joint frame (frame a)
  // The loop frame's directions to hold ("x" ... "rz", the loop frame having its z along
  // the axis), a subset of the type's; empty: the type's less those the tree cannot violate.
  std::vector<std::string> directions;
};

// The directions a loop type holds in its loop frame (bits x..rz): revolute all but rz,
// prismatic all but z, spherical x y z, fixed all six.
unsigned loop_type_directions(LoopType type);

// Resolves `loops` on `model` and appends them to Model::loops, in order. The loop frame
// is the joint frame turned so that its z runs along the axis (the smallest turn that does
// it; the frame itself for spherical and fixed loops). Without a `directions` list, each
// of the type's directions whose relative-Jacobian row is, at every one of a fixed set of
// sampled configurations, zero or a combination of the rows kept before it (this loop's
// and the earlier loops') is dropped (LoopJoint::dropped): the out-of-plane directions of
// a planar loop, the repeated ones of a parallelogram. Throws achd::Error naming the loop
// and the field: an empty or repeated name, an unknown link, a loop of a link with
// itself, the root of a floating base (a link fixed to it is named instead), an axis
// that is zero or not finite, a frame that is not finite, a direction the type does not
// hold, a loop with no direction left, or more columns than kMaxConstraints per loop.
void add_loops(Model& model, const std::vector<LoopJointSpec>& loops);

// The names of the directions in `directions` (bit k: direction_name(k), "x" ... "rz"), in
// index order: what a loop holds or dropped ({"x", "y"} ...).
std::vector<std::string> loop_direction_names(unsigned directions);

}  // namespace achd
