// `delmesh mesh`: a CAD model, a closed surface or a TetGen .poly/.smesh in, a quality
// tetrahedral mesh out (issue 5: importers/import.h -> refiners/tet3d/mesh_plc.h ->
// toolkit/mesh3d/tetra_mesh_writer.h), with long options or TetGen switch strings
// (tetgen_switches.h), a summary and --stats JSON (mesh_report.h), --check (check_mesh).
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>

#include "importers/import.h"
#include "importers/input_format.h"
#include "refiners/tet3d/angle_bearing.h"
#include "refiners/tet3d/interior_strategy.h"
#include "refiners/tet3d/mesh_plc.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"
#include "tools/delmesh/allocator_policy.h"
#include "tools/delmesh/cli_support.h"
#include "tools/delmesh/commands.h"
#include "tools/delmesh/mesh_report.h"
#include "tools/delmesh/progress_sink.h"
#include "tools/delmesh/tetgen_switches.h"

namespace delmesh::cli {

namespace {

constexpr std::string_view kVerb = "mesh";

constexpr std::string_view kHelp =
    "usage: delmesh mesh INPUT [-o OUTPUT] [options]\n"
    "       delmesh mesh -pq1.414a0.1 INPUT        (TetGen switches)\n"
    "\n"
    "Quality tetrahedral mesh of a solid: 3D Delaunay refinement with every input facet\n"
    "kept as tagged boundary triangles and every region as tet attributes.\n"
    "\n"
    "INPUT   .step .stp .brep .iges .igs (CAD), .stl .off .obj .ply (closed surfaces),\n"
    "        .poly .smesh (TetGen PLCs)\n"
    "OUTPUT  format by extension: .vtu (ParaView), .msh (Gmsh 4.1; --gmsh22 for 2.2),\n"
    "        .mesh (Medit), .node (TetGen: writes .node, .ele and .face), .inp (Abaqus),\n"
    "        .ovm (OpenVolumeMesh). Default: INPUT's name with TetGen's iteration number,\n"
    "        'part.poly' -> part.1.node/.1.ele/.1.face.\n"
    "\n"
    "  -o OUTPUT            output file\n"
    "  --radius-edge B      circumradius-to-shortest-edge bound (default 2.0)\n"
    "  --interior-strategy S  uniform: the bound B for every tet (default); graded: B = 1\n"
    "                       away from the boundary, sqrt(2) at facets, 2 at segments, each\n"
    "                       capped by B (notes 4.3)\n"
    "  --no-quality         no quality refinement (boundary recovery and volume bounds only)\n"
    "  --facet-recovery M   ccdt: facets recovered without Steiner points as a conforming\n"
    "                       constrained Delaunay tetrahedralization (falls back to splits\n"
    "                       where that fails; refinement then inserts with constrained\n"
    "                       cavities); conforming: missing subfacets split at circumcenters.\n"
    "                       Default: ccdt without refinement (--no-quality, TetGen -p), else\n"
    "                       conforming, rerun as ccdt if it stops at its Steiner-point bound\n"
    "  --segment-recovery M diametral: split every missing or encroached subsegment (closed\n"
    "                       diametral spheres, default); strongly-delaunay: split only those\n"
    "                       missing or not strongly Delaunay, recover facets as a CCDT and\n"
    "                       refine it splitting boundary elements only for rejected points\n"
    "  --max-volume V       maximum tet volume\n"
    "  --min-dihedral DEG   minimum dihedral angle target (default none)\n"
    "  --max-dihedral DEG   maximum dihedral angle target (default none)\n"
    "  --no-improve         no default improvement of the tets with a dihedral angle\n"
    "                       below 10 degrees (done without --min/--max-dihedral; never\n"
    "                       makes a tet above the radius-edge or volume bound)\n"
    "  --off-centers        split tets outside the dihedral window at Chew's random\n"
    "                       off-centers instead of circumcenters (notes 4.4)\n"
    "  --max-steiner N      last-resort budget of Steiner points (result Partial when hit)\n"
    "  --seed N             seed of randomized choices (default 1; same seed, same mesh)\n"
    "  --keep-hull          keep the convex hull's tets outside the domain, as region -1\n"
    "  --gmsh22             write .msh as Gmsh 2.2\n"
    "  --zero-based         TetGen files numbered from 0\n"
    "  --check              verify the mesh (orientation, facets, segments, constrained\n"
    "                       Delaunay, volume); exit code 1 if it finds a problem\n"
    "  --stats FILE.json    write the summary figures as JSON\n"
    "  --quiet              no summary or progress; warnings only\n"
    "  --verbose            also informational messages\n"
    "\n"
    "TetGen switches (one or more arguments starting with a single '-'):\n"
    "  -p  PLC (accepted)      -q[B][/DEG]  quality        -a#  max volume\n"
    "  -a  region max volumes  -A  region attributes (always written)\n"
    "  -c  keep convex hull    -S#  Steiner budget          -C  check\n"
    "  -Q  quiet               -V  verbose                  -z  number from zero\n"
    "  -I  no iteration number in output names              -g  also write Medit .mesh\n"
    "  -O0 no default improvement (-O, -O#: on)\n"
    "Without -q or -a, TetGen switches mean no quality refinement, as in TetGen.\n"
    "\n"
    "Exit code: 0 mesh written (status Complete or Partial, see the summary), 1 input\n"
    "refused or --check failed (message names the file, line or entity), 2 usage error.\n";

struct MeshArgs {
  std::string input;
  std::string output;
  std::string stats;
  bool gmsh22 = false;
  TetgenSwitches switches;  ///< flags and options, from TetGen's or delmesh's defaults
  bool used_switches = false;
};

bool is_switch_string(std::string_view a) { return a.size() >= 2 && a[0] == '-' && a[1] != '-'; }

/// Parses the command line; returns an exit code when parsing ends the run (help, error).
std::optional<int> parse_args(CommandArgs args, MeshArgs& out) {
  // TetGen's defaults (no quality) apply when any switch string is present.
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "-o") {
      ++i;
    } else if (is_switch_string(args[i]) && args[i] != "-h") {
      out.used_switches = true;
    }
  }
  if (!out.used_switches) out.switches.options = MeshOptions{};
  MeshOptions& options = out.switches.options;
  auto number = [&](std::size_t& i) -> std::optional<double> {
    if (i + 1 >= args.size()) return std::nullopt;
    return parse_double(args[++i]);
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    if (a == "--help" || a == "-h") {
      std::cout << kHelp;
      return 0;
    } else if (a == "-o") {
      if (i + 1 >= args.size()) return usage_error(kVerb, "-o needs a file name");
      out.output = std::string(args[++i]);
    } else if (a == "--stats") {
      if (i + 1 >= args.size()) return usage_error(kVerb, "--stats needs a file name");
      out.stats = std::string(args[++i]);
    } else if (a == "--radius-edge") {
      const auto v = number(i);
      if (!v || !(*v > 0)) return usage_error(kVerb, "--radius-edge needs a positive number");
      options.quality = true;
      options.max_radius_edge = *v;
    } else if (a == "--interior-strategy") {
      if (i + 1 >= args.size()) return usage_error(kVerb, "--interior-strategy needs uniform or graded");
      const auto strategy = parse_interior_strategy(args[++i]);
      if (!strategy) {
        return usage_error(kVerb, "--interior-strategy: '" + std::string(args[i]) + "' is not uniform or graded");
      }
      options.interior_strategy = *strategy;
    } else if (a == "--no-quality") {
      options.quality = false;
    } else if (a == "--facet-recovery") {
      if (i + 1 >= args.size()) return usage_error(kVerb, "--facet-recovery needs ccdt or conforming");
      const std::string_view mode = args[++i];
      if (mode == "ccdt") {
        options.facet_recovery = FacetRecovery::Ccdt;
      } else if (mode == "conforming") {
        options.facet_recovery = FacetRecovery::Conforming;
      } else {
        return usage_error(kVerb, "--facet-recovery: '" + std::string(mode) + "' is not ccdt or conforming");
      }
    } else if (a == "--segment-recovery") {
      if (i + 1 >= args.size()) return usage_error(kVerb, "--segment-recovery needs diametral or strongly-delaunay");
      const std::string_view mode = args[++i];
      if (mode == "diametral") {
        options.segment_recovery = SegmentRecovery::Diametral;
      } else if (mode == "strongly-delaunay") {
        options.segment_recovery = SegmentRecovery::StronglyDelaunay;
      } else {
        return usage_error(kVerb,
                           "--segment-recovery: '" + std::string(mode) + "' is not diametral or strongly-delaunay");
      }
    } else if (a == "--max-volume") {
      const auto v = number(i);
      if (!v || !(*v > 0)) return usage_error(kVerb, "--max-volume needs a positive number");
      options.max_volume = *v;
    } else if (a == "--no-improve") {
      options.improve = false;
    } else if (a == "--off-centers") {
      options.sliver_off_centers = true;
    } else if (a == "--min-dihedral" || a == "--max-dihedral") {
      const auto v = number(i);
      if (!v || *v < 0 || *v > 180) return usage_error(kVerb, std::string(a) + " needs an angle in degrees");
      (a == "--min-dihedral" ? options.min_dihedral_deg : options.max_dihedral_deg) = *v;
    } else if (a == "--max-steiner" || a == "--seed") {
      if (i + 1 >= args.size()) return usage_error(kVerb, std::string(a) + " needs a count");
      const auto v = parse_count(args[++i]);
      if (!v) return usage_error(kVerb, std::string(a) + ": '" + std::string(args[i]) + "' is not a count");
      if (a == "--seed") {
        options.seed = *v;
      } else {
        options.max_steiner_points = static_cast<long long>(*v);
      }
    } else if (a == "--keep-hull") {
      options.keep_convex_hull = true;
    } else if (a == "--gmsh22") {
      out.gmsh22 = true;
    } else if (a == "--zero-based") {
      out.switches.zero_based = true;
    } else if (a == "--check") {
      out.switches.check = true;
    } else if (a == "--quiet") {
      out.switches.quiet = true;
    } else if (a == "--verbose") {
      out.switches.verbose = true;
    } else if (is_switch_string(a)) {
      if (auto r = apply_tetgen_switches(a, out.switches); !r) return usage_error(kVerb, r.error().message);
    } else if (a.size() >= 2 && a[0] == '-') {
      return usage_error(kVerb, "unknown option '" + std::string(a) + "'");
    } else if (out.input.empty()) {
      out.input = std::string(a);
    } else {
      return usage_error(kVerb, "more than one input file ('" + out.input + "', '" + std::string(a) + "')");
    }
  }
  if (out.input.empty()) return usage_error(kVerb, "no input file");
  if (options.min_dihedral_deg >= options.max_dihedral_deg) {
    return usage_error(kVerb, "--min-dihedral must be below --max-dihedral");
  }
  if (out.output.empty()) out.output = tetgen_output_base(out.input, out.switches.iteration_number) + ".node";
  const std::string ext = extension_of(out.output);
  if (ext != ".vtu" && ext != ".msh" && ext != ".mesh" && ext != ".node" && ext != ".ele" && ext != ".inp" &&
      ext != ".ovm") {
    return usage_error(kVerb, "unknown output format '" + out.output +
                                  "' (use .vtu .msh .mesh .node .inp or .ovm)");
  }
  return std::nullopt;
}

