// Exact facet and segment tests (see plc_geometry.h for the method).
#include "toolkit/plc/plc_geometry.h"

#include <algorithm>
#include <span>

namespace delmesh {
namespace {

using predicates::dot3d;
using predicates::orient2d_projected;
using predicates::orient3d;

constexpr Axis kAxes[3] = {Axis::X, Axis::Y, Axis::Z};

/// Is x on the closed segment [a, b], given that the three are collinear?
bool between_collinear(const Vec3& a, const Vec3& b, const Vec3& x) {
  return dot3d(a.data(), b.data(), x.data()) != Sign::Positive;
}

bool facet_has_vertex(const Plc::Facet& facet, std::uint32_t id) {
  if (id == kNoVertex) return false;
  for (const auto& polygon : facet.polygons) {
    if (std::find(polygon.begin(), polygon.end(), id) != polygon.end()) return true;
  }
  return false;
}

/// Closed segments [a,b] and [c,d] given by ids (kNoVertex never matches) and points:
/// do they meet other than at one shared endpoint id? Sets `touch_shared` when they share
/// an endpoint id (and meet only there).
/// `plane_axis`: when the four points are known to lie in one plane that does not contain
/// that axis direction, the projection along it is used directly (no orient3d, whose zero
/// would cost an exact evaluation).
bool meet_improperly(std::uint32_t ia, std::uint32_t ib, std::uint32_t ic, std::uint32_t id,
                     const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                     bool* touch_shared, const Axis* plane_axis = nullptr) {
  const bool ac = ia != kNoVertex && ia == ic, ad = ia != kNoVertex && ia == id;
  const bool bc = ib != kNoVertex && ib == ic, bd = ib != kNoVertex && ib == id;
  if ((ac && bd) || (ad && bc)) {
    if (touch_shared) *touch_shared = true;
    return false;  // the same segment
  }
  if (ac || ad || bc || bd) {
    const Vec3& s = (ac || ad) ? a : b;
    const Vec3& x = (ac || ad) ? b : a;
    const Vec3& y = (ac || bc) ? d : c;
    if (touch_shared) *touch_shared = true;
    return collinear(s, x, y) && dot3d(x.data(), y.data(), s.data()) == Sign::Positive;
  }
  if (!plane_axis && orient3d(a.data(), b.data(), c.data(), d.data()) != Sign::Zero) return false;
  const Axis only[1] = {plane_axis ? *plane_axis : Axis::X};
  for (Axis axis : plane_axis ? std::span<const Axis>(only) : std::span<const Axis>(kAxes)) {
    const Sign o1 = orient2d_projected(a.data(), b.data(), c.data(), axis);
    const Sign o2 = orient2d_projected(a.data(), b.data(), d.data(), axis);
    const Sign o3 = orient2d_projected(c.data(), d.data(), a.data(), axis);
    const Sign o4 = orient2d_projected(c.data(), d.data(), b.data(), axis);
    if (o1 == Sign::Zero && o2 == Sign::Zero && o3 == Sign::Zero && o4 == Sign::Zero) continue;
    if (to_int(o1) * to_int(o2) > 0 || to_int(o3) * to_int(o4) > 0) return false;
    if (o1 == Sign::Zero && o2 == Sign::Zero) break;  // collinear after all: fall through
    return true;
  }
  // All four points on one line: the segments meet iff their intervals overlap.
  return between_collinear(a, b, c) || between_collinear(a, b, d) ||
         between_collinear(c, d, a) || between_collinear(c, d, b);
}

/// In-plane orientation (a, b, x) for the query point x, and the other in-plane
/// questions point_in_facet() asks about it.
class QueryOps {
 public:
  QueryOps(const Plc& plc, const FacetFrame& frame, const PlaneQuery& q)
      : plc_(plc), frame_(frame), q_(q) {}

  Sign orient(const Vec3& a, const Vec3& b) const {
    if (q_.point) return orient_in_plane(plc_, frame_, a, b, *q_.point);
    // p = [below, above] ∩ plane: det[b-a, below-a, above-a] = ((b-a)x(p-a)).(above-below)
    // and (above - below) points to the positive side, so the signs agree.
    return orient3d(a.data(), b.data(), q_.below->data(), q_.above->data());
  }

