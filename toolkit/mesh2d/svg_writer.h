// An SVG picture of a 2D triangle mesh for a quick look at its quality: every edge drawn
// thin, the subsegments (input segments) thicker, and the worst triangles (the given
// fraction with the smallest minimum angle, at least one) filled red. A caption states the
// triangle count, the angle range and the threshold of the highlighted triangles.
#pragma once

#include <filesystem>

#include "toolkit/core/error.h"
#include "toolkit/mesh2d/triangle_mesh.h"

namespace delmesh {

struct SvgOptions {
  double width_px = 1000.0;       ///< width of the drawing; the height follows the aspect ratio
  double worst_fraction = 0.01;   ///< fraction of triangles highlighted (smallest angles first)
};

Expected<void> write_svg(const std::filesystem::path& path, const TriangleMesh& mesh,
                         const SvgOptions& options = {});

}  // namespace delmesh
