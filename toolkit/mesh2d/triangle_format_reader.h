// Reader for Shewchuk's Triangle input formats: `.node` (a point set) and `.poly` (a PSLG
// with holes and regional attributes / area bounds), into a delmesh `Pslg`.
//
// Format (see Triangle's documentation and ../shared/reference/tetgen-triangle-cli-and-formats.md §4.3):
//   .node: <#vertices> <dimension = 2> <#attributes> <#boundary markers 0|1>
//          then per vertex: <id> <x> <y> [attributes] [marker]
//   .poly: a .node block (with #vertices = 0 the points come from the sibling .node file),
//          then <#segments> <#markers 0|1>, per segment: <id> <endpoint> <endpoint> [marker]
//          then <#holes>, per hole: <id> <x> <y> (a file ending after the segments has
//          no holes, as CGAL reads it; Triangle would refuse it)
//          then optionally <#regions>, per region: <id> <x> <y> <attribute> [<max area>]
//          (with only three numbers after the id, the one value serves as both attribute and
//          max area, as in Triangle).
// '#' starts a comment anywhere on a line; blank lines are skipped. Vertex numbering starts
// at 0 or 1, decided by the first vertex's id (any other first id is refused); ids must
// then be consecutive. Segment, hole and region ids are read but not interpreted.
//
// The reader is strict where Triangle is lenient, because a miscounted header silently
// shifts every later number: a line with too few or too many fields, a token that is not
// entirely a number, NaN or infinite coordinates, negative or absurd counts, a duplicate or
// out-of-sequence vertex id, a segment naming a missing vertex or joining a vertex to
// itself, and a file that ends early are all Errors naming the file and line. Nothing is
// allocated from an untrusted count: storage grows with the lines actually read.
//
// Duplicate vertex positions are not checked here: two vertices at the same point are a
// property of the geometry, and triangulate() decides what to do with them (see its header).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "toolkit/core/error.h"
#include "toolkit/mesh2d/pslg.h"

namespace delmesh {

/// A PSLG read from Triangle files, with the numbering the file used.
struct TriangleInput {
  Pslg pslg;
  int first_index = 1;        ///< 0 or 1: the id of the first vertex in the file
  bool has_segment_section = false;  ///< the input was a .poly (segments, holes, regions)
  std::string node_file;      ///< the file the vertices came from
};

/// Parses the text of a .node file. `file_name` is used in error messages only.
Expected<TriangleInput> parse_triangle_node(std::string_view text, std::string_view file_name);

/// Parses the text of a .poly file. When its vertex section is empty (count 0), the
/// vertices are taken from `read_node()` (the sibling .node file); an empty function
/// makes that case an error.
Expected<TriangleInput> parse_triangle_poly(
    std::string_view text, std::string_view file_name,
    const std::function<Expected<TriangleInput>()>& read_node = {});

/// Reads a .node file.
Expected<TriangleInput> read_triangle_node(const std::filesystem::path& path);
/// Reads a .poly file (and its sibling .node when the .poly lists no vertices).
Expected<TriangleInput> read_triangle_poly(const std::filesystem::path& path);
/// Reads a .node or .poly file, chosen by extension (case-insensitive).
Expected<TriangleInput> read_triangle_input(const std::filesystem::path& path);

}  // namespace delmesh
