// Delaunay refinement of a constrained Delaunay triangulation (notes ch. 3): Ruppert's
// algorithm with diametral circles (§3.4), or Chew's first algorithm (§3.3).
//
// Ruppert: encroached subsegments are split first (a subsegment is encroached when a
// vertex sees it at 90 degrees or more: predicates::dot2d); then bad triangles (angle
// below the bound, or area above a global / regional / callback bound) are split at
// their circumcenters, taken from a bucketed queue (§3.5.2: 64 FIFO buckets by
// circumradius-to-shortest-edge ratio, worst first). Too-large triangles sit in a stack
// that is served first: on A.poly with an area bound this gives 1-4% fewer triangles than
// serving the skinny ones first and fewer unmet triangles above 30 degrees, and the
// depth-first order stays in cache. A circumcenter that would encroach subsegments (or
// that lies behind a subsegment) is rejected and those subsegments are split instead.
//
// Off-centers (Üngör, "Off-centers: a new type of Steiner points for computing size-
// optimal quality-guaranteed Delaunay triangulations", 2004), on by default: a skinny
// triangle whose circumcenter lies far from its shortest edge pq is split at the point
// of pq's bisector that makes the triangle on pq meet the bound exactly. Measured
// without an area bound at 33 degrees: p2t-dude 693 -> 497 triangles, p2t-debug2 477k ->
// 462k, A.poly 180 -> 174 (cgal-clusters at 30 degrees: 362 -> 317), with the same
// minimum angle and no more unmet triangles; with A.poly's area bound the counts are
// equal (+0.02%).
//
// Small input angles (§3.8): subsegments with an endpoint shared with another segment
// are split on concentric shells (power-of-two distances from that vertex); a triangle
// whose smallest angle lies between two subsegments is never split for its angle; and
// the Quitter decides whether a subsegment encroached by a circumcenter may be split.
//
// Termination (why refinement always stops). r(v), the insertion radius of v, is its
// distance to the nearest vertex when inserted; the parent of a circumcenter is the newer
// endpoint of its triangle's shortest edge, the parent of a subsegment vertex split for a
// rejected circumcenter is that circumcenter (its "grandparent" in §3.8 terms).
//  * Size-driven splits produce vertices whose insertion radius is bounded below in terms
//    of the area bounds, so there are finitely many of them.
//  * Angle-driven vertices carry an anchor: the largest insertion radius along their
//    chain of angle-driven ancestors. Such a vertex is inserted only if r(v) >= k *
//    anchor(parent) (k = 1/2 for bounds up to 30 degrees, where Ruppert's analysis gives
//    r(v) >= anchor / sqrt(2) anyway, k = 0.7 above). Every chain therefore stays above
//    k times the radius of its root (an input vertex, a size-driven vertex or an
//    encroachment split), so insertion radii are bounded below and the packing argument
//    of §3.4.3 bounds the number of vertices. Above 30 degrees, subsegment splits caused
//    by an encroaching vertex inherit that vertex's anchor as well.
//  * Encroachment cascades between segments meeting at small angles stop at power-of-two
//    lengths (concentric shells), and the Quitter (with the conservative r_g = d
//    approximation and without the ancestor provision) refuses trigger vertices that
//    would restart them at a smaller scale (notes Theorem 25).
//  * As a last resort against floating-point collapse, a subsegment is never split when
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
  bool off_centers = true;
  bool relaxed_boundary = false;  ///< see TriangulateOptions::relaxed_boundary
  long long max_steiner_points = -1;
  /// Optional per-vertex attributes (num_attributes per vertex, vertex-major): new
  /// vertices get values interpolated linearly along their subsegment or in the
  /// triangle that contains them.
  std::vector<double>* attributes = nullptr;
  int num_attributes = 0;
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
