// Constrained Delaunay triangulation of a PSLG (notes §2.1.2, §3.5.1) on the kernel of
// triangulation.h, and the removal of holes and concavities.
//
// Segment recovery is by flipping (Sloan 1993): the edges crossed by a missing segment
// are collected by a walk, flipped away while their quadrilateral is strictly convex, and
// the new edges are then made locally Delaunay again by Lawson flips that never flip a
// subsegment. Every sign decision is an exact predicate.
//
// Degenerate input:
//   * A vertex lying exactly on a segment (exact orient2d == 0) splits the segment there.
//   * Two segments that cross are both split at their intersection point. The point is
//     computed in floating point (it is generally not representable), inserted as a new
//     vertex, and the four pieces are then recovered as ordinary segments: the pieces are
//     straight between representable vertices, so they may deviate from the input lines
//     by a rounding error, but all subsequent decisions are again exact.
//     An intersection vertex counts as lying on the lines of the two input segments it
//     was defined on (and a vertex exactly on a piece's input segment line splits the
//     piece), so that segments overlapping one of them are split there too instead of
//     forming a second, almost coincident constraint chain.
//   * Overlapping collinear segments share the edges of their common part; exact
//     duplicate segments are inserted once.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/mesh2d/pslg.h"
#include "toolkit/mesh2d/triangulation.h"

namespace delmesh::mesh2d {

/// Which input segment each subsegment lies on, keyed by its two (unordered) vertices.
class SubsegmentOwners {
 public:
  static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(a) << 32) | b;
  }
  void set(std::uint32_t a, std::uint32_t b, std::uint32_t segment) { map_[key(a, b)] = segment; }
  /// The owning input segment, or kNone.
  std::uint32_t get(std::uint32_t a, std::uint32_t b) const {
    const auto it = map_.find(key(a, b));
    return it == map_.end() ? kNone : it->second;
  }
  void erase(std::uint32_t a, std::uint32_t b) { map_.erase(key(a, b)); }
  std::size_t size() const { return map_.size(); }
  const std::unordered_map<std::uint64_t, std::uint32_t>& map() const { return map_; }

 private:
  std::unordered_map<std::uint64_t, std::uint32_t> map_;
};

struct CdtStats {
  std::size_t vertices_on_segments = 0;  ///< segment splits at existing vertices
  std::size_t crossings = 0;             ///< intersection vertices inserted
};

/// Inserts `segments` (vertex ids of tri.points) as constraints. Intersection vertices
/// are appended to tri.points. Zero-length segments are skipped.
Expected<void> insert_segments(Triangulation& tri,
                               const std::vector<std::array<std::uint32_t, 2>>& segments,
                               SubsegmentOwners& owners, CdtStats& stats);

struct DomainOptions {
  bool keep_convex_hull = false;  ///< do not eat concavities from the exterior
  bool track_regions = false;     ///< fill tri.region (0: none, k+1: region k)
};

struct DomainResult {
  /// Edges newly marked as subsegments because they bound the domain without being on
  /// an input segment (hull edges when the exterior is kept).
  std::vector<std::array<std::uint32_t, 2>> boundary_edges;
  std::vector<std::size_t> unused_regions;  ///< region points outside the domain
};

/// Marks as kOutside the triangles reachable from the exterior (unless kept) and from
/// each hole point without crossing a subsegment, then marks every edge between the
/// domain and the rest as a subsegment. A hole point outside the triangulation or in
/// the exterior is an InvalidInput error naming the hole.
Expected<DomainResult> classify_domain(Triangulation& tri, const std::vector<Point2>& holes,
                                       const std::vector<Pslg::Region>& regions,
                                       const DomainOptions& options);

}  // namespace delmesh::mesh2d
