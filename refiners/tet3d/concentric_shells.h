// Concentric shells around the input vertices where segments meet (notes §3.8, Figure
// 3.33, carried to 3D): an encroached subsegment with such a vertex for an endpoint is
// split on a sphere around it, so that the piece at the vertex has a shell radius.
// Incident pieces of equal length do not encroach each other, which ends the cycle of
// Figure 3.32.
//
// The argument needs one geometric family of radii per apex, not the powers of two of
// one global unit: delmesh uses unit * 2^k with the unit of each apex the length of the
// shortest segment incident there. The shortest segment then lies on a shell itself,
// and a cluster of segments meeting at the apex below 60 degrees, whose pieces at the
// apex end up all of one length, settles on that length without splitting it. With the
// global powers of two the shortest segment lies between two shells: its neighbours'
// pieces at the larger radius are encroached by its far end and those at the smaller
// radius encroach it, so it is split as well, and the pieces around the apex are up to
// half as long as they need to be.
#pragma once

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Sets SegmentData::shell_a / shell_b (the endpoint is an input vertex shared with
/// another segment) and SegmentData::shell_unit_a / shell_unit_b (the length of the
/// shortest segment at that endpoint). Call once the segment list is complete.
void mark_shells(RefineState& state);

/// Distance from the apex at which a subsegment of length `length` is split on shells
/// of unit `unit`: the radius unit * 2^k nearest to length / 2 in log scale (the smaller
/// piece is at least a third of the subsegment), or 0 when there is none strictly
/// between 0 and `length` (the caller splits at the midpoint).
double shell_split_distance(double unit, double length);

}  // namespace delmesh::tet3d
