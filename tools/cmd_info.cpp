// achd info ROBOT.urdf [--root LINK] [--tip LINK] [--lock JOINT=VALUE ...]
//           [--mimic couple|independent|error] [--loops LOOPS.json] [--inertia accept|strict|repair]
//           [--convention physical|kdl] [--srdf FILE]
// Prints the model the other commands would load, as JSON (model_info.hpp).
#include <iostream>

#include "args.hpp"
#include "case_json.hpp"
#include "commands.hpp"
#include "model_info.hpp"
#include "read_text_file.hpp"
#include "urdf_options.hpp"

namespace achd::cli {

int cmd_info(int argc, char** argv) {
  std::set<std::string> valued = {"--root", "--tip", "--convention", "--srdf"};
  valued.insert(kUrdfValued.begin(), kUrdfValued.end());
  const Args args(argc, argv, valued, kUrdfFlags);
  if (args.positional().size() != 1) throw Error("info: expected one URDF file, see `achd help`");
  const std::string convention = args.get("--convention", "physical");
  if (convention != "physical" && convention != "kdl")
    throw Error("option --convention: expected 'physical' or 'kdl', got '" + convention + "'");
  const std::string urdf = args.positional()[0];
  const Model model = load_robot(urdf, args);
  const std::string srdf = args.get("--srdf", "");
  const std::vector<SrdfPose> poses =
      srdf.empty() ? std::vector<SrdfPose>{}
                   : read_srdf_poses(read_text_file(srdf, kMaxUrdfFileBytes, "an SRDF file"), srdf);
  std::cout << model_info_json(model, read_text_file(urdf, kMaxUrdfFileBytes, "a URDF file"), poses);
  return 0;
}

}  // namespace achd::cli
