// `delmesh import`: reads any supported input into a PLC, validates it, prints its size
// and the angles that predict refinement trouble, and optionally writes it out.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>
#include <string>

#include "importers/import.h"
#include "importers/plc_writer.h"
#include "tools/delmesh/cli_support.h"
#include "tools/delmesh/commands.h"
#include "toolkit/plc/plc_statistics.h"
#include "toolkit/plc/plc_tables.h"
#include "toolkit/plc/plc_validate.h"

namespace delmesh::cli {
namespace {

constexpr const char* kUsage =
    "usage: delmesh import INPUT [-o OUT.{smesh,poly,off,vtu}] [options]\n"
    "\n"
    "Reads INPUT (.stl .off .obj .ply .poly .smesh .node, and .step .stp .brep .iges .igs\n"
    "when built with OpenCASCADE) into a piecewise linear complex, validates it exactly and\n"
    "prints its size, the smallest angle between two segments at a vertex and the smallest\n"
    "dihedral angle between two facets at a segment. Refused or invalid input: exit code 1.\n"
    "\n"
    "options:\n"
    "  -o FILE        write the PLC (.poly keeps everything; .smesh/.off need one polygon\n"
    "                 per facet; .vtu for viewing)\n"
    "  --weld TOL     surface meshes: weld vertices closer than TOL (default: exact only)\n"
    "  --no-merge     surface meshes: keep triangles, do not merge coplanar ones\n"
    "  --allow-open   surface meshes: import open surfaces too (for inspection)\n"
    "  --deflection R CAD files: chordal deflection of curved faces as a fraction of the\n"
    "                 bounding-box diagonal (0 < R < 1; default 0.001)\n"
    "  --angle DEG    CAD files: angular deflection (0 < DEG < 180; default 20)\n"
    "  --no-glue      CAD files: do not glue touching solids into shared facets\n"
    "  --plane-tol R  CAD files: coordinate planes (x, y or z constant) closer than R times\n"
    "                 the bounding-box diagonal are one plane (0 <= R < 0.001; default\n"
    "                 1e-10; 0: only equal values)\n"
    "  --quiet        print nothing but errors\n";

/// "N named, M coloured" and, for a short table, one line per coloured or named id.
void print_table(const char* what, const std::map<int, std::string>& names,
                 const std::map<int, Plc::Color>& colors) {
  std::set<int> ids;
  for (const auto& entry : names) ids.insert(entry.first);
  for (const auto& entry : colors) ids.insert(entry.first);
  std::printf("%-24s %zu named, %zu coloured\n", what, names.size(), colors.size());
  if (ids.size() > 20) return;
  for (int id : ids) {
    const auto name = names.find(id);
    const auto color = colors.find(id);
    std::printf("  %-22d %-8s %s\n", id, color == colors.end() ? "-" : color_hex(color->second).c_str(),
                name == names.end() ? "" : name->second.c_str());
  }
}

void print_summary(const Plc& plc, const std::vector<PlcIssue>& issues, double seconds) {
  const PlcStatistics stats = plc_statistics(plc);
  std::printf("vertices                 %zu\n", stats.vertices);
  std::printf("segments                 %zu\n", stats.segments);
  std::printf("facets                   %zu (%zu polygons)\n", stats.facets, stats.polygons);
  std::printf("regions                  %zu\n", stats.regions);
  std::printf("volume holes             %zu\n", stats.holes);
  print_table("facet marker table", plc.facet_marker_names, plc.facet_marker_colors);
  print_table("region table", plc.region_names, plc.region_colors);
  if (stats.min_angle_vertex != ~0u) {
    std::printf("smallest segment angle   %.4g deg at vertex %u\n", stats.min_segment_angle_deg,
                stats.min_angle_vertex);
  } else {
    std::printf("smallest segment angle   -\n");
  }
  if (stats.min_dihedral_facets[0] != ~0u) {
    std::printf("smallest facet dihedral  %.4g deg at segment %u-%u (facets %u, %u)\n",
                stats.min_dihedral_deg, stats.min_dihedral_edge[0], stats.min_dihedral_edge[1],
                stats.min_dihedral_facets[0], stats.min_dihedral_facets[1]);
  } else {
    std::printf("smallest facet dihedral  -\n");
  }
  std::printf("validation issues        %zu\n", issues.size());
  std::printf("time                     %.3f s\n", seconds);
}

}  // namespace

int run_import(CommandArgs args) {
  std::string input, output;
  bool quiet = false;
  ImportOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (a == "-o") {
      if (++i >= args.size()) return usage_error("import", "-o needs a file name");
      output = std::string(args[i]);
    } else if (a == "--weld") {
      if (++i >= args.size()) return usage_error("import", "--weld needs a tolerance");
      const auto tol = parse_double(args[i]);
      if (!tol || *tol < 0) return usage_error("import", "--weld needs a non-negative number");
      options.weld_tolerance = *tol;
    } else if (a == "--no-merge") {
      options.merge_coplanar = false;
    } else if (a == "--allow-open") {
      options.require_closed = false;
    } else if (a == "--deflection" || a == "--angle") {
      if (++i >= args.size()) return usage_error("import", std::string(a) + " needs a number");
      const auto value = parse_double(args[i]);
      const double limit = a == "--angle" ? 180.0 : 1.0;
      if (!value || !(*value > 0.0 && *value < limit))
        return usage_error("import", std::string(a) + " needs a number in (0, " + (a == "--angle" ? "180)" : "1)"));
      (a == "--angle" ? options.step.angular_deflection_deg : options.step.relative_linear_deflection) = *value;
    } else if (a == "--plane-tol") {
      if (++i >= args.size()) return usage_error("import", "--plane-tol needs a number");
      const auto value = parse_double(args[i]);
      if (!value || !(*value >= 0.0 && *value < 1e-3))
        return usage_error("import", "--plane-tol needs a number in [0, 0.001)");
      options.step.relative_plane_tolerance = *value;
    } else if (a == "--no-glue") {
      options.step.glue_assembly = false;
    } else if (a == "--quiet" || a == "-Q") {
      quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("import", "unknown option '" + std::string(a) + "'");
    } else if (input.empty()) {
      input = std::string(a);
    } else {
      return usage_error("import", "more than one input file");
    }
  }
  if (input.empty()) return usage_error("import", "no input file");
  StderrLogSink sink(quiet);
  options.log = &sink;
  options.step.log = &sink;
  const Stopwatch clock;
  auto plc = import_file(input, options);
  if (!plc) return report_error(plc.error());
  PlcValidationOptions validation;
  validation.require_closed = options.require_closed;
  const auto issues = validate_plc(*plc, validation);
  const double seconds = clock.seconds();
  if (!quiet) {
    std::printf("input                    %s\n", input.c_str());
    print_summary(*plc, issues, seconds);
  }
  if (!issues.empty()) {
    std::cerr << "delmesh import: " << input << ": " << issues_to_error(issues, 20).message << '\n';
    return 1;
  }
  if (!output.empty()) {
    if (auto written = write_plc(*plc, output); !written) return report_error(written.error());
    if (!quiet) std::printf("written                  %s\n", output.c_str());
  }
  return 0;
}

}  // namespace delmesh::cli
