// Point location in a TetMesh by a randomized visibility walk (the "remembering
// stochastic walk" of Devillers, Pion and Teillaud, "Walking in a triangulation", 2002;
// notes §2.1.5 on locating the tet that receives a new vertex).
//
// From a starting tet, the walk crosses any face that separates the tet from the query
// point (exact orient3d), trying the faces in a pseudo-random order so that it cannot
// cycle, until no face separates them. The result also classifies where the point lies
// in the closed tet found: strictly inside, on a face, on an edge, on a vertex, or
// outside the convex hull (an infinite tet whose hull face sees the point). Should the
// walk exceed a step budget (which exact predicates make impossible in a valid mesh), it
// falls back to visiting every tet, so location never loops forever.
#pragma once

#include <cstdint>

#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {

enum class LocationKind : std::uint8_t {
  InTet,        ///< strictly inside finite tet `tet`
  OnFace,       ///< in the relative interior of face `i` of `tet`
  OnEdge,       ///< in the relative interior of edge (v[i], v[j]) of `tet`
  OnVertex,     ///< at the position of vertex v[i] of `tet`
  OutsideHull,  ///< strictly outside the hull; `tet` is an infinite tet whose hull face sees it
};

struct Location {
  LocationKind kind = LocationKind::InTet;
  std::uint32_t tet = kNone;
  std::uint8_t i = 0;
  std::uint8_t j = 0;
};

/// Locates p starting from tet `hint` (any live tet; kNone means mesh.last_tet()).
/// `rng` is the walk's pseudo-random state (any nonzero value; it is advanced).
/// Requires a mesh with at least one finite tet.
Location locate(const TetMesh& mesh, const double* p, std::uint32_t hint, std::uint64_t& rng);

}  // namespace delmesh
