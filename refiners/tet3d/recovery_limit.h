// The Steiner-point bound of boundary recovery and the diagnosis when it is reached
// (notes §4.2.1-4.2.3).
//
// Conforming Delaunay recovery splits every missing subsegment and subfacet without a
// floor (the mesh must conform), so it needs about the integral of 1/lfs along the
// segments (and of 1/lfs² over the facets) in Steiner points, lfs being the local
// feature size of §4.2.2. Where two nonincident features run close to each other over a
// long stretch (two segments d apart over a length L: about L/d points per segment; a
// segment or vertex near a facet likewise) that number is out of reach: millions of
// points for the 5e-4 gap of a 2000-unit model, and the cost per insertion grows with the
// facet triangulations along the gap. Recovery therefore counts its Steiner points and
// stops at a bound derived from the size of the input,
//     kRecoveryBase + kRecoveryPerInput * (input vertices + input subfacets),
// with a measured margin over every corpus input recovery completes (docs/MESHING.md). The
// bound is a count, not a time, so the outcome does not depend on the machine; it ends
// the run with an error that names the two features the Steiner points crowd between,
// how far apart they are, over what length, and the count conforming recovery would
// need there (length / distance). A constrained (CDT) recovery, which needs no points
// between such features, is the way to mesh these inputs; delmesh does not implement it.
#pragma once

#include <cstddef>

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

inline constexpr std::size_t kRecoveryBase = 20'000;
inline constexpr std::size_t kRecoveryPerInput = 16;

/// The vertex count at which boundary recovery of `state` stops (input vertices plus
/// the bound above), for RefineState::recovery_vertex_limit.
std::size_t recovery_vertex_limit(const RefineState& state);

/// The error for a recovery stopped at the limit: the input entity (segment or facet)
/// holding the most Steiner points, the nonincident entity its Steiner points are
/// closest to, their distance, the length over which they run close and the Steiner
/// count length / distance that conforming recovery would need. PLC ids in the text and
/// in Error::entity_ids (segment endpoints as point ids, facets as facet ids).
Error recovery_limit_error(const RefineState& state);

/// The error for a split point of subsegment (a, b) that coincides with an existing
/// vertex (where the last prepare_insertion located it): Steiner points have crowded
/// down to the resolution of double precision, which conforming recovery reaches where
/// features meet at small angles or nearly touch (§4.2.3). Names the segment, the feature
/// of the vertex met and the nearest input vertex with its distance.
Error split_point_error(const RefineState& state, std::uint32_t a, std::uint32_t b);

}  // namespace delmesh::tet3d
