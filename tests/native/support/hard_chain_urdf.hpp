#pragma once
// URDF text for serial chains described in code, for the hard-case and bad-input
// suites: links link0 (root) .. linkN, joints j1 .. jN, one link per joint.
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace achd::test {

struct LinkSpec {
  std::string joint_type = "revolute";      // revolute, continuous, prismatic, fixed, ...
  Eigen::Vector3d joint_xyz{0, 0, 0};       // joint origin in the parent link frame
  Eigen::Vector3d joint_rpy{0, 0, 0};
  Eigen::Vector3d axis{0, 0, 1};
  bool has_inertial = true;                 // false: a massless link (no <inertial>)
  double mass = 1;
  Eigen::Vector3d com{0, 0, 0};             // in the link frame
  Eigen::Vector3d com_rpy{0, 0, 0};
  Eigen::Vector3d inertia_diag{0.01, 0.01, 0.01};  // principal moments about the COM
  double ixy = 0, ixz = 0, iyz = 0;
  std::string name;                         // default "link<i>"
};

inline std::string vec3(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(17);
  s << v.x() << " " << v.y() << " " << v.z();
  return s.str();
}

inline std::string link_name(const std::vector<LinkSpec>& links, size_t i) {
  if (i == 0) return "link0";
  return links[i - 1].name.empty() ? "link" + std::to_string(i) : links[i - 1].name;
}

// The chain link0 -> link1 -> ... -> linkN with links[i] describing joint j<i+1> and
// link<i+1>.
inline std::string chain_urdf(const std::vector<LinkSpec>& links) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\"?>\n<robot name=\"chain\">\n  <link name=\"link0\"/>\n";
  for (size_t i = 0; i < links.size(); ++i) {
    const LinkSpec& l = links[i];
    x << "  <link name=\"" << link_name(links, i + 1) << "\">";
    if (l.has_inertial) {
      x << "<inertial><origin xyz=\"" << vec3(l.com) << "\" rpy=\"" << vec3(l.com_rpy)
        << "\"/><mass value=\"" << l.mass << "\"/><inertia ixx=\"" << l.inertia_diag.x()
        << "\" ixy=\"" << l.ixy << "\" ixz=\"" << l.ixz << "\" iyy=\"" << l.inertia_diag.y()
        << "\" iyz=\"" << l.iyz << "\" izz=\"" << l.inertia_diag.z() << "\"/></inertial>";
    }
    x << "</link>\n";
    x << "  <joint name=\"j" << i + 1 << "\" type=\"" << l.joint_type << "\"><parent link=\""
      << link_name(links, i) << "\"/><child link=\"" << link_name(links, i + 1)
      << "\"/><origin xyz=\"" << vec3(l.joint_xyz) << "\" rpy=\"" << vec3(l.joint_rpy)
      << "\"/><axis xyz=\"" << vec3(l.axis) << "\"/>";
    if (l.joint_type == "revolute" || l.joint_type == "prismatic")
      x << "<limit lower=\"-10\" upper=\"10\" effort=\"100\" velocity=\"100\"/>";
    x << "</joint>\n";
  }
  x << "</robot>\n";
  return x.str();
}

}  // namespace achd::test
