// delmesh command-line entry point: dispatches `delmesh <verb> ...` to the verb's runner.
#include <exception>
#include <iostream>
#include <string_view>
#include <vector>

#include "tools/delmesh/commands.h"

namespace delmesh::cli {

std::span<const Command> all_commands() {
  static const std::vector<Command> commands{
      {"tri", "triangulate and refine a 2D .poly/.node (Triangle formats and switches)", run_tri},
      {"delaunay", "Delaunay tetrahedralization of a .node point set", run_delaunay},
      {"import", "read STEP/STL/OFF/OBJ/PLY/.poly/.smesh into a validated PLC", run_import},
      {"mesh", "quality tetrahedral mesh of a STEP/STL/.poly solid for FEM", run_mesh},
  };
  return commands;
}

}  // namespace delmesh::cli

namespace {

void print_help() {
  std::cout << "usage: delmesh <verb> [options]\n\nverbs:\n";
  for (const auto& command : delmesh::cli::all_commands()) {
    std::cout << "  " << command.name << std::string(12 - command.name.size(), ' ')
              << command.summary << '\n';
  }
  std::cout << "\n'delmesh <verb> --help' describes a verb's options.\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string_view> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_help();
    return args.empty() ? 2 : 0;
  }
  for (const auto& command : delmesh::cli::all_commands()) {
    if (command.name == args[0]) {
      try {
        return command.run(delmesh::cli::CommandArgs(args).subspan(1));
      } catch (const std::bad_alloc&) {
        std::cerr << "delmesh " << command.name << ": out of memory\n";
        return 1;
      } catch (const std::exception& e) {
        std::cerr << "delmesh " << command.name << ": " << e.what() << '\n';
        return 1;
      }
    }
  }
  std::cerr << "delmesh: unknown verb '" << args[0] << "' (see 'delmesh --help')\n";
  return 2;
}
