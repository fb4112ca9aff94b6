// Small input angles and the tets touching them (see small_angles.h).
#include "refiners/tet3d/small_angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <utility>

#include "refiners/tet3d/plc_preparation.h"

namespace delmesh::tet3d {

namespace {

/// Rule (f): a tet across a sharp wedge counts where the wedge is narrower than this many
/// floors.
constexpr double kAcrossWedgeFloors = 2.0;

double angle_deg(const Vec3& u, const Vec3& v) {
  const double c = u.dot(v) / (u.norm() * v.norm());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

/// Does direction d, projected onto the plane of triangle (v, p, q), point strictly into
/// the triangle's corner at v?
bool projects_into_corner(const Vec3& v, const Vec3& p, const Vec3& q, const Vec3& d) {
  const Vec3 e1 = p - v, e2 = q - v;
  const Vec3 n = e1.cross(e2);
  const double n2 = n.squaredNorm();
  if (!(n2 > 0.0)) return false;
  const Vec3 in_plane = d - (d.dot(n) / n2) * n;
  // in_plane = alpha e1 + beta e2.
  const double alpha = in_plane.cross(e2).dot(n) / n2;
  const double beta = e1.cross(in_plane).dot(n) / n2;
  return alpha > 0.0 && beta > 0.0;
}

/// The angle between direction d and the plane of triangle (v, p, q), in degrees.
double angle_to_plane_deg(const Vec3& v, const Vec3& p, const Vec3& q, const Vec3& d) {
  const Vec3 n = (p - v).cross(q - v);
  return 90.0 - angle_deg(d, n.dot(d) >= 0.0 ? n : Vec3(-n));
}

/// The termination floor a vertex ended with: its quality-stage floor, or its recovery
/// floor for a vertex that has none (quality_refinement.h).
double termination_floor_of(const RefineState& state, std::uint32_t v) {
  const VertexInfo& info = state.vertices[v];
  return info.field_floor > 0.0 ? info.field_floor : info.floor;
}

/// The segments at each vertex, indexed by vertex id up to the largest segment endpoint
/// (vertices beyond have none). Segment endpoints are input vertices, so the array stays
/// small when the mesh is refined: sized by every vertex, it cost 3.0 MB at the end of
/// cgal-bear at radius-edge 1.414, on top of what the run holds there.
std::vector<std::vector<std::uint32_t>> incident_segments(const RefineState& state) {
  std::uint32_t last = 0;
  for (const SegmentData& seg : state.segments) last = std::max({last, seg.a, seg.b});
  std::vector<std::vector<std::uint32_t>> incident(state.segments.empty() ? 0 : std::size_t{last} + 1);
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    incident[state.segments[s].a].push_back(s);
    incident[state.segments[s].b].push_back(s);
  }
  return incident;
}

/// Segment s from its end v to its other end.
Vec3 arm_vector(const RefineState& state, std::uint32_t s, std::uint32_t v) {
  const SegmentData& seg = state.segments[s];
  return state.mesh.point(seg.a == v ? seg.b : seg.a) - state.mesh.point(v);
}

/// A cosine below this is of an angle above kSmallSegmentAngleDeg (60 degrees) by far more
/// than acos's rounding.
constexpr double kNarrowCornerCosineBelow = 0.5 - 1e-9;
static_assert(kSmallSegmentAngleDeg == 60.0);

/// Calls fn(s1, s2, v, degrees) for each pair of segments meeting at a vertex v at an
/// angle below kSmallSegmentAngleDeg.
template <typename Fn>
void for_each_narrow_corner(const RefineState& state, const std::vector<std::vector<std::uint32_t>>& incident, Fn fn) {
  for (std::uint32_t v = 1; v < incident.size(); ++v) {
    const auto& segs = incident[v];
    for (std::size_t i = 0; i < segs.size(); ++i)
      for (std::size_t j = i + 1; j < segs.size(); ++j) {
        const Vec3 u = arm_vector(state, segs[i], v), w = arm_vector(state, segs[j], v);
        // cos 60 degrees is 1/2: arms whose cosine lies clearly below it make a wider angle,
        // whatever acos's rounding (the angle itself is measured for the others only).
        if (u.dot(w) / (u.norm() * w.norm()) < kNarrowCornerCosineBelow) continue;
        const double angle = angle_deg(u, w);
        if (angle < kSmallSegmentAngleDeg) fn(segs[i], segs[j], v, angle);
      }
  }
}

/// IdLists from the (key, id) pairs `for_each_pair(emit)` emits by calling emit(key, id):
/// each key's ids in the order emitted; with `unique`, each id once per key (its first
/// occurrence). The pairs are emitted three times over (largest key, counts, fill) instead
/// of being stored: on a surface every input edge is a segment, and an array of the pairs
/// of its ends raised the peak memory of the run (cgal-bear, strongly Delaunay: +1.7 MB).
template <typename ForEachPair>
IdLists make_id_lists(const ForEachPair& for_each_pair, bool unique) {
  IdLists lists;
  std::uint32_t keys = 0;
  for_each_pair([&](std::uint32_t key, std::uint32_t) { keys = std::max(keys, key + 1); });
  lists.start.assign(std::size_t{keys} + 1, 0);
  for_each_pair([&](std::uint32_t key, std::uint32_t) { ++lists.start[key + 1]; });
  for (std::size_t k = 0; k < keys; ++k) lists.start[k + 1] += lists.start[k];
  lists.ids.resize(lists.start[keys]);
  std::vector<std::uint32_t> fill(lists.start.begin(), lists.start.end() - 1);
  for_each_pair([&](std::uint32_t key, std::uint32_t id) { lists.ids[fill[key]++] = id; });
  if (!unique) return lists;
  // Drop repeated ids within each (short) list, closing the gaps in place.
  std::uint32_t out = 0;
  for (std::size_t k = 0; k < keys; ++k) {
    const std::uint32_t begin = lists.start[k], end = lists.start[k + 1], first = out;
    for (std::uint32_t i = begin; i < end; ++i) {
      const std::uint32_t id = lists.ids[i];
      const auto kept = lists.ids.begin() + out;
      if (std::find(lists.ids.begin() + first, kept, id) == kept) lists.ids[out++] = id;
    }
    lists.start[k] = first;
  }
  lists.start[keys] = out;
  lists.ids.resize(out);
  lists.ids.shrink_to_fit();
  return lists;
}

/// The facets through each input vertex at a segment's end, by vertex id.
IdLists facets_at_segment_ends(const RefineState& state) {
  return make_id_lists(
      [&](const auto& emit) {
        for (const SegmentData& seg : state.segments)
          for (const std::uint32_t end : {seg.a, seg.b})
            for (const std::uint32_t f : seg.facets) emit(end, f);
      },
      true);
}

/// The facets vertex x lies on (on the facet or on its boundary): its own facet, its
/// segment's facets, or for an input vertex the facets of its segments.
std::span<const std::uint32_t> facets_of_vertex(const RefineState& state, const IdLists& input_facets,
                                                std::uint32_t x) {
  const VertexInfo& info = state.vertices[x];
  if (info.kind == VertexKind::OnFacet) return std::span<const std::uint32_t>(&info.owner, 1);
  if (info.kind == VertexKind::OnSegment) return state.segments[info.owner].facets;
  if (info.kind == VertexKind::Input) return input_facets.of(x);
  return {};
}

/// Distance from p to segment s.
double distance_to_segment(const RefineState& state, const Vec3& p, std::uint32_t s) {
  const SegmentData& seg = state.segments[s];
  const Vec3& a = state.mesh.point(seg.a);
  const Vec3 ab = state.mesh.point(seg.b) - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

}  // namespace

void classify_small_angles(RefineState& state) {
  const std::vector<std::vector<std::uint32_t>> incident = incident_segments(state);
  // Records a small angle of segment s at its end v: v is an apex (rule (a)), and s keeps
  // the sine of its smallest such angle there (rule (d)).
  auto note_small_angle = [&](std::uint32_t s, std::uint32_t v, double degrees) {
    state.vertices[v].small_angle = true;
    SegmentData& seg = state.segments[s];
    double& sine = seg.a == v ? seg.sine_at_a : seg.sine_at_b;
    const double sn = std::sin(degrees * std::numbers::pi / 180.0);
    if (sine == 0.0 || sn < sine) sine = sn;
  };
  // Two segments at a vertex.
  for_each_narrow_corner(state, incident, [&](std::uint32_t s1, std::uint32_t s2, std::uint32_t v, double angle) {
    note_small_angle(s1, v, angle);
    note_small_angle(s2, v, angle);
  });
  // A segment and a facet at a vertex, where the segment projects into the facet.
  for (std::uint32_t f = 0; f < state.facets.size(); ++f) {
    for (const Subface& t : state.facets[f].subfaces()) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = t[k];
        if (v >= incident.size()) continue;  // on no segment
        const Vec3& pv = state.mesh.point(v);
        const Vec3& pp = state.mesh.point(t[(k + 1) % 3]);
        const Vec3& pq = state.mesh.point(t[(k + 2) % 3]);
        for (const std::uint32_t s : incident[v]) {
          const auto& fs = state.segments[s].facets;
          if (std::find(fs.begin(), fs.end(), f) != fs.end()) continue;  // a segment of the facet
          const Vec3 d = arm_vector(state, s, v);
          // The corner test first: it needs no acos (both tests must pass; the order
          // changes no answer).
          if (!projects_into_corner(pv, pp, pq, d)) continue;
          const double angle = angle_to_plane_deg(pv, pp, pq, d);
          if (angle < kSmallSegmentFacetAngleDeg) note_small_angle(s, v, angle);
        }
      }
    }
  }
  // Two facets at a segment.
  std::vector<std::pair<std::uint32_t, Vec3>> wings;
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    SegmentData& seg = state.segments[s];
    if (seg.facets.size() < 2) continue;
    const Vec3& pa = state.mesh.point(seg.a);
    const Vec3 d = (state.mesh.point(seg.b) - pa).normalized();
    wings.clear();
    for (const std::uint32_t f : seg.facets) {
      std::uint32_t c = state.facets[f].third_vertex(seg.a, seg.b);
      if (c == ~0u) c = state.facets[f].third_vertex(seg.b, seg.a);
      if (c == ~0u) continue;
      Vec3 w = state.mesh.point(c) - pa;
      w -= w.dot(d) * d;
      wings.emplace_back(f, w);
    }
    for (std::size_t i = 0; i < wings.size(); ++i)
      for (std::size_t j = i + 1; j < wings.size(); ++j) {
        const double angle = angle_deg(wings[i].second, wings[j].second);
        if (!(angle < kSmallFacetAngleDeg)) continue;
        seg.small_angle = true;
        state.segment_wedges.push_back({s, wings[i].first, wings[j].first, std::sin(angle * std::numbers::pi / 180.0)});
      }
    if (seg.small_angle) {
      state.vertices[seg.a].small_angle = true;
      state.vertices[seg.b].small_angle = true;
    }
  }
}

