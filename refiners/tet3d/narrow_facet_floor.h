// Floors that follow a facet narrower than them between two of its own segments that
// share no vertex (notes §3.8, §4.2.2-4.2.3; the termination floors of
// quality_refinement.h and termination_floor.h).
//
// The local feature size of an input vertex (feature_size.h) counts a segment of the
// vertex's own facet that does not contain it only down to a quarter of the nearest
// vertex distance, and the floor field then grows from the input vertices by kFloorSlope
// per unit of distance. Along a long strip facet (occt-propeller.stl: planar strips 31
// long and 0.1-0.2 wide; occt-tr12j.stl: a 4-gon 21.3 long and 0.001-0.016 wide) whose
// two long segments share no vertex, the floors of the vertices put on those segments
// grow to several times the strip's width in its middle: the tets across the strip, of
// circumradius about half the width, lie under the floor, their splits (and the splits of
// the strip's subsegments their circumcenters encroach) are refused, and they stay above
// the radius-edge bound with no small input angle near them.
//
// The rule: the partners of a segment s are the segments of a facet of s that share no
// vertex with s and come closer to s than s's length (farther, the floors from s's own
// endpoints, kFloorFactor times their local feature size plus kFloorSlope per unit, stay
// below kFloorFactor times the gap). A vertex inserted on s at p takes as its field floor
// at most kFloorFactor times the distance from p to the nearest partner (commit_insertion,
// boundary_split.h), so the floors along the strip follow its width, which is its local
// feature size.
//
// Termination (quality_refinement.h's packing argument) still holds: a partner shares no
// vertex with s, so in a valid PLC it does not meet s and the distance between them is
// positive; every such cap is at least kFloorFactor times the smallest distance d_min
// between partner segments, and every floor stays at least min(f_min, kFloorFactor d_min)
// > 0, where f_min is the smallest input floor. The cap only lowers floors (more vertices,
// still finitely many); partners are found once, by a sweep over each facet's segments,
// and each cap is a loop over a segment's partners. A small input angle between two
// segments that share a vertex is not followed (those are adjacent, not partners): the
// gap between two arms of one corner goes to zero at the apex, the floors there exist to
// stop refinement (termination_floor.h).
#pragma once

#include <cstdint>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Fills RefineState::narrow_partners for every segment (facet boundary segments; free
/// segments have none). Needs the segments with their facets (plc_preparation.h).
void find_narrow_partners(RefineState& state);

/// kFloorFactor times the distance from p (a point on segment `seg`) to the nearest
/// partner of `seg`; infinity when it has none.
double narrow_facet_floor(const RefineState& state, std::uint32_t seg, const Vec3& p);

/// Distance between segments [a, b] and [c, d] (closest points, Ericson, Real-Time
/// Collision Detection §5.1.9), in floating point: it sets a size, no sign.
double segment_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace delmesh::tet3d
