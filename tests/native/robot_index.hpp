#pragma once
// The robots of robots/index.json (URDF text, root, tip, default pose), for the suites
// that run on every shipped robot.
#include <string>
#include <vector>

#include "achd/achd.hpp"

namespace achd::test {

struct IndexedRobot {
  std::string name, urdf_path, urdf, root, tip;
  Eigen::VectorXd q0;
  Model model;
  bool has_fixed_joints() const { return model.num_links() != model.num_joints(); }
};

// Reads `source_dir`/robots/index.json and loads every robot through load_urdf_string.
std::vector<IndexedRobot> load_robot_index(const std::string& source_dir);

// The text of a file; throws std::runtime_error naming the path if it cannot be read.
std::string read_text(const std::string& path);

}  // namespace achd::test
