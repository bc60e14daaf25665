#pragma once
// One URDF element at a time in achd's terms (urdf.cpp walks the tree with them): the
// angles of the origins as written, an origin's transform, a link's spatial inertia and
// a movable joint's body.
#include <array>
#include <map>
#include <string>
#include <vector>

#include <urdf_model/model.h>

#include "achd/model.hpp"
#include "achd/urdf.hpp"

namespace achd {

// The rpy attributes of the joints' origins and of the links' inertial origins, read as
// urdfdom reads them. urdfdom turns rpy into a quaternion with the C library's sin and
// cos, whose last bits differ between glibc (native) and musl (wasm): the two builds would
// load a URDF into models an ulp apart, which a long chain amplifies past 1e-12. With the
// angles themselves, the loader builds every rotation with achd's sin_cos instead.
// The joints' positions in the file are read with them: the order in which the tree's
// children are walked.
// And the round-off of each link's six <inertia> numbers as written (link_inertia.hpp).
struct OriginAngles {
  std::map<std::string, urdf::Vector3> joint, inertial;  // by joint / link name
  std::map<std::string, int> joint_position;             // by joint name: 0, 1, ... in the file
  std::map<std::string, std::array<double, 6>> inertia_roundoff;  // by link name
};

OriginAngles read_origin_angles(const std::string& xml);

// The angles written for `name` in one of OriginAngles' maps; nullptr when none.
template <class Map>
const urdf::Vector3* find_angles(const Map& map, const std::string& name) {
  const auto it = map.find(name);
  return it == map.end() ? nullptr : &it->second;
}

// The pose of an origin; `rpy`, when the element had one, gives its rotation.
Transform to_transform(const urdf::Pose& pose, const urdf::Vector3* rpy, const std::string& where);

// Spatial inertia of a URDF link about the link frame origin, its rotational inertia
// checked (and under the repair policy repaired) by checked_rotational_inertia.
Matrix6 link_inertia(const urdf::Link& link, const urdf::Vector3* rpy, const double* roundoff,
                     InertiaPolicy policy, std::vector<std::string>& warnings);

// The body of movable joint j below body `parent`, its frame the joint frame with z along
// the axis: X_tree is the URDF joint origin (from the parent body's frame) turned by R_axis =
// frame_with_z_along(axis), which is returned as well.
Body make_body(const urdf::Joint& j, const Transform& X_tree, int parent, Matrix3& R_axis);

}  // namespace achd
