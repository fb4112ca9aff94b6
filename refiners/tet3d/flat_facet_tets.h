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
//
// On a CCDT (refinement with constrained cavities, `--segment-recovery strongly-delaunay`,
// `--facet-recovery ccdt`) the same flat tet also lies across a subsegment: its two
// subfacets belong to two facets that are coplanar or nearly so and meet at the segment
// (x, y), its other two faces face the domain, and a Steiner point on a segment near x (or
// y) made it, the subsegment (x, y) left encroached since a present subsegment is not split
// on the CCDT. Refinement leaves it (without a representable circumcenter a tet is not
// skinny; why it left the ones with a circumcenter was not traced), the release above cannot flip a segment, and the default improvement's edge
// removal of (c, d) would make a tet above the radius-edge bound, which its strict bounds
// forbid, though the flat tet, already above it, would leave. (cgal-fandisk at radius-edge
// 1.414: the 0.000 and 0.004 degree tets; cgal-bear: the 3.1 degree one; pocc-io1-ug-214:
// the 0.1 and 0.9 degree ones.) After that pass, remove_flat_boundary_tets removes the edge (c,
// d) joining the two vertices opposite the subfacets (toolkit remove_edge, exact
// orientation checks), every tet around it of the tet's region and no face around it a
// subfacet, choosing among the triangulations of its ring (at most kFlatRingMax vertices)
// the one whose smallest dihedral angle is largest among those with no more tets above the
// bounds (MeshStats::unmet_tets' rule) than the ring had, and only if that angle exceeds
// the ring's smallest. The subfacets (c, x, y) and (d, x, y) stay faces (every
// triangulation of the ring has its side (x, y)), the faces around (c, d) are interior, so
// the boundary, the regions and the volume stay; the count of tets above the bounds does
// not grow.
#pragma once

#include <cstddef>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Releases the in-domain tets outside the dihedral window [low, high] (degrees) that lie
/// flat on one facet (above); returns how many.
std::size_t release_flat_facet_tets(RefineState& state, double low, double high);

/// Most vertices of an edge ring remove_flat_boundary_tets triangulates (Catalan(4) = 14
/// triangulations at six).
inline constexpr std::size_t kFlatRingMax = 6;

/// Removes, by edge removal, the in-domain tets outside the dihedral window [low, high]
/// (degrees) with exactly two subfacet faces (above); returns how many.
std::size_t remove_flat_boundary_tets(RefineState& state, double low, double high);

}  // namespace delmesh::tet3d
