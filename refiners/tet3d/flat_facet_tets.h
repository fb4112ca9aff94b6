// Flat tets lying on a facet, before and after the improvement pass (sliver_improvement.h,
// with a dihedral window or the default improvement's, default_improvement.h). Where
// concentric shells put two pairs of vertices on two segments of one facet close to the
// small angle between them, the tetrahedralization can hold a tet whose four vertices
// are the four corners of a quadrilateral of that facet: two of its faces are the
// facet's two subfacets across the quadrilateral's diagonal (x, y), the other two are the
// other diagonal's triangles, facing the domain. Coplanar but for the rounding of the
// split points, the tet has dihedral angles of 0 and 180 degrees, and the improvement
// pass leaves it: its flips never remove a subfacet, and the tet stays flat wherever its
// vertices move on their segments. (On cgal-knot2.off at the default bound with the
// window [20, 150], 2 of the 13 tets the pass left outside the window away from small
// angles were such tets; none on td-slit-1, td-wedge-*, as-wavy-cube, pocc-io1 or
// gmsh-angled.) Released before the pass too: in place, such a tet is the worst tet of
// every star and edge ring it is in, so no smoothing of its four vertices and no flip
// around it beats it (936 such tets on as-capot-40mm, 1418 on gmsh-laufrad-impeller before
// the pass with [20, 150]; without a window they are the 0 and 180 degree tets the default
// improvement left on pocc-io1-ug-214 and gmsh-part at radius-edge 1.414).
//
// The repair flips the facet's edge (x, y) to the other diagonal (c, d) (FacetTriangulation::
// flip_edge: the quadrilateral strictly convex in the facet's projection, exact test) and
// hands the tet to the region on the facet's other side: the new subfacets are then the
// tet's faces towards the domain, and the tet, of all but zero volume, leaves it. Made only
// when the two subfacets are the tet's only subfacet faces, (x, y) is not a segment, the
// tets across them share one region other than the tet's, and the tets across the other
// two faces are of the tet's region; so the boundary stays a closed surface on the same
// facet (same marker), the regions stay consistent and no tet changes shape.
#pragma once

#include <cstddef>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Releases the in-domain tets outside the dihedral window [low, high] (degrees) that lie
/// flat on one facet (above); returns how many.
std::size_t release_flat_facet_tets(RefineState& state, double low, double high);

}  // namespace delmesh::tet3d
