// Small input angles (notes §4.2.3) and the tets that touch them. Theorem 28 of the notes
// guarantees termination of 3D Delaunay refinement only when the PLC has
//   * no two segments meeting at a vertex at an angle below 60 degrees,
//   * no segment meeting a facet at a vertex at an angle below arccos(1 / (2 sqrt 2)),
//     about 69.3 degrees, when the segment's orthogonal projection onto the facet's
//     plane enters the facet at that vertex (else the Projection Lemma makes the angle
//     harmless),
//   * no two facets meeting at a segment at a dihedral angle below 90 degrees (the
//     projection condition for convex facets; measured here as the angle between the
//     two facets' half-planes at the segment, so a thin wedge counts whichever side the
//     domain is on).
// Where such an angle occurs the termination floors of quality_refinement.h stop
// refinement, and the tets there may miss the radius-edge bound or the dihedral window.
//
// The rule used to report them (MeshResult::tet_at_small_angle, MeshStats, the CLI
// summary): a tet touches a small input angle when one of its four vertices is
//   (a) an input vertex where one of the angles above occurs (an apex), or
//   (b) a vertex on a segment whose facets meet below 90 degrees (a sharp segment; its
//       endpoints are apices by (a)).
// Segments are the facets' polygon edges and the free segments: on a triangulated
// surface every triangle edge, so an input vertex with a triangle angle below 60 degrees
// is an apex.
// Right angles computed in floating point land a hair on either side of 90 degrees, so
// the facet test uses 89 degrees: a box's edges do not count. Angles are measured in
// floating point: this is reporting, no geometric decision of the mesher depends on it.
#pragma once

#include <cstdint>
#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

inline constexpr double kSmallSegmentAngleDeg = 60.0;
/// arccos(1 / (2 sqrt 2)) in degrees.
inline constexpr double kSmallSegmentFacetAngleDeg = 69.295188945364572;
inline constexpr double kSmallFacetAngleDeg = 89.0;

/// Sets VertexInfo::small_angle on the input vertices and SegmentData::small_angle on
/// the segments (rules (a) and (b) above). Call once the
/// segments and the facet triangulations of the input are built (plc_preparation.h).
void classify_small_angles(RefineState& state);

/// Does vertex v touch a small input angle (rules (a) and (b))?
bool vertex_at_small_angle(const RefineState& state, std::uint32_t v);

/// Per tet slot of state.mesh: 1 when the tet has a vertex that touches a small input
/// angle, else 0 (dead and infinite slots: 0).
std::vector<std::uint8_t> small_angle_tets(const RefineState& state);

}  // namespace delmesh::tet3d
