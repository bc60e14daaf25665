// achd solve ROBOT.urdf [--root LINK] [--tip LINK] --case CASE.json [--lock JOINT=VALUE ...]
//            [--mimic couple|independent|error] [--loops LOOPS.json] [solver options]
// Without --tip: the whole tree below --root (default: the URDF's root link).
#include <iostream>

#include "args.hpp"
#include "case_json.hpp"
#include "json_file.hpp"
#include "commands.hpp"
#include "urdf_options.hpp"

namespace achd::cli {

int cmd_solve(int argc, char** argv) {
  std::set<std::string> valued = {"--root", "--tip", "--case"};
  valued.insert(kSolverValued.begin(), kSolverValued.end());
  valued.insert(kUrdfValued.begin(), kUrdfValued.end());
  std::set<std::string> flags = kSolverFlags;
  flags.insert(kUrdfFlags.begin(), kUrdfFlags.end());
  const Args args(argc, argv, valued, flags);
  if (args.positional().size() != 1) throw Error("solve: expected one URDF file, see `achd help`");
  const Options options = solver_options(args);
  const std::string urdf = args.positional()[0];
  const Model model = load_robot(urdf, args);
  const std::string case_path = args.get("--case");
  const std::string text = read_json_file(case_path, "a case file", true);
  const Case c = parse_case(text, model, case_path);
  Data data(model);
  hybrid_dynamics(model, data, c, options);
  std::cout << result_json(model, data, c);
  return 0;
}

}  // namespace achd::cli
