// The `achd` command line. stdout carries only results; an error is one line
// "achd: error: ..." on stderr and exit code 2 (also when the result cannot be written
// to stdout, a closed pipe included: SIGPIPE is ignored, so the write fails with EPIPE
// and is reported like a full disk); a run stopped by Ctrl-C is one line
// "achd: interrupted: ..." and exit code 130, by SIGTERM or SIGHUP one line
// "achd: interrupted by SIGTERM: ..." and exit code 128 + the signal.
#include <signal.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "achd/error.hpp"
#include "commands.hpp"
#include "printable.hpp"
#include "progress.hpp"

namespace {

const char* kUsage =
    "usage: achd <command> [arguments]\n"
    "  solve ROBOT.urdf [--root LINK] [--tip LINK] [--floating] --case CASE.json\n"
    "        [--lock JOINT=VALUE ...] [--mimic couple|independent|error]\n"
    "        [--inertia accept|strict|repair] [--loops LOOPS.json]\n"
    "        [--convention physical|kdl] [--policy truncate|damped|variable_damping]\n"
    "        [--tolerance X] [--absolute-tolerance] [--damping X]\n"
    "        [--singular-region X] [--max-damping X]\n"
    "                  solve one case, print the result JSON; without --tip the\n"
    "                  whole tree below --root (default: the URDF's root link),\n"
    "                  with --tip the chain (side branches merged, their movable\n"
    "                  joints locked at 0 or at --lock's value; --convention kdl\n"
    "                  ignores them, as KDL does); --floating: a free joint\n"
    "                  between the world and the root link, first in q (7 numbers:\n"
    "                  x y z qx qy qz qw) and qd (6: v w, world axes); --lock\n"
    "                  holds any movable joint; --inertia: odd inertias loaded\n"
    "                  with a warning and joints that move no mass held\n"
    "                  (accept, default), refused (strict) or made physical\n"
    "                  (repair); --loops: loop joints closing the\n"
    "                  tree (their columns follow the case's blocks in nu)\n"
    "  bench ROBOT.urdf [--root LINK] [--tip LINK] [--floating] --case CASE.json\n"
    "        [--iterations N] [--repeats R] [--against kdl]\n"
    "        [--lock JOINT=VALUE ...] [--mimic couple|independent|error]\n"
    "        [--inertia accept|strict|repair] [--loops LOOPS.json] [--link-outputs]\n"
    "        [solver options]\n"
    "                  ns per solve (median of R repeats of N calls), with\n"
    "                  --against kdl also KDL's solver in the same run; the\n"
    "                  solves compute the links' accelerations only with\n"
    "                  --link-outputs\n"
    "  info ROBOT.urdf [--root LINK] [--tip LINK] [--floating] [--lock JOINT=VALUE ...]\n"
    "        [--mimic couple|independent|error] [--inertia accept|strict|repair]\n"
    "        [--loops LOOPS.json] [--convention physical|kdl] [--srdf FILE]\n"
    "                  print the model as JSON: joints, links, masses, locked\n"
    "                  joints, loop joints with their held and dropped\n"
    "                  directions, a default pose, the loader's warnings, and the\n"
    "                  SRDF's named poses (its group_states)\n"
    "  simulate SCENE.json [--out traj.csv] [--integrator NAME] [--rtol R] [--atol A]\n"
    "                  run a scene (robots/scenes/*.json), write the trajectory\n"
    "                  CSV, print a JSON summary (steps, ns per step, drifts);\n"
    "                  --out - : the CSV on stdout instead; Ctrl-C stops (exit 130);\n"
    "                  --integrator, --rtol, --atol replace the scene's\n"
    "  accuracy SCENE.json [--out DIR] [--quick]\n"
    "                  error against an RK4 reference and cost per step of each\n"
    "                  integrator at dt = 10 ms .. 0.05 ms and of the solver knobs;\n"
    "                  writes DIR/accuracy.{csv,json,svg}, prints the JSON\n"
    "  help            this text\n";

struct Command {
  const char* name;
  int (*run)(int, char**);
};

const Command kCommands[] = {
    {"solve", achd::cli::cmd_solve},
    {"bench", achd::cli::cmd_bench},
    {"info", achd::cli::cmd_info},
    {"simulate", achd::cli::cmd_simulate},
    {"accuracy", achd::cli::cmd_accuracy},
};

// Everything a command wrote to stdout has gone out, else an error (a full disk, a
// closed terminal).
void check_stdout() {
  errno = 0;
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout))
    throw achd::Error(std::string("cannot write the result to stdout") + (errno ? ": " + std::string(std::strerror(errno)) : ""));
}

int run(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "--help")) {
    std::cout << kUsage;
    return argc < 2 ? 2 : 0;
  }
  for (const Command& c : kCommands)
    if (argv[1] == std::string(c.name)) return c.run(argc - 2, argv + 2);
  throw achd::Error(std::string("unknown command '") + argv[1] + "' (see `achd help`)");
}

}  // namespace

int main(int argc, char** argv) {
  // A closed stdout (`achd ... | head -c 10`) is a failed write, reported as one line and
  // exit 2 as docs/guide/cli.md says, rather than a silent death by SIGPIPE (exit 141).
  signal(SIGPIPE, SIG_IGN);
  try {
    const int code = run(argc, argv);
    check_stdout();
    return code;
  } catch (const achd::cli::Interrupted& e) {
    std::cerr << "achd: interrupted" << (e.signal() == SIGINT ? "" : " by " + e.signal_name()) << ": " << e.what()
              << "\n";
    return 128 + e.signal();
  } catch (const std::exception& e) {
    // printable(): a newline inside a name the message quotes stays in the one line.
    std::cerr << "achd: error: " << achd::cli::printable(e.what()) << "\n";
    return 2;
  }
}
