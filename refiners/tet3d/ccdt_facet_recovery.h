// Facet recovery without Steiner points: a conforming constrained Delaunay
// tetrahedralization (CCDT) once the segments are strongly Delaunay (notes §2.1.4: a
// ridge-protected PLC has a CDT; §2.1.7: recover the facets one by one, deleting the tets
// whose interiors they cross and retriangulating the cavities left on each side; ch. 4
// §4.2.1: form a conforming CDT as soon as every segment has been recovered).
//
// After the segments stage every subsegment has a closed diametral ball free of other
// vertices, so the subfacets (each facet's own 2D Delaunay triangulation) can be made
// faces of the tetrahedralization without new vertices. Each connected region R of
// missing subfacets of one facet is recovered by cavity retriangulation:
//   1. the cavity is the set of tets having an edge that crosses the relative interior of
//      R (exact orient3d tests), or that lies in R's plane and meets a subfacet's open
//      interior (exact orient2d in a projection), found by a search from the stars of
//      R's vertices; infinite tets count by their hull face, so R may lie on the hull;
//   2. its boundary faces fall into two sides, split by the edges of R (the side of a
//      component is the orient3d sign of its apex over the subfacet next to it). An
//      interior edge of R that is already a mesh edge may lie on the boundary (the
//      cavity is pinched there), and so may an edge away from R with four or more
//      boundary faces: there each face is paired with the one reached by turning about
//      the edge through cavity tets. When the cavity holds infinite tets (R in a hull
//      face's plane), the side beyond the hull is every face through the infinite
//      vertex and every face in R's plane facing outwards, the other side the rest;
//   3. each side's cavity, bounded by its boundary faces and R, is filled with the tets
//      of the Delaunay tetrahedralization of its vertices (toolkit/tetmesh, perturbed by
//      vertex id through insphere_sos: deterministic) that lie inside the faces; when a
//      boundary face is missing from that tetrahedralization the cavity grows by the tet
//      beyond it and the step repeats, as TetGen does (a bounded number of times). Where
//      that fails otherwise (a subfacet missing from it) the side is filled by
//      constrained gift-wrapping (cavity_gift_wrap.h), whose tets must then be
//      constrained Delaunay across every face that is no subfacet (else the region
//      fails). The side beyond the hull is the cone from the infinite vertex over its
//      faces;
//   4. the new tets replace the cavity only when every boundary face gets exactly one
//      new tet and every other new face exactly two: all tets are positively oriented
//      (Delaunay tetrahedralization, gift-wrapping with orient3d Positive apexes, or
//      infinite tets over outward faces) and each face is glued between tets on its
//      two sides, so the mesh stays a valid triangulation of the same hull.
// Before that, a missing subfacet whose place the tetrahedralization covers with the
// other diagonal of a cocircular pair is matched by flipping the facet triangulation
// (Figure 4.8, as the conforming recovery does), so coplanar regions need no cavity.
// A region that fails (no crossing edge, a cavity that does not split in two, a face that
// stays missing, too much work) is left for the conforming recovery of
// boundary_recovery.h: the tetrahedralization is rebuilt as the Delaunay one of the same
// vertices, the failed facets are recovered by splitting, and the CCDT pass repeats for
// the others (a few rounds; the last round recovers everything left the conforming way).
// The result is no longer Delaunay, only constrained Delaunay: quality refinement that
// follows it inserts with constrained Bowyer–Watson cavities (RefineState::constrained,
// mesh_plc.h).
#pragma once

#include <array>
#include <cstddef>

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

/// Why a region was left to the conforming fallback.
enum class CcdtFailure : std::uint8_t {
  NoCrossingEdge,  ///< no tet edge crosses it (or the search passed its work bound)
  SplitSurface,    ///< the cavity's boundary does not split into two sides along it
  FaceMissing,     ///< a face stays missing from a side's Delaunay tetrahedralization
  Gluing,          ///< the new tets do not close up with the rest of the mesh
  NotDelaunay,     ///< a gift-wrapped side is not constrained Delaunay across some face
};

struct CcdtCounts {
  std::size_t regions = 0;            ///< regions of missing subfacets met (over all rounds)
  std::size_t recovered_regions = 0;  ///< of those, recovered by cavity retriangulation
  std::size_t failed_regions = 0;     ///< left to the conforming fallback
  std::size_t fallback_facets = 0;    ///< facets recovered the conforming way
  std::size_t enlargements = 0;       ///< cavity enlargements by one tet
  std::size_t cocircular_flips = 0;   ///< facet triangulation flips to match (Figure 4.8)
  std::size_t rounds = 0;             ///< CCDT passes
  std::size_t gift_wrapped_sides = 0; ///< cavity sides filled by gift-wrapping (cavity_gift_wrap.h)
  std::array<std::size_t, 5> failures = {};  ///< failed regions by CcdtFailure
};

/// Recovers every subfacet of state.subfaces as a face of state.mesh (see above). The
/// segments must be recovered and the queues empty. Errors only from the conforming
/// fallback (recovery_limit.h, vertex cap).
Expected<CcdtCounts> recover_facets_ccdt(RefineState& state);

}  // namespace delmesh::tet3d
