// 2D triangulation and Delaunay refinement of a PSLG: the library entry point behind
// `delmesh tri` (notes ch. 3). Constrained Delaunay triangulation, removal of holes and
// concavities, regional attributes and area bounds, then Ruppert's (or Chew's first)
// refinement with guaranteed termination for any input angles.
#pragma once

#include <cstdint>
#include <functional>

#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/core/mesh_status.h"
#include "toolkit/mesh2d/pslg.h"
#include "toolkit/mesh2d/triangle_mesh.h"

namespace delmesh {

struct TriangulateOptions {
  /// Triangulate the PSLG (constrained Delaunay, holes and concavities removed). When
  /// false, only the points are triangulated (Delaunay triangulation of their convex hull).
  bool pslg = true;
  /// Keep the triangles of the convex hull (Triangle -c): concavities are not removed.
  bool keep_convex_hull = false;
  /// Delaunay refinement to the minimum angle below (Triangle -q).
  bool quality = false;
  double min_angle_deg = 20.0;
  /// Global maximum triangle area (Triangle -a#); <= 0: none.
  double max_area = -1.0;
  /// Apply the per-region max areas of the PSLG (Triangle -a without a number).
  bool region_max_area = false;
  /// Copy region attributes to triangles (Triangle -A).
  bool region_attributes = false;
  /// Optional sizing callback: the largest area wanted for a triangle whose circumcenter
  /// (or centroid) is (x, y); <= 0 means no bound there.
  std::function<double(double x, double y)> max_area_at;
  /// Use Chew's first algorithm (uniform, edge length bounded by the shortest input
  /// feature) instead of Ruppert's.
  bool chew = false;
  /// Split skinny triangles at off-centers (Üngör) rather than circumcenters when the
  /// circumcenter is far from the shortest edge: fewer triangles at the same quality.
  bool off_centers = true;
  /// Interior improvement of notes §3.6 (first strategy): triangles with a vertex in the
  /// interior of a segment need only 20.7 degrees (circumradius-to-shortest-edge ratio
  /// sqrt 2), the others the full bound. Guarantees termination for bounds up to 30
  /// degrees without relying on the rules for small angles, at the price of weaker
  /// triangles along segments.
  bool relaxed_boundary = false;
  /// Upper bound on the number of Steiner points (Triangle -S); negative: unlimited.
  long long max_steiner_points = -1;
  /// Log sink for progress and warnings; null discards.
  LogSink* log = nullptr;
};

struct TriangulateStats {
  std::size_t input_points = 0;
  std::size_t steiner_points = 0;
  std::size_t duplicate_points = 0;   ///< input points equal to an earlier one (merged)
  std::size_t segment_crossings = 0;  ///< intersection vertices inserted where segments cross
  double min_angle_deg = 0.0;
  double max_angle_deg = 0.0;
  /// Triangles left below the angle bound because a small input angle forbids fixing
  /// them (or the Steiner budget ran out).
  std::size_t unmet_triangles = 0;
  double seconds_triangulate = 0.0;
  double seconds_refine = 0.0;
};

struct TriangulateResult {
  TriangleMesh mesh;
  MeshStatus status = MeshStatus::Complete;
  TriangulateStats stats;
};

/// Triangulates (and refines) `input`. Bad input (crossing segments that cannot be
/// split, hole points outside, fewer than three non-collinear points) is an Error.
Expected<TriangulateResult> triangulate(const Pslg& input, const TriangulateOptions& options);

}  // namespace delmesh
