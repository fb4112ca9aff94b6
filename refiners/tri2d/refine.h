// Delaunay refinement of a constrained Delaunay triangulation (notes ch. 3): Ruppert's
// algorithm with diametral circles (§3.4), or Chew's first algorithm (§3.3).
//
// Ruppert: encroached subsegments are split first (a subsegment is encroached when a
// vertex sees it at 90 degrees or more: predicates::dot2d); then bad triangles (angle
// below the bound, or area above a global / regional / callback bound) are split at
// their circumcenters, taken from a bucketed queue (§3.5.2: 64 FIFO buckets by
// circumradius-to-shortest-edge ratio, worst first; well-shaped but too large triangles
// in one last bucket). A circumcenter that would encroach subsegments (or that lies
// behind a subsegment) is rejected and those subsegments are split instead.
//
// Small input angles (§3.8): subsegments with an endpoint shared with another segment
// are split on concentric shells (power-of-two distances from that vertex); a triangle
// whose smallest angle lies between two subsegments is never split for its angle; and
// the Quitter decides whether a subsegment encroached by a circumcenter may be split.
//
// Termination (why refinement always stops), with r(v) the insertion radius of v (its
// distance to the nearest vertex when inserted) and d the shortest edge of a triangle:
//  * size-driven splits produce vertices whose insertion radius is bounded below in
//    terms of the area bounds, so there are finitely many of them;
//  * for angle bounds of at most 30 degrees (B = 1/(2 sin theta) >= 1) this is
//    Ruppert's algorithm with the Quitter (notes Theorem 25, with the conservative r_g
//    = d approximation and without the ancestor provision);
//  * for bounds above 30 degrees (B < 1) two more rules make every angle-driven vertex's
//    insertion radius at least its parent's: a circumcenter is inserted only if its
//    circumradius is >= r(parent), parent being the newer endpoint of the shortest
//    edge; a subsegment split requested by a circumcenter is done only if the new
//    vertex's insertion radius is >= d (notes §3.6, third strategy). With radii that
//    never decrease along ancestor chains, the packing argument of §3.4.3 bounds the
//    number of vertices;
//  * as a last resort against floating-point collapse, a subsegment is never split when
//    the split point would coincide with an endpoint, and a Steiner budget may be set.
// Triangles left bad for any of these reasons are counted as unmet.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "toolkit/core/log.h"
#include "toolkit/mesh2d/cdt.h"
#include "toolkit/mesh2d/triangulation.h"

namespace delmesh::tri2d {

/// Per-vertex classification used by refinement (bit set).
enum VertexKind : std::uint8_t {
  kInputVertex = 1,     ///< from the input (or an intersection vertex of crossing segments)
  kCornerVertex = 2,    ///< input vertex where two or more segments meet
  kSmallAngleVertex = 4,///< input vertex with two segments meeting at less than 60 degrees
  kSegmentVertex = 8,   ///< Steiner vertex on a segment
  kFreeVertex = 16,     ///< Steiner vertex in the interior
};

/// Owner id of subsegments on the domain boundary that lie on no input segment.
inline constexpr std::uint32_t kHullSegment = 0xFFFFFFFEu;

struct RefineParams {
  bool quality = false;
  double min_angle_deg = 20.0;
  double max_area = -1.0;
  std::vector<double> region_max_area;  ///< indexed by tri.region value (0: none)
  std::function<double(double, double)> max_area_at;
  bool chew = false;
  long long max_steiner_points = -1;
  LogSink* log = nullptr;
};

struct RefineOutcome {
  std::size_t steiner_points = 0;
  std::size_t unmet_triangles = 0;   ///< bad triangles left at the end
  bool budget_exhausted = false;
};

/// Refines `tri` in place. `kind` has one entry per vertex (grown as vertices are
/// added); `owners` is kept up to date as subsegments split.
RefineOutcome refine(mesh2d::Triangulation& tri, mesh2d::SubsegmentOwners& owners,
                     std::vector<std::uint8_t>& kind, const RefineParams& params);

/// Sets kCornerVertex / kSmallAngleVertex for the input vertices of a constrained
/// triangulation from the subsegments around them.
void classify_input_vertices(const mesh2d::Triangulation& tri, std::vector<std::uint8_t>& kind);

}  // namespace delmesh::tri2d
