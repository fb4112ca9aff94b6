// TetGen command-line switches for `delmesh mesh` (format: ../shared/reference/
// tetgen-triangle-cli-and-formats.md §4.1), so that a TetGen user can type
// `delmesh mesh -pq1.414a0.1 part.poly` and get the mesh and file names TetGen would write.
//
// Switches are letters concatenated after one '-', a number directly after its letter,
// several numbers separated by '/' or ','. Supported:
//   -p        mesh a PLC (the only mode; accepted for compatibility)
//   -q[B][/D] quality: radius-edge bound B (default 2.0), minimum dihedral D degrees (0)
//   -a#       global maximum tet volume (turns on -q)
//   -a        apply the regions' maximum volumes (turns on -q)
//   -A        region attributes per tet (delmesh always writes them; accepted)
//   -c        keep the convex hull (its outer tets get region -1)
//   -S#       Steiner-point budget
//   -C        check the mesh (check_mesh)      -Q  quiet      -V  verbose
//   -z        number output files from zero    -I  no iteration number in output names
//   -g        also write a Medit .mesh
//   -O[L]     mesh optimization: -O0 turns the default improvement off (MeshOptions::
//             improve); other levels keep it on (delmesh has one schedule); -OL/ops refused
// Anything else (-Y, -r, -o2, -m, -i, -T, -M, -d, -f, -e, -n, -k, ...) is refused with
// an InvalidOption / Unsupported error naming the switch rather than silently ignored.
// Without -q or -a no quality refinement is done, as in TetGen.
#pragma once

#include <string>
#include <string_view>

#include "refiners/tet3d/mesh_plc.h"
#include "toolkit/core/error.h"

namespace delmesh::cli {

struct TetgenSwitches {
  MeshOptions options = default_options();
  bool check = false;             ///< -C
  bool quiet = false;             ///< -Q
  bool verbose = false;           ///< -V
  bool zero_based = false;        ///< -z
  bool iteration_number = true;   ///< cleared by -I
  bool medit = false;             ///< -g

  /// TetGen's defaults: no quality refinement, no region volume bounds.
  static MeshOptions default_options() {
    MeshOptions options;
    options.quality = false;
    options.region_max_volume = false;
    return options;
  }
};

/// Applies one switch argument ("-pq1.414/18a0.1") to `into`. Several arguments may be
/// applied in turn ("-pq", "-a0.5"). Errors name the switch and the argument.
Expected<void> apply_tetgen_switches(std::string_view argument, TetgenSwitches& into);

/// Parses a single switch argument from TetGen's defaults.
Expected<TetgenSwitches> parse_tetgen_switches(std::string_view argument);

/// TetGen's output base name for `input`: "dir/name.poly" -> "dir/name.1",
/// "name.3.smesh" -> "name.4"; without the iteration number "dir/name".
std::string tetgen_output_base(std::string_view input, bool iteration_number = true);

}  // namespace delmesh::cli
