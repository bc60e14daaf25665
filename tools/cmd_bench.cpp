// achd bench ROBOT.urdf [--root LINK] [--tip LINK] --case CASE.json [--iterations N]
//            [--repeats R] [--clock cpu|wall] [--against kdl] [--lock JOINT=VALUE ...]
//            [--mimic couple|independent|error] [--loops LOOPS.json] [--link-outputs]
//            [solver options]
// Loads the robot and reads the case as `achd solve` does (without --tip: the whole tree).
// The solves compute no link's acceleration (Data::set_link_outputs({}): what a controller
// that reads qdd and the forces pays) unless --link-outputs: then every link's, as
// `achd solve` returns them.
// Prints {"achd_ns": ...}: ns per hybrid_dynamics() call, the median of R rounds of N
// calls (default: about 2 ms per round, 51 rounds) after a warm-up round; with --against
// kdl also KDL's ChainHdSolver_Vereshchagin on the same chain and case, timed in the same
// rounds, "ratio" = the median of the per-round ratios achd / KDL, and the relative
// difference of the two qdd (a check that both solved the same problem). The clock is the
// thread's CPU time unless --clock wall.
#include <cstdio>
#include <iostream>

#include "args.hpp"
#include "case_json.hpp"
#include "json_file.hpp"
#include "commands.hpp"
#include "timing.hpp"
#include "urdf_options.hpp"
#ifdef ACHD_HAVE_KDL
#include "kdl_problem.hpp"
#endif

namespace achd::cli {

int cmd_bench(int argc, char** argv) {
  std::set<std::string> valued = {"--root", "--tip", "--case", "--iterations", "--repeats", "--against", "--clock"};
  valued.insert(kSolverValued.begin(), kSolverValued.end());
  valued.insert(kUrdfValued.begin(), kUrdfValued.end());
  std::set<std::string> flags = kSolverFlags;
  flags.insert(kUrdfFlags.begin(), kUrdfFlags.end());
  flags.insert("--link-outputs");
  const Args args(argc, argv, valued, flags);
  if (args.positional().size() != 1) throw Error("bench: expected one URDF file, see `achd help`");
  const Options options = solver_options(args);
  const std::string urdf = args.positional()[0];
  const Model model = load_robot(urdf, args);
  const std::string case_path = args.get("--case");
  const Case c = parse_case(read_json_file(case_path, "a case file", true), model,
                            case_path);
  // Ranges: a round of 1e9 calls already takes minutes; 1e5 rounds keep the samples small.
  const int repeats = static_cast<int>(args.integer("--repeats", 51, 1, 100000));
  const std::string against = args.get("--against", "");
  const std::string clock_name = args.get("--clock", "cpu");
  if (clock_name != "cpu" && clock_name != "wall")
    throw Error("option --clock: expected 'cpu' or 'wall', got '" + clock_name + "'");
  const Clock clock = clock_name == "wall" ? Clock::Wall : Clock::ThreadCpu;
  if (!against.empty() && against != "kdl")
    throw Error("option --against: expected 'kdl', got '" + against + "'");
  // KDL's solver holds a chain at its tip: no trees, no constraint blocks.
  if (!against.empty() && !model.has_tip()) throw Error("--against kdl: KDL's solver takes a chain; give --tip");
  if (!against.empty() && !c.constraints.empty())
    throw Error("--against kdl: KDL's solver has no constraint blocks (\"constraints\")");

  Data data(model);
  if (!args.has("--link-outputs")) data.set_link_outputs({});
  std::vector<std::function<void()>> fns = {[&] { hybrid_dynamics(model, data, c, options); }};
#ifdef ACHD_HAVE_KDL
  std::unique_ptr<KdlProblem> kdl;
  if (!against.empty()) {
    kdl = std::make_unique<KdlProblem>(urdf, false, model.root_name, model.tip_name, c);
    fns.push_back([&] { kdl->solve(); });
  }
#else
  if (!against.empty()) throw Error("--against kdl: this achd was built without KDL");
#endif
  std::vector<long> iterations;
  for (const auto& fn : fns)
    iterations.push_back(args.has("--iterations") ? args.integer("--iterations", 1, 1, 1000000000)
                                                  : calibrate_iterations(fn, 2e6, clock));
  const std::vector<std::vector<double>> samples = sample_ns(fns, iterations, repeats, clock);

  char buf[512];
  std::snprintf(buf, sizeof buf, "{\"achd_ns\": %.1f, \"iterations\": %ld, \"repeats\": %d", median(samples[0]),
                iterations[0], repeats);
  std::string out = buf;
#ifdef ACHD_HAVE_KDL
  if (kdl) {
    // KDL's qdd is NaN where its own solve breaks down (a singular constraint set under its
    // absolute tolerance, for one): the difference is then null, and said why.
    const Eigen::VectorXd q_kdl = kdl->qdd();
    std::snprintf(buf, sizeof buf, ", \"kdl_ns\": %.1f, \"kdl_iterations\": %ld, \"ratio\": %.4f",
                  median(samples[1]), iterations[1], median_ratio(samples[0], samples[1]));
    out += buf;
    if (q_kdl.allFinite()) {
      const double diff = (data.qdd - q_kdl).cwiseAbs().maxCoeff() / std::max(1.0, q_kdl.cwiseAbs().maxCoeff());
      std::snprintf(buf, sizeof buf, ", \"qdd_rel_diff\": %.3g", diff);
      out += buf;
    } else {
      out += ", \"qdd_rel_diff\": null, \"kdl_qdd_finite\": false";
    }
  }
#endif
  std::cout << out << "}\n";
  return 0;
}

}  // namespace achd::cli
