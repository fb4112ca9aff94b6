// Exact geometric tests on PLC facets and segments (notes §2.1.4: facets are planar
// polygons with holes; two PLC entities may meet only at shared vertices and segments).
//
// Every sign comes from toolkit/predicates. A facet's plane is represented by a
// reference triple of its own vertices (never by a rounded normal), and 2D questions
// inside the plane are answered with orient2d_projected on an axis along which that
// triple does not degenerate; that projection is an affine bijection of the plane, so
// it preserves every in-plane orientation. Points where a segment crosses a plane are
// never constructed: an in-plane orientation involving such an implicit point p = uv ∩
// plane is the orient3d of the two in-plane points and u, v (see point_in_facet()).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "toolkit/plc/plc.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh {

inline constexpr std::uint32_t kNoVertex = ~0u;

/// The exact plane of a planar facet: three non-collinear facet vertices (a, b, c) and a
/// projection axis along which their orientation is not zero. "In-plane orientation"
/// below is the orientation seen from the side the normal (b-a)x(c-a) points to.
struct FacetFrame {
  std::uint32_t a = 0, b = 0, c = 0;
  Axis axis = Axis::Z;
  Sign axis_sign = Sign::Positive;  ///< orient2d_projected(a, b, c, axis)
};

/// True when p, q, r lie on one line (exact; coincident points count as collinear).
bool collinear(const Vec3& p, const Vec3& q, const Vec3& r);

/// First non-collinear triple among the facet's vertices (polygon order), or nullopt if
/// the facet is degenerate (fewer than three distinct non-collinear vertices). Vertex
/// ids must be valid indices into plc.points.
std::optional<FacetFrame> facet_frame(const Plc& plc, const Plc::Facet& facet);

/// In-plane orientation of three points lying in the frame's plane.
Sign orient_in_plane(const Plc& plc, const FacetFrame& frame, const Vec3& p, const Vec3& q,
                     const Vec3& r);

/// Side of x with respect to the frame's plane: Positive on the normal's side.
Sign side_of_plane(const Plc& plc, const FacetFrame& frame, const Vec3& x);

enum class PointLocation : std::uint8_t { Outside, Boundary, Inside };

/// A query point for point_in_facet(): either an explicit point lying exactly in the
/// facet plane, or the implicit crossing point of segment [below, above] with the
/// plane, where `below` is strictly on the negative and `above` strictly on the positive
/// side.
struct PlaneQuery {
  const Vec3* point = nullptr;
  const Vec3* below = nullptr;
  const Vec3* above = nullptr;
};

/// Where the query point lies relative to the closed facet. Boundary: on an edge of one
/// of its polygons (including 2-vertex polygons) or on a 1-vertex polygon. Inside is
/// decided by ray parity per loop (loops are polygons of >= 3 vertices, ray crossings
/// counted with the half-open rule, so vertices on the ray count once): a facet with
/// hole points is the set of points inside an odd number of its loops (outer boundary
/// plus hole loops); a facet without hole points is the union of its loops' interiors
/// (inner loops are then constraints, as in TetGen).
PointLocation point_in_facet(const Plc& plc, const Plc::Facet& facet, const FacetFrame& frame,
                             const PlaneQuery& query);

/// How a closed segment meets a closed facet.
enum class Contact : std::uint8_t {
  None,      ///< disjoint
  Allowed,   ///< only at facet vertices that are endpoints of the segment (same ids), or
             ///< the segment is an edge of the facet
  Improper,  ///< any other contact (crossing, touching the interior or an edge, overlap)
};

/// Contact of the segment [plc.points[u], plc.points[v]] with the facet. u or v may be
/// kNoVertex together with explicit coordinates pu / pv for points that are no PLC
/// vertex (used for rays). A segment lying in the facet plane whose two endpoints are
/// both facet vertices (a chord, e.g. another facet's edge along this facet's diagonal)
/// is Improper when it runs through the facet's interior and Allowed when it runs
/// outside (across a hole or a notch).
Contact segment_facet_contact(const Plc& plc, const Plc::Facet& facet, const FacetFrame& frame,
                              std::uint32_t u, std::uint32_t v, const Vec3& pu, const Vec3& pv);

/// Do the closed segments [a,b] and [c,d] (PLC vertex ids) meet other than at a shared
/// endpoint id? Identical segments (same ids) do not count. Works in 3D (any position);
/// pass the frame of a facet whose plane holds all four points to test in that plane.
bool segments_meet_improperly(const Plc& plc, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                              std::uint32_t d, const FacetFrame* frame = nullptr);

/// Visits every edge of a polygon as f(a, b): consecutive vertices of a loop (>= 3
/// vertices, closing edge included) or the single edge of a 2-vertex polygon.
template <class F>
void for_each_polygon_edge(const Plc::Polygon& polygon, F&& f) {
  const std::size_t n = polygon.size();
  if (n == 2) {
    f(polygon[0], polygon[1]);
  } else if (n >= 3) {
    for (std::size_t i = 0; i < n; ++i) f(polygon[i], polygon[(i + 1) % n]);
  }
}

/// Visits every edge of every polygon of the facet as f(a, b).
template <class F>
void for_each_facet_edge(const Plc::Facet& facet, F&& f) {
  for (const auto& polygon : facet.polygons) for_each_polygon_edge(polygon, f);
}

}  // namespace delmesh
