// Recovery of a missing subfacet on the CCDT by flips of its facet's triangulation toward
// the faces the tetrahedralization has (notes §2.1.7, §4.2.1: "the facet triangulation is
// flipped to match", Figure 4.8, carried from one flip to a region of them).
//
// In refinement on a CCDT (RefineState::constrained) a subsegment or subfacet split's
// constrained cavity need not delete exactly the subfacets the facet triangulation's
// insertion and Lawson flips remove: where they differ, the facet holds triangles that are
// not faces of the tetrahedralization (docs/MESHING.md "Why refinement on the CCDT falls
// back on CAD parts"), while the tetrahedralization, which crosses no subfacet, still
// triangulates the facet's region there with faces between facet vertices. Splitting such
// a missing subfacet at its circumcenter, as conforming recovery does, leaves new ones
// missing in turn (a cascade). Here the facet is made to agree with the tets instead:
//
// - the region: the missing subfacet and the missing subfacets of the same facet joined
//   to it across edges that are not segments (at most kMaxFlipRegion); its boundary edges
//   are segments or edges of present subfacets;
// - the target: a depth-first search from the boundary edges (x, y) over the faces
//   (x, y, w) of the tets around each edge whose apex w is a vertex of the region on the
//   region's side of (x, y) in the facet's projection (exact orient2d_projected; not three
//   vertices of one segment), then from each new edge the same way, until the faces close
//   up over the region with as many triangles as it has, none overlapping another or
//   across a boundary edge: a triangulation of the region by its own vertices, every
//   triangle a face of the tetrahedralization (several faces at one edge are those of flat
//   tets lying on the facet between them, and only some choices close up);
// - the flips: FacetTriangulation::flip_to_subfaces inserts the target's edges by Sloan's
//   flips of the edges crossing them (all or nothing).
//
// Nothing moves in the tetrahedralization and no vertex is added: the facet's vertices,
// segments and polygon are unchanged, its triangulation need no longer be Delaunay. The
// new subfacets are faces between the same tets as before, so the regions stay exact.
#pragma once

#include <cstddef>
#include <cstdint>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Largest region of missing subfacets recovered by flips.
inline constexpr std::size_t kMaxFlipRegion = 64;

/// Makes missing subfacet `key` of `facet`, and the missing subfacets joined to it, faces of
/// the tetrahedralization by flips of the facet triangulation (the change goes through
/// apply_subface_change); false, with nothing changed, when the tets do not triangulate
/// the region by its vertices or the flips cannot reach it.
bool recover_subface_by_flips(RefineState& state, std::uint32_t facet, const FaceKey& key);

}  // namespace delmesh::tet3d
