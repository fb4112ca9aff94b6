// Domain marking (notes §4.2.1: once every segment and facet is recovered, the exterior
// tets are removed before any skinny tet is split). Flood fill over the
// tetrahedralization, never crossing a subfacet: from the infinite tets (the exterior,
// unless the convex hull is kept), from each volume hole point (hole), then from each
// region point (its region id). Enclosed space reached by none of them is region 0.
// During refinement the marks are kept exact locally: a new tet takes its region from
// the old tets it touches across faces that are not subfacets, once the mesh conforms
// again (a new tet's cavity may have crossed a subfacet that boundary splits have since
// restored, so the region of the cavity tet it replaced can be the wrong side's).
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

/// Sets state.tet_region for every live tet. Requires every subfacet to be a face of the
/// tetrahedralization.
void mark_domain(RefineState& state);

/// Re-marks the live tets among `created` (tets made since the mesh last conformed, with
/// repeats and dead slots allowed) by flood fill from their old neighbours, never across
/// a subfacet. Requires a marked domain and every subfacet present. A group of new tets
/// that touches no old tet except across subfacets keeps its marks.
void remark_new_tets(RefineState& state, const std::vector<std::uint32_t>& created);

}  // namespace delmesh::tet3d