bool vertex_at_small_angle(const RefineState& state, std::uint32_t v) {
  const VertexInfo& info = state.vertices[v];
  if (info.small_angle) return true;
  if (info.kind != VertexKind::OnSegment) return false;
  const SegmentData& seg = state.segments[info.owner];
  if (seg.small_angle) return true;
  // Rule (d): within the floor zone of a small angle at either end of the segment.
  const double floor = termination_floor_of(state, v);
  const Vec3& p = state.mesh.point(v);
  if (seg.sine_at_a > 0.0 && (p - state.mesh.point(seg.a)).norm() * seg.sine_at_a <= floor) return true;
  return seg.sine_at_b > 0.0 && (p - state.mesh.point(seg.b)).norm() * seg.sine_at_b <= floor;
}

SharpWedges::SharpWedges(const RefineState& state) : state_(state) {
  for (const SegmentWedge& w : state.segment_wedges) wedges_.push_back({w.segment, w.f1, w.f2, w.sine});
  if (wedges_.empty()) return;
  by_facet_ = make_id_lists(
      [&](const auto& emit) {
        for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(wedges_.size()); ++k) {
          emit(wedges_[k].f1, k);
          emit(wedges_[k].f2, k);
        }
      },
      false);
  input_facets_ = facets_at_segment_ends(state);
}

