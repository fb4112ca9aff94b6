// Writers of a Plc as TetGen .poly / .smesh and as .off, so that an imported PLC can be
// inspected or fed to TetGen. Coordinates are written with 17 significant digits, which
// reads back bit for bit; vertices are numbered from 1 (TetGen's default).
//
// .poly keeps everything (polygons with holes, hole points, volume holes, regions with
// attribute and maximum volume, markers); Plc::segments become facets of one 2-vertex
// polygon, which tetgen_reader.h turns back into segments. .smesh and .off have one
// polygon per facet and no facet holes: a facet with several polygons or with holes is
// refused with an Unsupported error naming it. .smesh keeps markers, volume holes and
// regions; .off keeps vertices, polygons and, when the PLC has facet colours, the colour
// of each facet's marker as three integers 0-255 after its vertex ids (OFF's per-face
// colour; 0 0 0 for a facet whose marker has none). TetGen's formats have no field for
// names or colours: .poly and .smesh end with the marker and region tables as # comment
// lines ("# facet_marker 3 name "top" color #ff0000"), which TetGen skips.
#pragma once

#include <filesystem>
#include <string>

#include "toolkit/core/error.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

Expected<std::string> format_tetgen_poly(const Plc& plc);
Expected<std::string> format_tetgen_smesh(const Plc& plc);
Expected<std::string> format_off(const Plc& plc);

/// Writes `text` to `path` (IoError naming the path on failure).
Expected<void> write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace delmesh
