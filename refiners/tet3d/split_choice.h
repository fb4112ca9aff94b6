// Choice of the split point of a subsegment in segment recovery (notes §4.2.1, §3.8).
//
// Segment recovery splits every missing or encroached subsegment until no vertex lies
// inside or on any subsegment's diametral sphere. Most of its splits on triangulated
// surfaces are a cascade: a point put on one segment encroaches a segment meeting it at
// an input vertex below 60 degrees, which is split in turn (cgal-fandisk: 12180 of the
// 12541 splits "encroached by a split point" are of that kind, cgal-bear 38913 of
// 43182). Where the point lands decides whether it does: on segment e2 at distance d from
// the common vertex x, it encroaches the neighbour e1 (length l1, angle t) when
// d <= l1 cos t, while its own piece at x is encroached by e1's far end when
// d >= l1 / cos t.
//
// The rule here keeps the split points of Ruppert's scheme (the midpoint, or a shell
// radius of an endpoint that is a shared input vertex, concentric_shells.h) but chooses
// among them: the usual point first, then the other shells of either end whose pieces
// are at least a quarter of the subsegment, then the midpoint. The first candidate that
// encroaches no other subsegment of its cavity and leaves the encroaching vertex outside
// both pieces' diametral spheres (exact predicates) is taken; when none does, the usual
// point. Every point taken is a midpoint or a shell point with pieces of at least a
// quarter of the subsegment, so the termination argument of concentric shells (equal
// pieces at an apex do not encroach each other) and the floors are unchanged.
#pragma once

#include <cstdint>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// The split point of the missing or encroached subsegment (a, b); `by` is the vertex
/// that encroaches it (kNone for a missing one). Leaves the cavity of the returned point
/// prepared when it prepared one (split_subsegment prepares its own anyway).
Vec3 choose_subsegment_split(RefineState& state, std::uint32_t a, std::uint32_t b, std::uint32_t by);

}  // namespace delmesh::tet3d
