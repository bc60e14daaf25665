#pragma once
// The robots of robots/index.json (URDF text, root, tip, default pose), for the suites
// that run on every shipped robot: the chains (entries with a tip) and the trees (entries
// without one, with default held links "constraints", an optional "mimic" option and an
// optional "loops" file of loop joints, the four-bar's).
#include <string>
#include <vector>

#include "achd/achd.hpp"

namespace achd::test {

struct IndexedRobot {
  std::string name, urdf_path, urdf, root, tip;  // tip empty: a tree
  Eigen::VectorXd q0;
  std::vector<std::string> constraints;  // a tree's default held links
  UrdfOptions options;                   // its "mimic" option and its loops file's loops
  Model model;
  bool has_fixed_joints() const { return model.num_links() != model.num_rates(); }
};

// Reads `source_dir`/robots/index.json and loads every chain through load_urdf_string.
std::vector<IndexedRobot> load_robot_index(const std::string& source_dir);
// The same for every tree (loaded whole below its root).
std::vector<IndexedRobot> load_tree_index(const std::string& source_dir);

// The text of a file; throws std::runtime_error naming the path if it cannot be read.
std::string read_text(const std::string& path);

// The loop joints of a loops file ({"loops": [...]}, tools/loops_json.hpp).
std::vector<LoopJointSpec> read_loops_file(const std::string& path);

}  // namespace achd::test
