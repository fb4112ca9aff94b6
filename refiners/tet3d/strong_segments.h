// The strongly Delaunay test for a subsegment (notes §2.1.4): an edge is strongly
// Delaunay when some sphere through its two vertices has every other vertex strictly
// outside, i.e. when its Voronoi face is a nondegenerate polygon. Tested locally on a
// Delaunay tetrahedralization: an edge missing from it is not strongly Delaunay; an edge
// of it is exactly when the polygon formed by the circumcenters of the tets around it
// has at least three distinct corners. Two consecutive tets around the edge, sharing the
// face (a, b, s), have the same circumcenter exactly when their five vertices are
// cospherical (exact insphere Zero; for two infinite tets, the hull faces coplanar:
// exact orient3d Zero; a finite and an infinite tet never share one). Counting the
// changes of circumcenter around the edge: none means the Voronoi face is one point, two
// mean it is a segment (or a ray for a hull edge whose two hull faces are coplanar),
// three or more a polygon with area (three faces around an edge cannot lie in one
// plane, so their Voronoi edges are not all parallel). The kernel's symbolic perturbation
// (insphere_sos) picks one tetrahedralization among cospherical ties; the test reads the
// real coordinates, so a tie never makes an edge count as strongly Delaunay.
#pragma once

#include <cstdint>
#include <vector>

#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh::tet3d {

/// Is (a, b) an edge of `mesh` (a Delaunay tetrahedralization) that is strongly Delaunay?
/// `tets` and `ring` are scratch.
bool strongly_delaunay_edge(TetMesh& mesh, std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& tets,
                            std::vector<std::uint32_t>& ring);

}  // namespace delmesh::tet3d
