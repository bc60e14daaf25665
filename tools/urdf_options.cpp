#include "urdf_options.hpp"

namespace achd::cli {

const std::set<std::string> kUrdfValued = {"--mimic"};

UrdfOptions urdf_options(const Args& args) {
  UrdfOptions options;
  options.mimic = mimic_joints_from_name(args.get("--mimic", "error"), "option --mimic");
  return options;
}

}  // namespace achd::cli
