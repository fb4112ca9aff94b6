// Boundary recovery and conformity by encroachment (notes §4.2.1): segments recovered by
// stitching (every missing or encroached subsegment split at its midpoint or on a
// concentric shell), then facets (every missing or encroached subfacet split at its
// circumcenter, in Projection Lemma order, unless the circumcenter encroaches
// subsegments, which are split instead). A missing subfacet whose place is covered by
// tetrahedralization faces that share its circumcircle is not split: the facet
// triangulation is flipped to match (Figure 4.8).
//
// The same loop restores conformity during quality refinement: after any insertion the
// queues hold the subsegments and subfacets its cavity touched. A MISSING element is
// always split (the mesh must conform); one that is present but encroached is split only
// when the new vertex respects the termination floor (quality_refinement.h), otherwise
// it stays: it is still a face or edge of the tetrahedralization.
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

/// Splits until no queued subsegment or subfacet is missing or encroached; subsegments
/// first. With `segments_only`, subfacets stay queued. Error when the vertex cap is hit.
Expected<void> restore_conformity(RefineState& state, bool segments_only);

}  // namespace delmesh::tet3d
