// Writes a Plc to a file chosen by extension: TetGen .poly/.smesh and .off
// (tetgen/tetgen_writer.h) or a VTK .vtu of its polygons for viewing in ParaView (one
// VTK_POLYGON cell per facet polygon of three or more vertices, one VTK_LINE per
// 2-vertex polygon and free segment, with cell data "facet" (facet id, -1 for free
// segments) and "marker", plus "color" (UInt8 RGB of the facet's marker, 0 0 0 for free
// segments and uncoloured markers) when the PLC has facet colours; region and hole points
// are not written).
#pragma once

#include <filesystem>
#include <string>

#include "toolkit/core/error.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

std::string format_plc_vtu(const Plc& plc);

/// .poly, .smesh, .off or .vtu; Unsupported for another extension.
Expected<void> write_plc(const Plc& plc, const std::filesystem::path& path);

}  // namespace delmesh
