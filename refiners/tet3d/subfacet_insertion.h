// Vertex insertion on a subfacet for the polish of the improvement pass (notes §2.2.4
// and the end of §4.4; §4.2.1 for the subfacet split; Klingner and Shewchuk, "Aggressive
// tetrahedral mesh improvement", 2007, which insert vertices on boundary faces too).
//
// The improvement pass inserts vertices only inside the domain (sliver_improvement.h,
// step 3), so a tet left outside the dihedral window with a face on a facet keeps that
// face: its angles at the face's edges are the facet's and the apex's. Here, for each tet
// left outside the window that touches no small input angle (small_angles.h) and has a
// subfacet as a face, a vertex is tried starting at the subfacet's circumcenter, then at
// its centroid (refinement's split points: quality_refinement.cpp), then at the other 9
// interior points of its barycentric grid of step 1/6 (on trimesh-tray-bottom these
// starts were the only ones with a consistent cavity for one of its 4 tets), moved within the
// facet's plane by a compass search (8 directions, the step from a quarter of the
// subfacet's shortest edge halved up to 6 times, at most 64 evaluations) that raises the
// judged worst new tet below, and inserted through refinement's insertion path
// (boundary_split.h: prepare_insertion, insert_facet_point) at the best point met that
// passes every check of the would-be result, made with nothing changed:
//   - the point lies strictly inside a subfacet in the facet's projection (exact
//     orient2d_projected), so the facet triangulation splits that subfacet and then flips
//     the edges its in-plane incircle test flips (Lawson); those flips are replayed here
//     with the same exact predicate (incircle_in_plane), which gives the subfacets the
//     insertion removes and adds;
//   - the Bowyer–Watson cavity of the point (the mesh is no longer Delaunay after the
//     pass, so the cavity is checked rather than trusted) holds the bad tet, deletes
//     exactly those subfacets and no other, keeps every subsegment as an edge of its
//     boundary and no edge inside the removed subfacets' region (one kept there, on
//     gmsh-netgen-hinge, left new faces between regions that no subfacet listed), and
//     every finite new tet is positively oriented (exact orient3d): the
//     new subfacets are faces of the new tets, and the regions, markers and segments
//     stay;
//   - the point encroaches no subsegment and no subfacet of another facet among the
//     cavity's (the conforming boundary refinement left stays so), and its insertion
//     radius is at least the least termination floor of the subfacet's vertices
//     (termination_floor.h);
//   - judged as the polish judges its insertions (sliver_improvement.h, step 5): where
//     the worst in-domain cavity tet touches a small angle, the worst new tet touching
//     none beats the worst cavity tet touching none by the polish's least gain and the
//     new tets touching one are no worse than the worst of them in the cavity;
//     elsewhere the worst new tet beats the worst cavity tet by that gain; and neither
//     kind has more tets outside the window than before, and no more tets break the
//     radius-edge bound than before.
// Each tet is tried once (its faces, two starting points each, each search bounded), so
// the work is bounded by the bad tets at the start. improvement_rounds.h runs it after
// its rounds and, where it inserted, one more round of the polish, which smooths the new
// vertices' neighbours.
#pragma once

#include <cstddef>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Least gain in the worst window dihedral sine for an insertion on a subfacet (the
/// polish's kMinFlipGain).
inline constexpr double kMinSubfacetInsertionGain = 1e-4;

/// Inserts vertices on the subfacets of the in-domain tets outside the options' dihedral
/// window that touch no small input angle, where that raises the worst tet around them
/// (see above). Returns the number of vertices inserted.
std::size_t insert_on_subfacets(RefineState& state);

}  // namespace delmesh::tet3d
