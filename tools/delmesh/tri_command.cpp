// `delmesh tri`: 2D triangulation and quality refinement of Triangle .poly / .node files
// (library entry point refiners/tri2d/triangulate.h, notes ch. 3), with delmesh's long
// options and, for users coming from Shewchuk's Triangle, its switch strings
// (`delmesh tri -pq30a0.01 A.poly`). Output formats follow the extension of -o: Triangle's
// .node/.ele/.poly(/.edge), VTK .vtu, or an .svg picture.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "refiners/tri2d/triangulate.h"
#include "toolkit/mesh2d/svg_writer.h"
#include "toolkit/mesh2d/triangle_format_reader.h"
#include "toolkit/mesh2d/triangle_format_writer.h"
#include "toolkit/mesh2d/vtu_writer.h"
#include "tools/delmesh/cli_support.h"
#include "tools/delmesh/commands.h"

namespace delmesh::cli {
namespace {

constexpr std::string_view kVerb = "tri";

constexpr std::string_view kUsage = R"(usage: delmesh tri INPUT [-o OUT.{node,vtu,svg}] [options]
       delmesh tri -SWITCHES INPUT [-o OUT]          (Triangle-style, e.g. -pq30a0.01)

Triangulates a planar straight line graph (.poly: vertices, segments, holes, regional
attributes and area bounds) or a point set (.node), optionally with Delaunay refinement
to a minimum angle and a maximum triangle area. Files are read and written in Triangle's
formats; numbering (0 or 1) follows the input unless -z is given.

What is computed:
  .poly input             constrained Delaunay triangulation of the PSLG, holes and
                          concavities removed (Triangle's -p is implied)
  .node input             Delaunay triangulation of the points; with a quality or area
                          bound, refined inside their convex hull (-p changes nothing)
  --min-angle DEG, -q#    Ruppert refinement: no angle below DEG (0 <= DEG < 60; -q alone: 20).
                          Where a small input angle makes the bound unreachable, the
                          triangles there are left and the status says Partial
  --max-area A, -a#       refine until no triangle has an area above A (with no angle
                          bound unless one is given)
  --uniform               Chew's first algorithm instead of Ruppert's (implies refinement)

Options:
  -o, --output FILE       output; the extension picks the format (repeat -o for several):
                            .node  FILE.node, FILE.ele, FILE.poly (+ FILE.edge with -e)
                            .vtu   VTK unstructured grid with cell data min_angle, region
                            .svg   picture: segments thick, the 1% worst triangles red
                          default: Triangle's naming, INPUT.1.node/.1.ele/.1.poly
                          (A.1.poly -> A.2.*); missing directories are created
  --min-angle DEG         see above
  --max-area A            see above
  --uniform               see above
  --region-areas          apply the per-region area bounds of the .poly (-a without number)
  --region-attributes     copy regional attributes to triangles (-A)
  --convex-hull           keep the triangles of the convex hull (-c)
  --max-steiner N         at most N Steiner points (-S#); the status is Partial if they run out
  --edges                 also write FILE.edge (-e)
  --zero-based            number output from 0 (-z)
  --no-output             write nothing (timing runs)
  --quiet                 print nothing but errors and warnings (-Q)
  --verbose               print progress (-V)
  -h, --help              this text

Triangle switches (one word starting with '-', letters in any order):
  p  triangulate the PSLG         q# minimum angle (default 20)   a# maximum area
  a  regional area bounds         A  regional attributes         c  keep convex hull
  S# Steiner point budget         e  write .edge                 z  zero-based output
  O  ignore holes                 B  no boundary markers         P  no .poly output
  N  no .node output              E  no .ele output              Q  quiet    V  verbose
Numbers may have exponents (-pq30a5e-8). Triangle's other switches are refused.

Prints vertices, triangles, segments, min/max angle, status and time. Exit code 0 on
success, 1 when the input is refused or the run fails, 2 for a usage error.
)";

struct TriArgs {
  std::string input;
  std::vector<std::string> outputs;
  TriangulateOptions options;
  bool quality = false;
  bool zero_based = false;
  bool edges = false;
  bool markers = true;
  bool write_node = true;
  bool write_ele = true;
  bool write_poly = true;
  bool no_output = false;
  bool ignore_holes = false;
  bool quiet = false;
  bool verbose = false;
  bool help = false;
};

/// Reads the number that starts at `word[i]` (digits, '.', and an exponent 'e'/'E' only
/// when a digit or a sign follows it). Returns its text and advances i past it.
std::string_view take_number(std::string_view word, std::size_t& i) {
  const std::size_t start = i;
  while (i < word.size() && ((word[i] >= '0' && word[i] <= '9') || word[i] == '.')) ++i;
  if (i > start && i + 1 < word.size() && (word[i] == 'e' || word[i] == 'E')) {
    std::size_t j = i + 1;
    if (word[j] == '-' || word[j] == '+') ++j;
    if (j < word.size() && word[j] >= '0' && word[j] <= '9') {
      i = j;
      while (i < word.size() && word[i] >= '0' && word[i] <= '9') ++i;
    }
  }
  return word.substr(start, i - start);
}

/// "" on success, else the usage error message.
std::string set_min_angle(TriArgs& a, std::string_view text, std::string_view flag) {
  const auto value = parse_double(text);
  if (!value || *value < 0 || *value >= 60) {
    return std::string(flag) + " needs an angle in degrees, 0 <= DEG < 60 (got '" + std::string(text) + "')";
  }
  a.quality = true;
  a.options.min_angle_deg = *value;
  return {};
}

std::string set_max_area(TriArgs& a, std::string_view text, std::string_view flag) {
  const auto value = parse_double(text);
  if (!value || *value <= 0) {
    return std::string(flag) + " needs a positive area (got '" + std::string(text) + "')";
  }
  a.options.max_area = *value;
  return {};
}

std::string set_steiner(TriArgs& a, std::string_view text, std::string_view flag) {
  const auto value = parse_count(text);
  if (!value || *value > static_cast<unsigned long long>(std::numeric_limits<long long>::max())) {
    return std::string(flag) + " needs a non-negative integer (got '" + std::string(text) + "')";
  }
  a.options.max_steiner_points = static_cast<long long>(*value);
  return {};
}

/// Applies a Triangle switch string such as "-pq30a0.01". "" on success.
std::string apply_switches(TriArgs& a, std::string_view word) {
  for (std::size_t i = 1; i < word.size();) {
    const char c = word[i++];
    switch (c) {
      case 'p': break;  // implied by a .poly input
      case 'q': {
        const std::string_view number = take_number(word, i);
        a.quality = true;
        if (!number.empty()) {
          if (auto e = set_min_angle(a, number, "-q"); !e.empty()) return e;
        }
        break;
      }
      case 'a': {
        const std::string_view number = take_number(word, i);
        if (number.empty()) {
          a.options.region_max_area = true;
        } else if (auto e = set_max_area(a, number, "-a"); !e.empty()) {
          return e;
        }
        break;
      }
      case 'S': {
        const std::string_view number = take_number(word, i);
        if (auto e = set_steiner(a, number, "-S"); !e.empty()) return e;
        break;
      }
      case 'A': a.options.region_attributes = true; break;
      case 'c': a.options.keep_convex_hull = true; break;
      case 'e': a.edges = true; break;
      case 'z': a.zero_based = true; break;
      case 'O': a.ignore_holes = true; break;
      case 'B': a.markers = false; break;
      case 'P': a.write_poly = false; break;
      case 'N': a.write_node = false; break;
      case 'E': a.write_ele = false; break;
      case 'Q': a.quiet = true; break;
      case 'V': a.verbose = true; break;
      case 'h': a.help = true; break;
      default:
        return std::string("Triangle switch '") + c + "' in '" + std::string(word) +
               "' is not supported by delmesh tri";
    }
  }
  return {};
}

/// Parses the arguments; "" on success, else the usage error message.
std::string parse_args(CommandArgs args, TriArgs& a) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string_view arg = args[i];
    std::string_view inline_value;
    bool has_inline = false;
    if (arg.starts_with("--")) {
      if (const auto eq = arg.find('='); eq != std::string_view::npos) {
        inline_value = arg.substr(eq + 1);
        arg = arg.substr(0, eq);
        has_inline = true;
      }
    }
    auto value = [&](std::string_view& out) -> bool {
      if (has_inline) {
        out = inline_value;
        return true;
      }
      if (i + 1 >= args.size()) return false;
      out = args[++i];
      return true;
    };
    std::string_view v;
    if (arg == "-h" || arg == "--help") {
      a.help = true;
    } else if (arg == "-o" || arg == "--output") {
      if (!value(v) || v.empty()) return "-o needs a file name";
      a.outputs.emplace_back(v);
    } else if (arg == "--min-angle") {
      if (!value(v)) return "--min-angle needs a value";
      if (auto e = set_min_angle(a, v, arg); !e.empty()) return e;
    } else if (arg == "--max-area") {
      if (!value(v)) return "--max-area needs a value";
      if (auto e = set_max_area(a, v, arg); !e.empty()) return e;
    } else if (arg == "--max-steiner") {
      if (!value(v)) return "--max-steiner needs a value";
      if (auto e = set_steiner(a, v, arg); !e.empty()) return e;
    } else if (arg.starts_with("--")) {
      if (has_inline) return "option " + std::string(arg) + " takes no value";
      if (arg == "--uniform") {
        a.options.chew = true;
      } else if (arg == "--region-areas") {
        a.options.region_max_area = true;
      } else if (arg == "--region-attributes") {
        a.options.region_attributes = true;
      } else if (arg == "--convex-hull") {
        a.options.keep_convex_hull = true;
      } else if (arg == "--edges") {
        a.edges = true;
      } else if (arg == "--zero-based") {
        a.zero_based = true;
      } else if (arg == "--no-output") {
        a.no_output = true;
      } else if (arg == "--quiet") {
        a.quiet = true;
      } else if (arg == "--verbose") {
        a.verbose = true;
      } else {
        return "unknown option " + std::string(arg);
      }
    } else if (arg.size() > 1 && arg[0] == '-') {
      if (auto e = apply_switches(a, arg); !e.empty()) return e;
    } else {
      if (!a.input.empty()) return "more than one input file ('" + a.input + "', '" + std::string(arg) + "')";
      a.input = std::string(arg);
    }
  }
  if (a.help) return {};
  if (a.input.empty()) return "no input file (a .poly or .node)";
  const std::string ext = extension_of(a.input);
  if (ext != ".poly" && ext != ".node") {
    return "input '" + a.input + "' must be a Triangle .poly or .node file";
  }
  for (const auto& out : a.outputs) {
    const std::string oext = extension_of(out);
    if (oext != ".node" && oext != ".vtu" && oext != ".svg") {
      return "output '" + out + "' must end in .node, .vtu or .svg";
    }
  }
  if (a.options.chew) a.quality = true;
  return {};
}

