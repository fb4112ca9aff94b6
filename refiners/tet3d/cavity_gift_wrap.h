// Constrained gift-wrapping of a polyhedral cavity (notes §2.1.3: gift-wrapping builds a
// CDT one tet at a time, each step considering only the vertices visible from the face it
// wraps; §2.1.7: retriangulating the cavities left on each side of a facet being
// recovered). Used by ccdt_facet_recovery.h where the Delaunay tetrahedralization of a
// cavity's vertices lacks one of its faces (a vertex hidden behind the cavity's walls
// spoils it).
//
// An advancing front: every face of the cavity is open, wanting a tet on its positive
// side. For an open face abc the apex is, among the cavity's vertices strictly on its
// positive side (exact orient3d) that are visible from it, the one whose sphere through
// a, b, c is smallest on that side (insphere_sos: perturbed by vertex id as the whole mesh
// is, so cospherical vertices give one deterministic choice). Visible here: no edge of the
// new tet crosses an open face and no edge of an open face crosses a face of the new tet
// (exact segment-triangle tests; the unfilled part of the cavity is bounded by the open
// faces). Each new tet closes the open faces it shares and opens its other faces from the
// far side. Every tet is positively oriented and each face ends with one tet on each side,
// so a completed fill covers the cavity exactly once (the caller still checks the gluing).
// The apex is first chosen among all vertices and kept when visible (the usual case);
// only otherwise is the choice repeated testing visibility. Bounded: at most `max_tets`
// tets, each step scans the vertices at most twice, the front once per visibility test.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh::tet3d {

/// Fills the cavity bounded by `faces` (global vertex ids of `mesh`, each with the cavity
/// on its positive side, distinct as vertex sets) with tets over the faces' vertices,
/// appended to `out` as positively oriented vertex quadruples. False (out unchanged) when
/// no visible apex exists for some open face, a face would be covered twice, or the fill
/// needs more than `max_tets` tets.
bool gift_wrap_cavity(const TetMesh& mesh, std::span<const std::array<std::uint32_t, 3>> faces,
                      std::size_t max_tets, std::vector<std::array<std::uint32_t, 4>>& out);

}  // namespace delmesh::tet3d
