#pragma once
// Loop joints in JSON (loops files, scenes, the JS loadURDF option, `achd info`):
//   [{"name", "link_a", "origin_a": {"xyz", "rpy"}, "link_b", "origin_b", "type",
//     "axis", "directions"}]
// origins as URDF writes them (rpy: roll about x, pitch about y, yaw about z, fixed
// axes: R = Rz(yaw) Ry(pitch) Rx(roll)), default the link's own frame; type "revolute",
// "prismatic", "spherical" or "fixed"; axis (revolute, prismatic) in frame a, default z;
// directions optional (loops.hpp: LoopJointSpec).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "achd/loops.hpp"
#include "case_json.hpp"

namespace achd::cli {

// The specs of a JSON array of loops; achd::Error naming `field`, the index and the
// field on a wrong type, a missing name, link or type, an unknown field, a number that is
// not finite.
std::vector<LoopJointSpec> loop_specs(const nlohmann::json& loops, const std::string& field);

// A loops file's text: an object {"loops": [...]}; errors start with `source`.
std::vector<LoopJointSpec> parse_loops(const std::string& text, const std::string& source);

// Model::loops as a JSON array [{"name", "type", "link_a", "link_b", "directions": [..],
// "dropped": [..]}] (links by name, the root link's for -1).
std::string loops_json(const Model& model);

}  // namespace achd::cli
