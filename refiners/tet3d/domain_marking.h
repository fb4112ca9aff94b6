// Domain marking (notes §4.2.1: once every segment and facet is recovered, the exterior
// tets are removed before any skinny tet is split). Flood fill over the
// tetrahedralization, never crossing a subfacet: from the infinite tets (the exterior,
// unless the convex hull is kept), from each volume hole point (hole), then from each
// region point (its region id). Enclosed space reached by none of them is region 0.
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

/// Sets state.tet_region for every live tet. Requires every subfacet to be a face of the
/// tetrahedralization.
void mark_domain(RefineState& state);

}  // namespace delmesh::tet3d
