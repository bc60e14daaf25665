#pragma once
// The subcommands of the `achd` command line; each takes the arguments after its name,
// writes its result to stdout and throws achd::Error on bad input.
namespace achd::cli {

int cmd_solve(int argc, char** argv);
int cmd_bench(int argc, char** argv);
int cmd_info(int argc, char** argv);
int cmd_simulate(int argc, char** argv);
int cmd_accuracy(int argc, char** argv);

}  // namespace achd::cli
