// Vertex deletion by edge contraction for mesh improvement (notes §2.2.4; Klingner and
// Shewchuk, "Aggressive tetrahedral mesh improvement", 2007, vertex deletion and edge
// contraction).
//
// A vertex v whose star lies inside the mesh is removed by contracting it onto a
// neighbour u: the tets around edge (u, v) disappear and every other tet of v's star
// takes u in v's place. The star's union P is a polyhedron whose boundary is the link of
// v, u is a vertex of that boundary, and the new tets are the cone from u over the link
// faces that do not contain u. If every new tet is positively oriented (exact orient3d),
// the cone covers P exactly once (its signed volumes sum to P's volume and the covering
// degree of each point is its winding number, 1 inside P), so the contraction keeps a
// valid tetrahedralization with the same boundary: the faces of the link, and hence any
// subfacet among them, stay as they are. Deciding whether a contraction is worth making
// is the caller's (sliver_improvement.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh::tet3d {

/// A planned contraction of vertex v onto vertex u.
struct Contraction {
  std::uint32_t v = kNone, u = kNone;
  std::vector<std::uint32_t> star;                 ///< v's tets: all of them go
  std::vector<std::array<std::uint32_t, 4>> tets;  ///< the new tets, in the star's order
  std::vector<std::uint32_t> outside;              ///< faces (4 t + j) across the link
};

/// Plans contracting v onto u, given v's star (TetMesh::star). False when a star tet is
/// infinite, no star tet has u, no star tet lacks u, or a new tet would not be positively
/// oriented (exact orient3d).
bool plan_contraction(const TetMesh& mesh, std::span<const std::uint32_t> star, std::uint32_t v,
                      std::uint32_t u, Contraction& plan);

/// Carries a plan out: kills the star's tets, creates the new ones (their ids into
/// `created`, in plan order) and glues them to each other and to the faces across the
/// link. v is left without tets (vertex_tet kNone); the vertices of the new tets point
/// to one of them. The plan must be fresh: made on the mesh as it is.
void commit_contraction(TetMesh& mesh, const Contraction& plan, std::vector<std::uint32_t>& created);

}  // namespace delmesh::tet3d
