#pragma once
// URDF loading through urdfdom: the chain between a root and a tip link.
#include <string>

#include "achd/model.hpp"

namespace achd {

// Builds the model of the chain root -> tip. Throws achd::Error naming the file, link
// or joint on malformed XML, unknown links, a tip not below the root, unsupported joint
// types (floating, planar), non-physical inertias or joints that move nothing.
Model load_urdf_file(const std::string& path, const std::string& root, const std::string& tip);
Model load_urdf_string(const std::string& xml, const std::string& root, const std::string& tip);

}  // namespace achd
