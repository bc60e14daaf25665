#include "urdf_options.hpp"

#include <cmath>
#include <cstdlib>
#include <iostream>

#include "json_file.hpp"
#include "loops_json.hpp"

namespace achd::cli {

const std::set<std::string> kUrdfValued = {"--mimic", "--lock", "--inertia", "--loops"};
const std::set<std::string> kUrdfFlags = {"--floating"};

namespace {

// "JOINT=VALUE" -> locked[JOINT] = VALUE (a finite number, rad or m), each joint once.
void add_lock(const std::string& text, std::map<std::string, double>& locked) {
  const std::size_t eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0)
    throw Error("option --lock: expected JOINT=VALUE, got '" + text + "'");
  const std::string joint = text.substr(0, eq), value = text.substr(eq + 1);
  char* end = nullptr;
  const double x = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(x))
    throw Error("option --lock " + text + ": '" + value + "' is not a finite number");
  if (!locked.emplace(joint, x).second) throw Error("option --lock: joint '" + joint + "' is locked twice");
}

}  // namespace

UrdfOptions urdf_options(const Args& args) {
  UrdfOptions options;
  options.mimic = mimic_joints_from_name(args.get("--mimic", "couple"), "option --mimic");
  for (const std::string& lock : args.all("--lock")) add_lock(lock, options.locked);
  // KDL's chain holds the links on the root-to-tip path only.
  if (args.get("--convention", "") == "kdl") options.side_branches = SideBranches::Ignore;
  options.floating = args.has("--floating");
  options.inertia = inertia_policy_from_name(args.get("--inertia", "accept"), "option --inertia");
  if (args.has("--loops")) {
    const std::string path = args.get("--loops");
    options.loops = parse_loops(read_json_file(path, "a loops file"), path);
  }
  return options;
}

void print_warnings(const Model& model, const std::string& path) {
  for (const std::string& w : model.warnings) std::cerr << "achd: warning: " << path << ": " << w << "\n";
}

Model load_robot(const std::string& path, const Args& args) {
  Model model = load_urdf_file(path, args.get("--root", ""), args.get("--tip", ""), urdf_options(args));
  print_warnings(model, path);
  return model;
}

}  // namespace achd::cli