  /// x on the closed segment [a, b], given orient(a, b) == Zero.
  bool on_segment(const Vec3& a, const Vec3& b) const {
    if (q_.point) return between_collinear(a, b, *q_.point);
    // a, b, below, above are coplanar and line ab crosses line (below, above) at x: x is
    // between a and b iff they are on opposite sides of that line within their plane.
    for (Axis axis : kAxes) {
      const Sign sa = orient2d_projected(q_.below->data(), q_.above->data(), a.data(), axis);
      if (sa == Sign::Zero) continue;
      const Sign sb = orient2d_projected(q_.below->data(), q_.above->data(), b.data(), axis);
      return to_int(sa) * to_int(sb) <= 0;
    }
    return true;  // a lies on the line (below, above), so a == x
  }

  bool equals(const Vec3& w) const {
    if (q_.point) return *q_.point == w;
    return collinear(*q_.below, *q_.above, w);
  }

  /// Side of y relative to the ray from x through q: orient(x, q, y) = orient(q, y, x).
  Sign ray_side(const Vec3& q, const Vec3& y) const { return orient(q, y); }

 private:
  const Plc& plc_;
  const FacetFrame& frame_;
  const PlaneQuery& q_;
};

/// Orientation of a loop (>= 3 vertices) in the frame's plane: the corner at its
/// lexicographically smallest vertex in the projection along the frame's axis, where a
/// simple loop turns strictly. Zero for a loop too degenerate to tell.
Sign loop_orientation(const Plc& plc, const FacetFrame& frame, const Plc::Polygon& loop) {
  const auto& P = plc.points;
  const int i0 = (static_cast<int>(frame.axis) + 1) % 3, i1 = (static_cast<int>(frame.axis) + 2) % 3;
  std::size_t lowest = 0;
  for (std::size_t k = 1; k < loop.size(); ++k) {
    const Vec3& a = P[loop[k]];
    const Vec3& b = P[loop[lowest]];
    if (a[i0] < b[i0] || (a[i0] == b[i0] && a[i1] < b[i1])) lowest = k;
  }
  const std::size_t n = loop.size();
  return orient_in_plane(plc, frame, P[loop[(lowest + n - 1) % n]], P[loop[lowest]], P[loop[(lowest + 1) % n]]);
}

/// Do points of the chord u-v close to u lie inside the loop `loop`, which passes through
/// u at position `at`? (v is in the plane and not on the loop's edges through u.) The
/// interior near u is the wedge left of prev->u->next for a loop turning positively.
bool chord_starts_inside_loop(const Plc& plc, const FacetFrame& frame, const Plc::Polygon& loop,
                              std::size_t at, std::uint32_t v, Sign orientation) {
  const auto& P = plc.points;
  const std::size_t n = loop.size();
  const Vec3* prev = &P[loop[(at + n - 1) % n]];
  const Vec3* next = &P[loop[(at + 1) % n]];
  if (orientation == Sign::Negative) std::swap(prev, next);
  const Vec3& u = P[loop[at]];
  const bool left_of_out = orient_in_plane(plc, frame, u, *next, P[v]) == Sign::Positive;
  const bool left_of_in = orient_in_plane(plc, frame, *prev, u, P[v]) == Sign::Positive;
  const Sign corner = orient_in_plane(plc, frame, *prev, u, *next);
  if (corner == Sign::Positive) return left_of_out && left_of_in;
  if (corner == Sign::Negative) return left_of_out || left_of_in;
  return left_of_out;  // a straight corner: the interior is the half-plane on the left
}

/// Is the open chord between facet vertices u and v, which lies in the facet plane and
/// meets no facet edge or vertex other than at u and v, inside the facet? The open chord
/// misses the boundary, so it lies wholly inside or wholly outside; decided near u by
/// counting the loops whose interior holds it there, with point_in_facet's rule (odd
/// count with hole points, any loop without).
bool chord_inside_facet(const Plc& plc, const Plc::Facet& facet, const FacetFrame& frame,
                        std::uint32_t u, std::uint32_t v) {
  int inside_loops = 0;
  for (const auto& polygon : facet.polygons) {
    if (polygon.size() < 3) continue;
    const auto at = std::find(polygon.begin(), polygon.end(), u);
    if (at != polygon.end()) {
      const Sign orientation = loop_orientation(plc, frame, polygon);
      if (orientation != Sign::Zero &&
          chord_starts_inside_loop(plc, frame, polygon, static_cast<std::size_t>(at - polygon.begin()),
                                   v, orientation)) {
        ++inside_loops;
      }
      continue;
    }
    Plc::Facet single;
    single.polygons.push_back(polygon);
    PlaneQuery q;
    q.point = &plc.points[u];
    if (point_in_facet(plc, single, frame, q) == PointLocation::Inside) ++inside_loops;
  }
  return facet.holes.empty() ? inside_loops > 0 : (inside_loops % 2) == 1;
}

}  // namespace

bool collinear(const Vec3& p, const Vec3& q, const Vec3& r) {
  for (Axis axis : kAxes) {
    if (orient2d_projected(p.data(), q.data(), r.data(), axis) != Sign::Zero) return false;
  }
  return true;
}

std::optional<FacetFrame> facet_frame(const Plc& plc, const Plc::Facet& facet) {
  const auto& P = plc.points;
  std::uint32_t a = kNoVertex, b = kNoVertex;
  for (const auto& polygon : facet.polygons) {
    for (std::uint32_t v : polygon) {
      if (a == kNoVertex) {
        a = v;
      } else if (b == kNoVertex) {
        if (P[v] != P[a]) b = v;
      } else if (!collinear(P[a], P[b], P[v])) {
        FacetFrame frame{a, b, v, Axis::Z, Sign::Zero};
        for (Axis axis : kAxes) {
          const Sign s = orient2d_projected(P[a].data(), P[b].data(), P[v].data(), axis);
          if (s != Sign::Zero) {
            frame.axis = axis;
            frame.axis_sign = s;
            return frame;
          }
        }
      }
    }
  }
  return std::nullopt;
}

Sign orient_in_plane(const Plc&, const FacetFrame& frame, const Vec3& p, const Vec3& q,
                     const Vec3& r) {
  return orient2d_projected(p.data(), q.data(), r.data(), frame.axis) * frame.axis_sign;
}

Sign side_of_plane(const Plc& plc, const FacetFrame& frame, const Vec3& x) {
  const auto& P = plc.points;
  return orient3d(P[frame.a].data(), P[frame.b].data(), P[frame.c].data(), x.data());
}

PointLocation point_in_facet(const Plc& plc, const Plc::Facet& facet, const FacetFrame& frame,
                             const PlaneQuery& query) {
  const auto& P = plc.points;
  const QueryOps ops(plc, frame, query);
  // Boundary first: on an edge or an isolated facet vertex.
  for (const auto& polygon : facet.polygons) {
    if (polygon.size() == 1) {
      if (ops.equals(P[polygon[0]])) return PointLocation::Boundary;
      continue;
    }
    bool on_edge = false;
    for_each_polygon_edge(polygon, [&](std::uint32_t a, std::uint32_t b) {
      if (!on_edge && ops.orient(P[a], P[b]) == Sign::Zero && ops.on_segment(P[a], P[b])) {
        on_edge = true;
      }
    });
    if (on_edge) return PointLocation::Boundary;
  }
  // Ray from x through the first loop vertex q (x != q, as x is on no edge); crossings
  // counted with the half-open rule: a vertex on the ray line counts as "right side".
  const Vec3* q = nullptr;
  for (const auto& polygon : facet.polygons) {
    if (polygon.size() >= 3) {
      q = &P[polygon[0]];
      break;
    }
  }
  if (!q) return PointLocation::Outside;
  int odd_loops = 0;
  for (const auto& polygon : facet.polygons) {
    const std::size_t n = polygon.size();
    if (n < 3) continue;
    bool odd = false;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& a = P[polygon[i]];
      const Vec3& b = P[polygon[(i + 1) % n]];
      const bool sa = ops.ray_side(*q, a) == Sign::Positive;
      const bool sb = ops.ray_side(*q, b) == Sign::Positive;
      if (sa == sb) continue;
      const Sign o = ops.orient(a, b);
      if ((!sa && o == Sign::Positive) || (sa && o == Sign::Negative)) odd = !odd;
    }
    odd_loops += odd ? 1 : 0;
  }
  const bool inside = facet.holes.empty() ? odd_loops > 0 : (odd_loops % 2) == 1;
  return inside ? PointLocation::Inside : PointLocation::Outside;
}

