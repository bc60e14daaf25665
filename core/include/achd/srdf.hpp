#pragma once
// Named poses from an SRDF file (the <group_state> elements robot descriptions ship beside
// their URDF: "standing", "half_sitting", "home"), as q for a loaded model.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

// One <group_state name="..." group="...">: its joint values in the order of the file,
// each joint's value attribute as numbers (one for a joint, seven for a floating base:
// x y z qx qy qz qw).
struct SrdfPose {
  std::string name, group;
  std::vector<std::pair<std::string, std::vector<double>>> joints;
};

// Every <group_state> of the SRDF text, in the order of the file. Throws achd::Error
// naming `source` and the state or joint on malformed XML, a state without a name, two
// states of one name, or a value that is not a list of finite numbers.
std::vector<SrdfPose> read_srdf_poses(const std::string& xml, const std::string& source);

// The pose as q for `model` (Model::num_positions() numbers): each joint of the model the
// state names takes the state's value; a joint it does not name is 0, or the middle of
// its limits when 0 is outside them. With a floating base, the free joint's seven numbers
// come from the state's "root_joint" entry (the name robot descriptions use for the
// virtual joint) or an entry named after the root link, else the identity pose. Entries
// naming joints the model does not have (a locked or a fixed joint, another variant of the
// robot, "root_joint" on a fixed base) are skipped. Throws achd::Error naming the state
// and joint on a value of the wrong length or a zero quaternion.
Eigen::VectorXd srdf_pose_q(const Model& model, const SrdfPose& pose);

// The pose named `name` among `poses`; an achd::Error listing the names otherwise.
const SrdfPose& find_srdf_pose(const std::vector<SrdfPose>& poses, const std::string& name,
                               const std::string& source);

// The start pose of a model without one given: every joint at 0, or the middle of its
// limits when 0 is outside them; a floating base at the identity pose.
Eigen::VectorXd default_pose(const Model& model);

// The value default_pose gives a joint with limits [lower, upper]: 0, or the middle of
// them when 0 is outside them (the loader holds a joint that moves nothing there too).
double default_joint_value(double lower, double upper);

}  // namespace achd
