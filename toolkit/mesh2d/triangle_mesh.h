// A 2D triangle mesh as delmesh returns it: plain arrays, 0-based ids, counterclockwise
// triangles, subsegments with the markers of the input segments they lie on.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "toolkit/mesh2d/pslg.h"

namespace delmesh {

struct TriangleMesh {
  std::vector<Point2> points;
  std::vector<int> point_markers;        ///< 0 for interior points, else the input marker
  int num_point_attributes = 0;
  std::vector<double> point_attributes;  ///< points.size() * num_point_attributes
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counterclockwise
  std::vector<double> triangle_attributes;              ///< one per triangle when regions carry attributes, else empty
  std::vector<std::array<std::uint32_t, 2>> segments;   ///< subsegments of input segments
  std::vector<int> segment_markers;                     ///< one per subsegment
  std::vector<Point2> holes;                            ///< the input's hole points (for .poly output)
};

}  // namespace delmesh
