// Small input angles and the tets touching them (see small_angles.h).
#include "refiners/tet3d/small_angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include "refiners/tet3d/plc_preparation.h"

namespace delmesh::tet3d {

namespace {

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

}  // namespace

void classify_small_angles(RefineState& state) {
  const std::uint32_t nv = state.mesh.num_vertices();
  std::vector<std::vector<std::uint32_t>> incident(nv);
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    incident[state.segments[s].a].push_back(s);
    incident[state.segments[s].b].push_back(s);
  }
  auto other_end = [&](std::uint32_t s, std::uint32_t v) {
    const SegmentData& seg = state.segments[s];
    return state.mesh.point(seg.a == v ? seg.b : seg.a) - state.mesh.point(v);
  };
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
  for (std::uint32_t v = 1; v < nv; ++v) {
    const auto& segs = incident[v];
    for (std::size_t i = 0; i < segs.size(); ++i)
      for (std::size_t j = i + 1; j < segs.size(); ++j) {
        const double angle = angle_deg(other_end(segs[i], v), other_end(segs[j], v));
        if (angle < kSmallSegmentAngleDeg) {
          note_small_angle(segs[i], v, angle);
          note_small_angle(segs[j], v, angle);
        }
      }
  }
  // A segment and a facet at a vertex, where the segment projects into the facet.
  for (std::uint32_t f = 0; f < state.facets.size(); ++f) {
    for (const Subface& t : state.facets[f]->subfaces()) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = t[k];
        const Vec3& pv = state.mesh.point(v);
        const Vec3& pp = state.mesh.point(t[(k + 1) % 3]);
        const Vec3& pq = state.mesh.point(t[(k + 2) % 3]);
        for (const std::uint32_t s : incident[v]) {
          const auto& fs = state.segments[s].facets;
          if (std::find(fs.begin(), fs.end(), f) != fs.end()) continue;  // a segment of the facet
          const Vec3 d = other_end(s, v);
          const double angle = angle_to_plane_deg(pv, pp, pq, d);
          if (angle < kSmallSegmentFacetAngleDeg && projects_into_corner(pv, pp, pq, d)) note_small_angle(s, v, angle);
        }
      }
    }
  }
  // Two facets at a segment.
  for (SegmentData& seg : state.segments) {
    if (seg.facets.size() < 2) continue;
    const Vec3& pa = state.mesh.point(seg.a);
    const Vec3 d = (state.mesh.point(seg.b) - pa).normalized();
    std::vector<std::pair<std::uint32_t, Vec3>> wings;
    for (const std::uint32_t f : seg.facets) {
      std::uint32_t c = state.facets[f]->third_vertex(seg.a, seg.b);
      if (c == ~0u) c = state.facets[f]->third_vertex(seg.b, seg.a);
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
        seg.wedges.push_back({wings[i].first, wings[j].first, std::sin(angle * std::numbers::pi / 180.0)});
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
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    for (const SegmentData::Wedge& w : state.segments[s].wedges) {
      const auto k = static_cast<std::uint32_t>(wedges_.size());
      wedges_.push_back({s, w.f1, w.f2, w.sine});
      by_facet_[w.f1].push_back(k);
      by_facet_[w.f2].push_back(k);
    }
  }
  if (wedges_.empty()) return;
  // The facets through each input vertex at a segment's end.
  for (const SegmentData& seg : state.segments) {
    for (const std::uint32_t end : {seg.a, seg.b}) {
      auto& facets = input_facets_[end];
      for (const std::uint32_t f : seg.facets)
        if (std::find(facets.begin(), facets.end(), f) == facets.end()) facets.push_back(f);
    }
  }
}

bool SharpWedges::in_wedge_zone(std::uint32_t x) const {
  if (wedges_.empty()) return false;
  const VertexInfo& info = state_.vertices[x];
  std::span<const std::uint32_t> facets;
  if (info.kind == VertexKind::OnFacet) {
    facets = std::span<const std::uint32_t>(&info.owner, 1);
  } else if (info.kind == VertexKind::OnSegment) {
    facets = state_.segments[info.owner].facets;
  } else if (info.kind == VertexKind::Input) {
    const auto it = input_facets_.find(x);
    if (it == input_facets_.end()) return false;
    facets = it->second;
  } else {
    return false;
  }
  const Vec3& p = state_.mesh.point(x);
  const double floor = termination_floor_of(state_, x);
  for (const std::uint32_t f : facets) {
    const auto it = by_facet_.find(f);
    if (it == by_facet_.end()) continue;
    for (const std::uint32_t k : it->second) {
      const Wedge& w = wedges_[k];
      const SegmentData& seg = state_.segments[w.segment];
      const Vec3& a = state_.mesh.point(seg.a);
      const Vec3 ab = state_.mesh.point(seg.b) - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      if ((p - (a + t * ab)).norm() * w.sine <= floor) return true;
    }
  }
  return false;
}

std::vector<std::uint8_t> small_angle_tets(const RefineState& state) {
  std::vector<std::uint8_t> mask(state.mesh.tet_slots(), 0);
  const SharpWedges wedges(state);
  // Asked four times per tet: once per vertex here, into a byte per vertex (1: rules
  // (a), (b), (d); 2: rule (c)).
  std::vector<std::uint8_t> at_small_angle(state.mesh.num_vertices(), 0);
  for (std::uint32_t x = 0; x < at_small_angle.size(); ++x) {
    if (x == kInfiniteVertex) continue;
    if (vertex_at_small_angle(state, x))
      at_small_angle[x] = 1;
    else if (wedges.in_wedge_zone(x))
      at_small_angle[x] = 2;
  }
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
    std::uint8_t flag = 0;
    for (const std::uint32_t x : state.mesh.tet(t).v)
      if (at_small_angle[x] != 0 && (flag == 0 || at_small_angle[x] < flag)) flag = at_small_angle[x];
    mask[t] = flag;
  }
  return mask;
}

}  // namespace delmesh::tet3d
