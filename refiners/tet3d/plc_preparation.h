// PLC preparation for 3D Delaunay refinement (notes §4.1, §4.2.1): input checks, the
// Delaunay tetrahedralization of the PLC vertices, the segment list (facet polygon edges
// and free segments, deduplicated) with the facets around each, one constrained
// Delaunay triangulation per facet in OpenMesh (built by the 2D CDT of the projected
// facet, then flipped to the facet's in-plane Delaunay triangulation), and the
// classification of small input angles (§4.2.3, small_angles.h) and of each input
// vertex's local feature size, which seeds the termination floors of
// quality_refinement.h.
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

/// An input vertex's termination floors, as a fraction of its local feature size: the
/// quality stage's (field_floor) from the nearest input vertex, segment or facet not
/// containing it (feature_size.h), boundary recovery's (floor) from the nearest input
/// vertex; Steiner vertices get theirs from termination_floor.h.
inline constexpr double kFloorFactor = 0.125;

/// Segments meeting at an input vertex below this angle form a cluster (two arms of a
/// needle, a strip of nearly parallel segments along two long thin triangles side by
/// side); those whose lines pass within this angle of the apex of the cluster's narrowest
/// corner, seen over their own length, split on a common grid of distances from that apex
/// (SegmentData::grid_origin, boundary_split.h), so that vertices of one do not encroach
/// another's subsegments (notes §3.8, §4.2.3). 0.01 degrees: at 0.5 (fewest segment-stage
/// points among 0.1, 0.5, 1, 3 and 10) gmsh-netgen-hinge.stl, whose narrowest corner is
/// 0.489 degrees, was left at radius-edge 1.414 with 162 flat tets (radius-edge above
/// 1e15) on its z = 0 facet beside the corner, against none with its corner off the grid;
/// at 0.1 occt-tr12j.stl (narrowest corner 0.086 degrees) kept 451 tets above 1.414 away
/// from small angles, against 148 off the grid (docs/MESHING.md, "Boundary recovery that cannot
/// finish").
inline constexpr double kGridCornerDeg = 0.01;

/// Fills `state` from state.plc: tetrahedralization, segments, subsegments (all queued),
/// facet triangulations, subfacets, angles, floors. Errors name the offending entity.
Expected<void> prepare_plc(RefineState& state);

}  // namespace delmesh::tet3d
