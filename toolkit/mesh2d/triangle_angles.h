// Angles of 2D triangles in degrees, for quality reports, pictures and VTK cell data.
// Each angle is atan2(|cross|, dot) of its two edge vectors, which stays accurate for
// angles near 0 and 180 degrees (unlike acos of a normalized dot product). These are
// measurements, never sign decisions: topology is decided by the exact predicates.
#pragma once

#include <array>

#include "toolkit/mesh2d/triangle_mesh.h"

namespace delmesh {

/// The angles at a, b and c (degrees; 0 for a zero-length edge).
std::array<double, 3> triangle_angles_deg(const Point2& a, const Point2& b, const Point2& c);
/// The smallest angle of the triangle (degrees).
double triangle_min_angle_deg(const Point2& a, const Point2& b, const Point2& c);

struct AngleRange {
  double min_deg = 0.0;  ///< smallest angle over all triangles (0 with no triangles)
  double max_deg = 0.0;  ///< largest angle over all triangles
};

/// Smallest and largest angle of the triangles of `mesh` (indices must be valid).
AngleRange mesh_angle_range(const TriangleMesh& mesh);

}  // namespace delmesh
