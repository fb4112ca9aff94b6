// What the polish's vertex insertions on the boundary share (subfacet_insertion.h,
// subsegment_insertion.h; notes §2.2.4 on vertex insertion as a mesh improvement
// operation, §4.2.1 on the boundary splits they go through):
//  - the Lawson flips a facet's 2D Delaunay triangulation makes after a new vertex p
//    splits some of its subfacets, replayed with the exact predicates before the mesh
//    changes (replay_facet_flips);
//  - the tets they try (in the domain, touching no small input angle, outside the
//    dihedral window) and the polish's judgement of the prepared cavity of p
//    (BoundaryInserter).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

using FacetFlip = std::pair<std::uint32_t, std::uint32_t>;

/// The Lawson flips of `facet` after p split some of its subfacets: starting from the
/// edges opposite p in `edges` (each (x, y) with (x, y, p) counterclockwise), every edge
/// that is neither a segment nor on the facet's boundary and whose far subfacet's in-plane
/// circle holds p (the facet's own test, incircle_in_plane) is flipped, in the order a
/// stack of those edges meets them, each with its quadrilateral strictly convex as
/// FacetTriangulation::flip_edge asks (exact orient2d_projected). `removed` gets the
/// subfacets beyond the flipped edges (appended), `flips` the flipped edges (x, y), each of
/// triangle (x, y, p) when flipped (cleared first). False when a quadrilateral is not
/// strictly convex. Each flip removes a subfacet, so at most the facet's subfacets are
/// visited.
bool replay_facet_flips(const TetMesh& mesh, const FacetTriangulation& facet, const Vec3& p,
                        std::vector<FacetFlip> edges, std::vector<FaceKey>& removed, std::vector<FacetFlip>& flips);

/// The tets a boundary insertion tries and the judgement of its points. run() calls
/// try_tet for each in-domain tet outside the window and touching no small angle when
/// run() starts, if it still exists then (found again by its vertices: an insertion
/// kills tets whose slots later ones may take), and counts the insertions made; run(k)
/// tries only the k-th of those tets (in the order of their slots).
class BoundaryInserter {
 public:
  explicit BoundaryInserter(RefineState& state);
  virtual ~BoundaryInserter() = default;
  BoundaryInserter(const BoundaryInserter&) = delete;
  BoundaryInserter& operator=(const BoundaryInserter&) = delete;

  /// run()'s argument: every tet.
  static constexpr std::size_t kEveryTet = static_cast<std::size_t>(-1);
  std::size_t run(std::size_t only = kEveryTet);
  /// The vertices of the tets the last run() had to try (in the domain, touching no small
  /// angle, outside the window when it started), in the order of their slots.
  const std::vector<std::array<std::uint32_t, 4>>& bad_tets() const { return bad_tets_; }

 protected:
  /// Tries to insert a vertex for tet t; true when one was inserted.
  virtual bool try_tet(std::uint32_t t) = 0;

  bool domain(std::uint32_t t) const;
  bool has_vertex(std::uint32_t t, std::uint32_t x) const;
  bool small(std::uint32_t x) const;
  /// Whether a vertex of v touches a small angle (a new vertex, given as kInfiniteVertex,
  /// touches none: the insertions place it away from the small-angle zones).
  bool touches_small(const std::array<std::uint32_t, 4>& v) const;
  bool outside(const std::array<std::uint32_t, 4>& v) const;

  /// The polish's judgement of the new tets of the prepared cavity (state.cavity) of p:
  /// false when a finite new tet is not positively oriented (exact orient3d), else
  /// `margin` is the judged worst new tet less the worst old one and `min_gain`, and
  /// `acceptable` tells whether the rules other than the gain hold: no more tets outside
  /// the window, touching a small angle or not, no more tets above the radius-edge bound,
  /// and, when the worst old tet touches a small angle, the tets touching one no worse
  /// (they are then the constraints and the others the objective; else the worst of all
  /// is). Tets are scored by min_window_dihedral_sine.
  bool judge(const Vec3& p, double min_gain, double& margin, bool& acceptable) const;

  RefineState& state_;
  TetMesh& mesh_;
  const double low_, high_, scale_;
  const std::vector<std::uint8_t> small_;

 private:
  std::vector<std::array<std::uint32_t, 4>> bad_tets_;
};

}  // namespace delmesh::tet3d