bool SharpWedges::within_floors(std::uint32_t x, double floors) const {
  if (wedges_.empty()) return false;
  const Vec3& p = state_.mesh.point(x);
  const double reach = floors * termination_floor_of(state_, x);
  for (const std::uint32_t f : facets_of_vertex(state_, input_facets_, x)) {
    for (const std::uint32_t k : by_facet_.of(f)) {
      const Wedge& w = wedges_[k];
      if (distance_to_segment(state_, p, w.segment) * w.sine <= reach) return true;
    }
  }
  return false;
}

bool SharpWedges::in_wedge_zone(std::uint32_t x) const { return within_floors(x, 1.0); }

bool SharpWedges::near_wedge(std::uint32_t x) const { return within_floors(x, kAcrossWedgeFloors); }

bool SharpWedges::across_wedge(const std::array<std::uint32_t, 4>& v) const {
  for (const std::uint32_t x : v) {
    const Vec3& p = state_.mesh.point(x);
    const double floor = termination_floor_of(state_, x);
    for (const std::uint32_t f : facets_of_vertex(state_, input_facets_, x)) {
      for (const std::uint32_t k : by_facet_.of(f)) {
        const Wedge& w = wedges_[k];
        if (distance_to_segment(state_, p, w.segment) * w.sine > kAcrossWedgeFloors * floor) continue;
        // x lies on facet f of the wedge near its segment: another vertex on the other facet?
        const std::uint32_t other = f == w.f1 ? w.f2 : w.f1;
        for (const std::uint32_t y : v) {
          if (y == x) continue;
          const auto fs = facets_of_vertex(state_, input_facets_, y);
          if (std::find(fs.begin(), fs.end(), other) != fs.end()) return true;
        }
      }
    }
  }
  return false;
}