bool write_text_file(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  file.close();
  return static_cast<bool>(file);
}

}  // namespace

int run_mesh(CommandArgs args) {
  MeshArgs cli;
  if (const auto code = parse_args(args, cli)) return *code;
  use_mapped_large_blocks();
  const TetgenSwitches& flags = cli.switches;
  StderrProgress progress(flags.quiet, flags.verbose);
  ProgressLogSink& sink = progress.sink();

  Stopwatch import_clock;
  sink.set_phase("importing");
  ImportOptions import_options;
  import_options.log = &sink;
  import_options.step.log = &sink;
  // A CAD tessellation without triangle corners the radius-edge bound cannot meet.
  if (flags.options.quality)
    import_options.step.surface_min_angle_deg = tet3d::tessellation_min_angle_deg(flags.options.max_radius_edge);
  auto plc = import_file(cli.input, import_options);
  if (!plc) {
    sink.finish_line();
    return report_error(plc.error());
  }
  const double import_seconds = import_clock.seconds();

  MeshOptions options = flags.options;
  options.log = &sink;
  Stopwatch mesh_clock;
  sink.set_phase("meshing");
  auto result = mesh_plc(*plc, options);
  sink.finish_line();
  if (!result) {
    Error error = result.error();
    if (!error.location) error.location = SourceLocation{cli.input, 0};
    return report_error(error);
  }
  const double mesh_seconds = mesh_clock.seconds();
  result->mesh.marker_names.insert(plc->facet_marker_names.begin(), plc->facet_marker_names.end());
  result->mesh.region_names.insert(plc->region_names.begin(), plc->region_names.end());

  Stopwatch write_clock;
  sink.set_phase("writing");
  TetraWriteOptions write_options;
  write_options.zero_based = flags.zero_based;
  write_options.gmsh_version = cli.gmsh22 ? 22 : 41;
  write_options.tet_at_small_angle = &result->tet_at_small_angle;
  std::vector<std::string> outputs;
  auto written = write_tetra_mesh(cli.output, result->mesh, write_options);
  if (!written) return report_error(written.error());
  for (const auto& file : *written) outputs.push_back(file.string());
  if (flags.medit && extension_of(cli.output) != ".mesh") {
    const std::string medit = strip_extension(cli.output) + ".mesh";
    if (auto w = write_tetra_mesh(medit, result->mesh, write_options); !w) return report_error(w.error());
    outputs.push_back(medit);
  }
  const double write_seconds = write_clock.seconds();

  MeshReport report = make_mesh_report(*plc, *result, flags.options);
  report.input = cli.input;
  report.input_format = std::string(to_string(detect_input_format(cli.input)));
  report.import_seconds = import_seconds;
  report.mesh_seconds = mesh_seconds;
  report.write_seconds = write_seconds;
  report.outputs = outputs;

  std::vector<MeshCheckIssue> issues;
  if (flags.check) {
    Stopwatch check_clock;
    sink.set_phase("checking");
    CheckMeshOptions check_options;
    check_options.check_delaunay = result->constrained_delaunay;
    issues = check_mesh(result->mesh, *plc, result->boundary_face_facets, check_options);
    report.check_seconds = check_clock.seconds();
    report.check_issues = issues.size();
  }

  progress.stop();
  if (!flags.quiet) std::cerr << mesh_summary_text(report);
  if (result->status == MeshStatus::Partial) {
    sink.write(LogLevel::Warning, "the mesh misses the requested bounds in " +
                                      std::to_string(result->stats.unmet_tets) + " tets (status Partial)");
  }
  if (!cli.stats.empty() && !write_text_file(cli.stats, mesh_stats_json(report))) {
    return report_error(make_error(ErrorCode::IoError, "cannot write the statistics file '" + cli.stats + "'"));
  }
  if (flags.check) {
    for (const MeshCheckIssue& issue : issues) {
      std::cerr << "check: " << to_string(issue.kind) << ": " << issue.message << '\n';
    }
    if (!issues.empty()) {
      std::cerr << "delmesh mesh: --check FAILED (" << issues.size() << " issues)\n";
      return 1;
    }
    if (!flags.quiet) std::cerr << "check: mesh verified against the input\n";
  }
  return 0;
}

}  // namespace delmesh::cli
