#include "urdf_options.hpp"

#include <cmath>
#include <cstdlib>

namespace achd::cli {

const std::set<std::string> kUrdfValued = {"--mimic", "--lock"};
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
  options.mimic = mimic_joints_from_name(args.get("--mimic", "error"), "option --mimic");
  for (const std::string& lock : args.all("--lock")) add_lock(lock, options.locked);
  // KDL's chain holds the links on the root-to-tip path only.
  if (args.get("--convention", "") == "kdl") options.side_branches = SideBranches::Ignore;
  options.floating = args.has("--floating");
  return options;
}

}  // namespace achd::cli