Contact segment_facet_contact(const Plc& plc, const Plc::Facet& facet, const FacetFrame& frame,
                              std::uint32_t u, std::uint32_t v, const Vec3& pu,
                              const Vec3& pv) {
  // A vertex of the (planar) facet lies on its plane: no predicate needed, and none of
  // the exact fallbacks that a zero determinant would cost.
  const Sign su = facet_has_vertex(facet, u) ? Sign::Zero : side_of_plane(plc, frame, pu);
  const Sign sv = facet_has_vertex(facet, v) ? Sign::Zero : side_of_plane(plc, frame, pv);
  if (su == sv && su != Sign::Zero) return Contact::None;
  if (su != Sign::Zero && sv != Sign::Zero) {
    PlaneQuery q;
    q.below = su == Sign::Negative ? &pu : &pv;
    q.above = su == Sign::Negative ? &pv : &pu;
    return point_in_facet(plc, facet, frame, q) == PointLocation::Outside ? Contact::None
                                                                           : Contact::Improper;
  }
  if (su != Sign::Zero || sv != Sign::Zero) {
    // Exactly one endpoint lies in the plane: the contact, if any, is that point.
    const std::uint32_t w = su == Sign::Zero ? u : v;
    const Vec3& pw = su == Sign::Zero ? pu : pv;
    if (facet_has_vertex(facet, w)) return Contact::Allowed;
    PlaneQuery q;
    q.point = &pw;
    return point_in_facet(plc, facet, frame, q) == PointLocation::Outside ? Contact::None
                                                                           : Contact::Improper;
  }
  // The segment lies in the facet plane.
  const auto& P = plc.points;
  bool is_edge = false, improper = false, touches = false;
  for_each_facet_edge(facet, [&](std::uint32_t a, std::uint32_t b) {
    if ((a == u && b == v) || (a == v && b == u)) is_edge = true;
  });
  if (is_edge) return Contact::Allowed;
  for_each_facet_edge(facet, [&](std::uint32_t a, std::uint32_t b) {
    if (!improper && meet_improperly(u, v, a, b, pu, pv, P[a], P[b], &touches, &frame.axis)) {
      improper = true;
    }
  });
  if (improper) return Contact::Improper;
  for (const auto& polygon : facet.polygons) {
    if (polygon.size() != 1 || polygon[0] == u || polygon[0] == v) continue;
    const Vec3& w = P[polygon[0]];
    if (collinear(pu, pv, w) && between_collinear(pu, pv, w)) return Contact::Improper;
  }
  const bool u_vertex = facet_has_vertex(facet, u), v_vertex = facet_has_vertex(facet, v);
  if (u_vertex && v_vertex && u != v) {
    return chord_inside_facet(plc, facet, frame, u, v) ? Contact::Improper : Contact::Allowed;
  }
  for (int k = 0; k < 2; ++k) {
    if (k == 0 ? u_vertex : v_vertex) continue;
    PlaneQuery q;
    q.point = k == 0 ? &pu : &pv;
    if (point_in_facet(plc, facet, frame, q) != PointLocation::Outside) return Contact::Improper;
  }
  return (u_vertex || v_vertex || touches) ? Contact::Allowed : Contact::None;
}

bool segments_meet_improperly(const Plc& plc, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                              std::uint32_t d, const FacetFrame* frame) {
  const auto& P = plc.points;
  return meet_improperly(a, b, c, d, P[a], P[b], P[c], P[d], nullptr, frame ? &frame->axis : nullptr);
}

}  // namespace delmesh
