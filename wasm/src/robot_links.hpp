#pragma once
// The links of a loaded robot as its URDF has them, for the page's view, which reads no
// URDF of its own.
#include <string>

#include "achd/model.hpp"

namespace achd::wasm {

// JSON array, one object per link the robot carries: the root, the model's links in
// model order, then the links the loader merged into a body without making them links of
// the model (a chain's side branches; a tree has none), each
//   {"name", "frame" (where it is drawn: 0 the root, 1 + its index in Model::links, a
//    side link its host's), "parent" (URDF parent link, null for the root), "joint"
//    ({"name", "type"} of the URDF joint above it, its URDF type, or null for the root),
//    "body" (the joint name of the body it rides on; null: fixed to the root), "mass" (its
//    own <inertial> mass, 0 without one), "offset" (a side link's pose in its frame's
//    link, {"position": [3], "rotation": [9, row-major]}, its joints at their locked
//    values or 0; null for the others), "visuals": [{"position", "rotation" (in the
//    link's frame), "geometry": {"type": "box", "size"} | {"type": "cylinder", "radius",
//    "length"} | {"type": "sphere", "radius"} | {"type": "mesh", "filename", "scale"},
//    "color": [r, g, b, a] or null (no colour given)}]}.
// Read with urdfdom, the loader's parser, from the text the model was loaded from.
// Throws achd::Error when that text no longer parses (it did for the loader).
std::string describe_links(const Model& model, const std::string& urdf_text);

}  // namespace achd::wasm
