#include "robot_index.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "loops_json.hpp"

namespace achd::test {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open file");
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<LoopJointSpec> read_loops_file(const std::string& path) {
  return cli::parse_loops(read_text(path), path);
}

namespace {

std::vector<IndexedRobot> load_index(const std::string& source_dir, bool trees) {
  const nlohmann::json index = nlohmann::json::parse(read_text(source_dir + "/robots/index.json"));
  std::vector<IndexedRobot> robots;
  for (const auto& r : index.at("robots")) {
    if (r.contains("tip") == trees) continue;
    IndexedRobot robot;
    robot.name = r.at("name");
    robot.urdf_path = source_dir + "/" + r.at("urdf").get<std::string>();
    robot.urdf = read_text(robot.urdf_path);
    robot.root = r.at("root");
    if (!trees) robot.tip = r.at("tip");
    const std::vector<double> q0 = r.at("q0");
    robot.q0 = Eigen::Map<const Eigen::VectorXd>(q0.data(), static_cast<Eigen::Index>(q0.size()));
    if (r.contains("constraints")) robot.constraints = r.at("constraints").get<std::vector<std::string>>();
    if (r.contains("mimic")) robot.options.mimic = mimic_joints_from_name(r.at("mimic"), robot.name + ": mimic");
    if (r.contains("loops")) robot.options.loops = read_loops_file(source_dir + "/" + r.at("loops").get<std::string>());
    robot.model = load_urdf_string(robot.urdf, robot.root, robot.tip, robot.options);
    robots.push_back(std::move(robot));
  }
  return robots;
}

}  // namespace

std::vector<IndexedRobot> load_robot_index(const std::string& source_dir) { return load_index(source_dir, false); }

std::vector<IndexedRobot> load_tree_index(const std::string& source_dir) { return load_index(source_dir, true); }

}  // namespace achd::test