NarrowCorners::NarrowCorners(const RefineState& state) : state_(state) {
  for_each_narrow_corner(state, incident_segments(state),
                         [&](std::uint32_t s1, std::uint32_t s2, std::uint32_t, double) {
                           corners_.push_back({s1, s2});
                         });
  if (corners_.empty()) return;
  by_facet_ = make_id_lists(
      [&](const auto& emit) {
        for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(corners_.size()); ++k)
          for (const std::uint32_t s : {corners_[k].s1, corners_[k].s2})
            for (const std::uint32_t f : state.segments[s].facets) emit(f, k);
      },
      true);
  input_facets_ = facets_at_segment_ends(state);
}

bool NarrowCorners::in_corner_zone(std::uint32_t x) const {
  if (corners_.empty()) return false;
  const VertexInfo& info = state_.vertices[x];
  const Vec3& p = state_.mesh.point(x);
  const double floor = termination_floor_of(state_, x);
  auto on_arm = [&](std::uint32_t s) {
    const SegmentData& seg = state_.segments[s];
    return (info.kind == VertexKind::OnSegment && info.owner == s) || x == seg.a || x == seg.b;
  };
  for (const std::uint32_t f : facets_of_vertex(state_, input_facets_, x)) {
    for (const std::uint32_t k : by_facet_.of(f)) {
      const Corner& c = corners_[k];
      if (on_arm(c.s1) || on_arm(c.s2)) continue;
      if (distance_to_segment(state_, p, c.s1) <= floor && distance_to_segment(state_, p, c.s2) <= floor) return true;
    }
  }
  return false;
}

std::vector<std::uint8_t> small_angle_vertices(const RefineState& state) {
  const SharpWedges wedges(state);
  const NarrowCorners corners(state);
  std::vector<std::uint8_t> at_small_angle(state.mesh.num_vertices(), 0);
  for (std::uint32_t x = 0; x < at_small_angle.size(); ++x) {
    if (x == kInfiniteVertex || state.vertices[x].kind == VertexKind::Unused) continue;
    if (vertex_at_small_angle(state, x))
      at_small_angle[x] = 1;
    else if (wedges.in_wedge_zone(x) || corners.in_corner_zone(x))
      at_small_angle[x] = 2;
  }
  return at_small_angle;
}

std::vector<std::uint8_t> small_angle_tets(const RefineState& state) {
  std::vector<std::uint8_t> mask(state.mesh.tet_slots(), 0);
  // Asked four times per tet: once per vertex here, into a byte per vertex (1: rules
  // (a), (b), (d); 2: rules (c), (e)); rule (f), a property of the tet, only for tets
  // none of whose vertices is marked and one of which lies near a sharp wedge.
  const std::vector<std::uint8_t> at_small_angle = small_angle_vertices(state);
  const SharpWedges wedges(state);
  std::vector<bool> near_wedge(at_small_angle.size(), false);
  for (std::uint32_t x = 0; x < at_small_angle.size(); ++x)
    if (x != kInfiniteVertex && at_small_angle[x] == 0 && state.vertices[x].kind != VertexKind::Unused)
      near_wedge[x] = wedges.near_wedge(x);
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
    std::uint8_t flag = 0;
    bool near = false;
    for (const std::uint32_t x : state.mesh.tet(t).v) {
      if (at_small_angle[x] != 0 && (flag == 0 || at_small_angle[x] < flag)) flag = at_small_angle[x];
      near = near || near_wedge[x];
    }
    if (flag == 0 && near && wedges.across_wedge(state.mesh.tet(t).v)) flag = 2;
    mask[t] = flag;
  }
  return mask;
}

}  // namespace delmesh::tet3d
