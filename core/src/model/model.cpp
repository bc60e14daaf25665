#include "achd/model.hpp"

#include <cmath>

#include "achd/error.hpp"

namespace achd {

const char* joint_type_name(JointType type) {
  switch (type) {
    case JointType::Revolute: return "revolute";
    case JointType::Continuous: return "continuous";
    case JointType::Prismatic: return "prismatic";
  }
  return "unknown";
}

void Model::set_rotor_inertia(int joint, double value) {
  if (joint < 0 || joint >= num_rates())
    throw Error("set_rotor_inertia: joint index " + std::to_string(joint) + " is out of range [0, " +
                std::to_string(num_rates()) + ")");
  if (!std::isfinite(value) || value < 0)
    throw Error("set_rotor_inertia: joint '" + bodies[joint].joint_name +
                "': rotor inertia must be finite and >= 0");
  bodies[joint].rotor_inertia = value;
}

int LoopJoint::num_columns() const {
  int n = 0;
  for (int k = 0; k < kNumDirections; ++k) n += (directions >> k) & 1u;
  return n;
}

int Model::num_loop_columns() const {
  int n = 0;
  for (const LoopJoint& l : loops) n += l.num_columns();
  return n;
}

int Model::joint_index(const std::string& name) const {
  for (int i = 0; i < num_rates(); ++i)
    if (bodies[i].joint_name == name) return i;
  return -1;
}

int Model::link_index(const std::string& name) const {
  for (int i = 0; i < num_links(); ++i)
    if (links[i].name == name) return i;
  return -1;
}

}  // namespace achd
