// Removal of an edge that lies inside a facet, for mesh improvement (notes §2.2.4 on
// topological transformations; the boundary case of edge removal, Shewchuk, "Two
// discrete optimization algorithms for the topological improvement of tetrahedral
// meshes", 2002; Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement", 2007,
// which flip boundary faces where they are coplanar).
//
// An edge (x, y) of a facet's triangulation that is not a segment has two subfacets,
// (x, y, c) and (x, y, d), and the tets around it form two fans, one on each side of the
// facet: from c to d on one side and from d back to c on the other. The 2-2 flip of the
// facet replaces the two subfacets by (c, d, x) and (c, d, y) (FacetTriangulation::
// flip_edge: the quadrilateral x, c, y, d strictly convex in the facet's projection,
// exact test); in 3D the tets around (x, y) are replaced by an edge removal whose ring
// triangulation holds the diagonal (c, d): each side's open ring (c, w1, ..., d) is
// triangulated apart, each triangle joined to x and to y, so the new subfacets are faces
// of the new tets on both sides. The triangulation of an in-domain side maximizes the
// worst quality of its new tets by dynamic programming (Klincsek), that of a side outside
// the domain is any valid one; every new tet must be positively oriented (exact
// orient3d), which holds exactly when the new tets of each side fill that side's fan.
// Each new tet takes its side's region, so the regions, the facet (and with it the
// marker) and every segment stay as they are; the subfacets change within their facet.
//
// The flip must not lower the smallest angle of the two subfacets: refinement leaves each
// facet's triangulation constrained Delaunay, which maximizes that angle, so the flip is
// made only where smoothing has moved facet vertices or the four are nearly cocircular
// (without the rule, flips that each raised the worst tet around their edge left thin
// subfacets that bounded the tets on them later: on gmsh-as1-tu-203 with [20, 150], 12
// tets outside the window elsewhere without flips, 36 with them, 15 with the rule).
//
// Refused: (x, y) a subsegment, not exactly two subfacets around it or two of different
// facets, a side of one tet (the flat tet between the two subfacets: flat_facet_tets.h),
// a side whose tets are of different regions, a ring through the infinite vertex (the
// convex hull is left as it is) or longer than kMaxFacetEdgeRing.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Longest ring (tets around the edge, both sides) a facet edge flip considers.
inline constexpr std::size_t kMaxFacetEdgeRing = 24;

/// Quality of a new tet of an in-domain region (larger is better); the flip's worst new
/// tet is the least of these.
using RegionTetQuality =
    std::function<double(int region, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)>;

/// A planned flip of facet edge (x, y) to (c, d).
struct FacetEdgeFlip {
  std::uint32_t x = kNone, y = kNone, c = kNone, d = kNone, facet = kNone;
  std::vector<std::uint32_t> old_tets;             ///< the tets around (x, y)
  std::vector<std::array<std::uint32_t, 4>> tets;  ///< the new tets, positively oriented
  std::vector<int> regions;                        ///< region of each new tet
  double worst = 0.0;                              ///< worst quality of the new in-domain tets
};

/// Plans the flip of facet edge (x, y): true when it is possible (above) and the worst
/// quality of its new in-domain tets exceeds that of the in-domain tets around (x, y) by
/// more than `min_gain`.
bool plan_facet_edge_flip(RefineState& state, std::uint32_t x, std::uint32_t y, double min_gain,
                          const RegionTetQuality& quality, FacetEdgeFlip& plan);

/// Carries out a fresh plan: flips the facet's edge, replaces the tets (their ids into
/// `created`, in plan order, regions set), updates state.subfaces. False, with nothing
/// changed, when the facet refuses the flip (quadrilateral not strictly convex in its
/// projection).
bool commit_facet_edge_flip(RefineState& state, const FacetEdgeFlip& plan, std::vector<std::uint32_t>& created);

}  // namespace delmesh::tet3d
