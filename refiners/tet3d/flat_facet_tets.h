// Flat tets lying on a facet, after sliver improvement (sliver_improvement.h). Where
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
// gmsh-angled.)
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

/// Releases the in-domain tets outside the dihedral window [options.min_dihedral_deg,
/// options.max_dihedral_deg] that lie flat on one facet (above); returns how many.
std::size_t release_flat_facet_tets(RefineState& state);

}  // namespace delmesh::tet3d
