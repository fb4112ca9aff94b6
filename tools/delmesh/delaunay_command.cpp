// `delmesh delaunay`: Delaunay tetrahedralization of the points of a TetGen .node file,
// written as TetGen-style .node/.ele (toolkit/tetmesh/delaunay.h, tet_node_io.h).
#include <iostream>
#include <string>
#include <string_view>
#include <utility>

#include "toolkit/tetmesh/delaunay.h"
#include "toolkit/tetmesh/tet_check.h"
#include "toolkit/tetmesh/tet_node_io.h"
#include "tools/delmesh/cli_support.h"
#include "tools/delmesh/commands.h"

namespace delmesh::cli {

namespace {

constexpr std::string_view kHelp =
    "usage: delmesh delaunay POINTS.node [-o OUT.node] [--quiet] [--check]\n"
    "\n"
    "Delaunay tetrahedralization of the points of a TetGen .node file (3D).\n"
    "Writes OUT.node (all input points, in input order) and OUT.ele (the tets), both\n"
    "1-based as TetGen writes them; tets are positively oriented. Default OUT: POINTS.1.node.\n"
    "Points at the same position are merged into the first of them (reported on stderr);\n"
    "all-coplanar or all-collinear input is refused.\n"
    "\n"
    "  -o OUT.node   output name (OUT.ele is written beside it)\n"
    "  --quiet       no summary on stderr\n"
    "  --check       verify the result (topology, orientation, exact Delaunay property);\n"
    "                exit code 1 if any check fails\n";

}  // namespace

int run_delaunay(CommandArgs args) {
  std::string input, output;
  bool quiet = false, check = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    if (a == "--help" || a == "-h") {
      std::cout << kHelp;
      return 0;
    } else if (a == "--quiet" || a == "-Q") {
      quiet = true;
    } else if (a == "--check") {
      check = true;
    } else if (a == "-o") {
      if (i + 1 >= args.size()) return usage_error("delaunay", "-o needs a file name");
      output = std::string(args[++i]);
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("delaunay", "unknown option '" + std::string(a) + "'");
    } else if (input.empty()) {
      input = std::string(a);
    } else {
      return usage_error("delaunay", "more than one input file");
    }
  }
  if (input.empty()) return usage_error("delaunay", "no input .node file");
  if (extension_of(input) != ".node") {
    return usage_error("delaunay", "input must be a TetGen .node file: '" + input + "'");
  }
  if (output.empty()) output = strip_extension(input) + ".1.node";
  if (extension_of(output) != ".node") return usage_error("delaunay", "-o must name a .node file");
  const std::string ele = strip_extension(output) + ".ele";

  StderrLogSink sink(quiet);
  Stopwatch total;
  auto points = read_node_file(input);
  if (!points) return report_error(points.error());
  const double read_seconds = total.seconds();

  Stopwatch build;
  DelaunayOptions options;
  options.log = &sink;
  const std::size_t n = points->points.size();
  // The library builds in the moved-in array: no second copy of the points.
  auto result = delaunay_tetrahedralize(std::move(points->points), options);
  if (!result) {
    Error e = result.error();
    if (!e.location) e.location = SourceLocation{input, 0};
    return report_error(e);
  }
  const double build_seconds = build.seconds();
  if (result->num_duplicates > 0) {
    sink.write(LogLevel::Warning, std::to_string(result->num_duplicates) +
                                      " duplicate points merged (they appear in no tet)");
  }

  Stopwatch write;
  if (auto w = write_node_file(output, result->mesh.points().subspan(1)); !w) return report_error(w.error());
  if (auto w = write_ele_file(ele, result->mesh); !w) return report_error(w.error());
  const double write_seconds = write.seconds();

  if (!quiet) {
    const std::size_t tets = result->mesh.num_finite_tets();
    std::cerr << "delaunay: " << n << " points, " << tets << " tets; read " << read_seconds
              << " s, tetrahedralize " << build_seconds << " s ("
              << static_cast<long long>(static_cast<double>(n) / build_seconds) << " points/s), write "
              << write_seconds << " s\n"
              << "wrote " << output << " and " << ele << '\n';
  }
  if (check) {
    const auto topology = check_topology(result->mesh);
    const auto delaunay = topology.empty() ? check_delaunay(result->mesh) : std::vector<MeshIssue>{};
    for (const auto& issue : topology) std::cerr << "check: " << issue.message << '\n';
    for (const auto& issue : delaunay) std::cerr << "check: " << issue.message << '\n';
    if (!topology.empty() || !delaunay.empty()) {
      std::cerr << "delmesh delaunay: --check FAILED\n";
      return 1;
    }
    if (!quiet) std::cerr << "check: topology, orientation and Delaunay property verified\n";
  }
  return 0;
}

}  // namespace delmesh::cli
