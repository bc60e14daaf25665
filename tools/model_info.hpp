#pragma once
// The model as `achd info` prints it: what the loader made of a URDF (joints in model
// order with their types, parents and limits; links with the body they ride on and their
// mass; the locked joints; a default pose), so that a user can write cases by name.
#include <string>

#include "achd/model.hpp"
#include "achd/srdf.hpp"

namespace achd::cli {

// JSON text: {"root", "tip" (null for a tree), "joints": [{"name", "type", "parent"
// (joint name or null: the root), "link", "limits": {"lower", "upper" (null: unbounded),
// "velocity", "effort" (0: not given)}}], "links": [{"name", "body" (joint name or null:
// the root), "mass"}] (root link first), "locked_joints": [{"name", "value"}],
// "warnings": [the loader's], "default_q": {joint name: 0, or the middle of its limits
// when 0 is outside them (achd::default_pose)}, and with SRDF poses "poses": [{"name",
// "group", "q": {joint name: value}}] (achd::srdf_pose_q)}.
// `urdf_text`: the URDF the model was loaded from, for the links' own masses (a body's
// inertia is the sum of its links').
std::string model_info_json(const Model& model, const std::string& urdf_text, const std::vector<SrdfPose>& poses = {});

}  // namespace achd::cli
