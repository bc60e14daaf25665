#pragma once
// URDF loading through urdfdom: the chain between a root and a tip link.
#include <string>

#include "achd/model.hpp"

namespace achd {

// Elements nested deeper than this are refused before the XML parser (which recurses
// once per level) sees them; robot descriptions nest 5 to 8 deep.
constexpr int kMaxUrdfNesting = 100;

// Builds the model of the chain root -> tip. Throws achd::Error naming the file, link
// or joint on malformed XML, elements nested deeper than kMaxUrdfNesting, unknown links,
// a tip not below the root, unsupported joint types (floating, planar), non-physical
// inertias, geometry whose numbers overflow, or joints that move nothing.
Model load_urdf_file(const std::string& path, const std::string& root, const std::string& tip);
Model load_urdf_string(const std::string& xml, const std::string& root, const std::string& tip);

}  // namespace achd
