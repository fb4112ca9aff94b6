// Angle measures of CAD face tessellations (SurfaceMeshes, surface_refinement.h) that
// refinement and its acceptance test use: the smallest angle of a face's triangles that
// refinement can improve, i.e. not counting the corners between two CAD segments (an
// angle between two CAD edges at a CAD vertex, or between consecutive nodes of one CAD
// edge, is fixed by the input and its discretisation). No OCCT here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "importers/step/surface_refinement.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh::step {

/// Smallest 3D angle (degrees) of the triangles of face `face`, skipping triangles with a
/// repeated vertex (collapsed at a pole) and triangles whose smallest corner lies between
/// two edges on CAD segments; 180 when no triangle counts.
double smallest_unforced_angle_deg(const SurfaceMeshes& meshes, std::size_t face, const std::vector<Vec3>& points);

/// The smallest angle of smallest_unforced_angle_deg and where it lies: the smallest
/// corner of the face (the sum of its triangles' angles at a vertex on the face's
/// boundary, 360 for an inner vertex) among the vertices of its triangle.
struct UnforcedAngle {
  double angle_deg = 180.0;
  double corner_deg = 360.0;
  /// The smallest such angle of the triangles with no vertex at a corner of the face
  /// under kSmallFaceCornerDeg (where no triangulation can guarantee the bound).
  double away_from_small_corners_deg = 180.0;
};
/// Corners of a face under this many degrees are small input angles (notes §3.8).
constexpr double kSmallFaceCornerDeg = 60.0;
UnforcedAngle smallest_unforced_angle(const SurfaceMeshes& meshes, std::size_t face, const std::vector<Vec3>& points);

/// The PLC vertices at which face `face` has a corner under kSmallFaceCornerDeg, with the
/// corner (degrees): vertices on its boundary (an end of a triangle side used once,
/// triangles collapsed at a pole not counted) where the 3D angles of its triangles sum to
/// less than that.
std::map<std::uint32_t, double> small_face_corners(const SurfaceMeshes& meshes, std::size_t face,
                                                   const std::vector<Vec3>& points);

}  // namespace delmesh::step
