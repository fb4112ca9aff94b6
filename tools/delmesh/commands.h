// The verbs of the delmesh command line. Each verb lives in its own <verb>_command.cpp and
// receives the arguments after the verb. It returns the process exit code: 0 success,
// 1 refused input or failed run, 2 bad command-line usage.
#pragma once

#include <span>
#include <string_view>

namespace delmesh::cli {

using CommandArgs = std::span<const std::string_view>;

struct Command {
  std::string_view name;
  std::string_view summary;  ///< one line for `delmesh --help`
  int (*run)(CommandArgs args);
};

/// Every verb, in the order `delmesh --help` lists them (defined in main.cpp).
std::span<const Command> all_commands();

// One declaration per verb, defined in <verb>_command.cpp.
int run_tri(CommandArgs args);
int run_delaunay(CommandArgs args);
int run_import(CommandArgs args);
int run_mesh(CommandArgs args);

}  // namespace delmesh::cli