/// Triangle's output naming: "dir/A.poly" -> "dir/A.1", "dir/A.3.poly" -> "dir/A.4".
std::string default_output_base(const std::string& input) {
  const std::string base = strip_extension(input);
  const auto dot = base.find_last_of('.');
  const auto slash = base.find_last_of('/');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash) && dot + 1 < base.size()) {
    const auto iteration = parse_count(std::string_view(base).substr(dot + 1));
    if (iteration && *iteration < 1000000000ULL) {
      return base.substr(0, dot + 1) + std::to_string(*iteration + 1);
    }
  }
  return base + ".1";
}

std::string plural(std::size_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

/// Six significant digits: "30.0194", "3.61215e-05".
std::string significant(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

/// Writes every requested output; returns the files written, or the first Error.
Expected<std::vector<std::string>> write_outputs(const TriArgs& a, const TriangleMesh& mesh,
                                                 int first_index) {
  std::vector<std::string> written;
  if (a.no_output) return written;
  std::vector<std::string> outputs = a.outputs;
  if (outputs.empty()) outputs.push_back(default_output_base(a.input) + ".node");
  TriangleWriteOptions options;
  options.first_index = a.zero_based ? 0 : first_index;
  options.markers = a.markers;
  auto record = [&](Expected<void> result, const std::string& path) -> Expected<void> {
    if (result) written.push_back(path);
    return result;
  };
  for (const auto& out : outputs) {
    if (const auto parent = std::filesystem::path(out).parent_path(); !parent.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(parent, ec);  // a failure surfaces when the file is created
    }
    const std::string ext = extension_of(out);
    const std::string base = strip_extension(out);
    if (ext == ".vtu") {
      if (auto r = record(write_vtu(out, mesh), out); !r) return r.error();
    } else if (ext == ".svg") {
      if (auto r = record(write_svg(out, mesh), out); !r) return r.error();
    } else {
      if (a.write_node) {
        if (auto r = record(write_triangle_node(base + ".node", mesh, options), base + ".node"); !r) {
          return r.error();
        }
      }
      if (a.write_ele) {
        if (auto r = record(write_triangle_ele(base + ".ele", mesh, options), base + ".ele"); !r) {
          return r.error();
        }
      }
      if (a.write_poly) {
        if (auto r = record(write_triangle_poly(base + ".poly", mesh, options), base + ".poly"); !r) {
          return r.error();
        }
      }
      if (a.edges) {
        if (auto r = record(write_triangle_edge(base + ".edge", mesh, options), base + ".edge"); !r) {
          return r.error();
        }
      }
    }
  }
  return written;
}

}  // namespace

int run_tri(CommandArgs args) {
  const Stopwatch total;
  TriArgs a;
  if (const std::string e = parse_args(args, a); !e.empty()) return usage_error(kVerb, e);
  if (a.help) {
    std::cout << kUsage;
    return 0;
  }

  const Stopwatch reading;
  auto input = read_triangle_input(a.input);
  if (!input) return report_error(input.error());
  const double read_seconds = reading.seconds();
  Pslg& pslg = input->pslg;
  if (a.ignore_holes) pslg.holes.clear();
  const std::size_t input_points = pslg.points.size();
  const std::size_t input_segments = pslg.segments.size();
  const std::size_t input_holes = pslg.holes.size();
  const std::size_t input_regions = pslg.regions.size();

  StderrLogSink sink(a.quiet, a.verbose);
  TriangulateOptions& options = a.options;
  options.quality = a.quality;
  options.pslg = input->has_segment_section;
  options.log = &sink;

  auto result = triangulate(pslg, options);
  if (!result) {
    Error e = result.error();
    if (!e.location) e.location = SourceLocation{a.input, 0};
    return report_error(e);
  }
  pslg = Pslg{};  // the input is no longer needed: free it before writing
  if (result->mesh.triangles.empty()) {
    return report_error(make_error(ErrorCode::DegenerateInput,
                                   "no triangles: the segments enclose no region outside the holes "
                                   "(-c / --convex-hull keeps the convex hull)",
                                   a.input, 0));
  }

  const Stopwatch writing;
  auto written = write_outputs(a, result->mesh, input->first_index);
  if (!written) return report_error(written.error());
  const double write_seconds = writing.seconds();

  if (!a.quiet) {
    const TriangleMesh& mesh = result->mesh;
    const TriangulateStats& stats = result->stats;
    std::cout << "input:      " << a.input << " (" << plural(input_points, "vertex", "vertices") << ", "
              << plural(input_segments, "segment", "segments") << ", " << plural(input_holes, "hole", "holes") << ", "
              << plural(input_regions, "region", "regions") << ")\n";
    std::cout << "vertices:   " << mesh.points.size() << '\n'
              << "triangles:  " << mesh.triangles.size() << '\n'
              << "segments:   " << mesh.segments.size() << '\n'
              << "min angle:  " << significant(stats.min_angle_deg) << " deg\n"
              << "max angle:  " << significant(stats.max_angle_deg) << " deg\n";
    if (result->status == MeshStatus::Complete) {
      std::cout << "status:     Complete\n";
    } else {
      std::cout << "status:     Partial (" << plural(stats.unmet_triangles, "triangle", "triangles")
                << " left below the bounds: small input angles or the Steiner budget)\n";
    }
    std::cout << "time:       " << fixed(total.seconds(), 3) << " s (read " << fixed(read_seconds, 3)
              << ", triangulate " << fixed(stats.seconds_triangulate, 3) << ", refine "
              << fixed(stats.seconds_refine, 3) << ", write " << fixed(write_seconds, 3) << ")\n";
    if (!written->empty()) {
      std::cout << "wrote:     ";
      for (const auto& file : *written) std::cout << ' ' << file;
      std::cout << '\n';
    }
  }
  return 0;
}

}  // namespace delmesh::cli
