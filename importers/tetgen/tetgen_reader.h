// Readers for TetGen's 3D input files: .node (points), .poly (facets as polygons with
// holes) and .smesh (one polygon per facet), into a Plc. Formats as documented by TetGen
// (reference/tetgen-triangle-cli-and-formats.md §4.2): '#' starts a comment; vertex
// numbering starts at the first index of the node list (0 or 1); a .poly/.smesh whose
// node list has 0 points reads the sibling file with extension .node. Comment lines in
// the form delmesh's writers use for names and colours ("# facet_marker 3 name "top"
// color #ff0000", "# region 1 name "bracket"", toolkit/plc/plc_tables.h) fill the PLC's
// marker and region tables, so a .poly or .smesh written by delmesh reads back with them.
//
// A facet made only of 2-vertex polygons (TetGen's way of giving free segments in 3D)
// becomes entries of Plc::segments with the facet's marker; isolated 1-vertex polygons
// alone in a facet are dropped (their vertex is a PLC vertex anyway).
//
// Every malformed input gives an Error with code ParseError (or InvalidInput for a bad
// vertex number) located at file:line; counts are never trusted for allocation.
#pragma once

#include <filesystem>
#include <string_view>

#include "toolkit/core/error.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

enum class TetgenFileKind { Node, Poly, Smesh };

/// Reads a .node, .poly or .smesh file (kind from the extension when not given).
Expected<Plc> read_tetgen(const std::filesystem::path& path);
Expected<Plc> read_tetgen(const std::filesystem::path& path, TetgenFileKind kind);

/// Parses file contents already in memory. `file_name` is used in error locations; when
/// the node list is empty, the points are read from `node_file` (an error if empty).
Expected<Plc> parse_tetgen(std::string_view text, TetgenFileKind kind, std::string_view file_name,
                           const std::filesystem::path& node_file = {});

}  // namespace delmesh
