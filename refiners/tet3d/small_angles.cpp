// Small input angles and the tets touching them (see small_angles.h).
#include "refiners/tet3d/small_angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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
  // Two segments at a vertex.
  for (std::uint32_t v = 1; v < nv; ++v) {
    const auto& segs = incident[v];
    for (std::size_t i = 0; i < segs.size() && !state.vertices[v].small_angle; ++i)
      for (std::size_t j = i + 1; j < segs.size(); ++j)
        if (angle_deg(other_end(segs[i], v), other_end(segs[j], v)) < kSmallSegmentAngleDeg) {
          state.vertices[v].small_angle = true;
          break;
        }
  }
  // A segment and a facet at a vertex, where the segment projects into the facet.
  for (std::uint32_t f = 0; f < state.facets.size(); ++f) {
    for (const Subface& t : state.facets[f]->subfaces()) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = t[k];
        if (state.vertices[v].small_angle) continue;
        const Vec3& pv = state.mesh.point(v);
        const Vec3& pp = state.mesh.point(t[(k + 1) % 3]);
        const Vec3& pq = state.mesh.point(t[(k + 2) % 3]);
        for (const std::uint32_t s : incident[v]) {
          const auto& fs = state.segments[s].facets;
          if (std::find(fs.begin(), fs.end(), f) != fs.end()) continue;  // a segment of the facet
          const Vec3 d = other_end(s, v);
          if (angle_to_plane_deg(pv, pp, pq, d) < kSmallSegmentFacetAngleDeg && projects_into_corner(pv, pp, pq, d)) {
            state.vertices[v].small_angle = true;
            break;
          }
        }
      }
    }
  }
  // Two facets at a segment.
  for (SegmentData& seg : state.segments) {
    if (seg.facets.size() < 2) continue;
    const Vec3& pa = state.mesh.point(seg.a);
    const Vec3 d = (state.mesh.point(seg.b) - pa).normalized();
    std::vector<Vec3> wings;
    for (const std::uint32_t f : seg.facets) {
      std::uint32_t c = state.facets[f]->third_vertex(seg.a, seg.b);
      if (c == ~0u) c = state.facets[f]->third_vertex(seg.b, seg.a);
      if (c == ~0u) continue;
      Vec3 w = state.mesh.point(c) - pa;
      w -= w.dot(d) * d;
      wings.push_back(w);
    }
    for (std::size_t i = 0; i < wings.size(); ++i)
      for (std::size_t j = i + 1; j < wings.size(); ++j)
        if (angle_deg(wings[i], wings[j]) < kSmallFacetAngleDeg) seg.small_angle = true;
    if (seg.small_angle) {
      state.vertices[seg.a].small_angle = true;
      state.vertices[seg.b].small_angle = true;
    }
  }
}

bool vertex_at_small_angle(const RefineState& state, std::uint32_t v) {
  const VertexInfo& info = state.vertices[v];
  if (info.small_angle) return true;
  return info.kind == VertexKind::OnSegment && state.segments[info.owner].small_angle;
}

std::vector<std::uint8_t> small_angle_tets(const RefineState& state) {
  std::vector<std::uint8_t> mask(state.mesh.tet_slots(), 0);
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t)) continue;
    for (const std::uint32_t v : state.mesh.tet(t).v)
      if (vertex_at_small_angle(state, v)) {
        mask[t] = 1;
        break;
      }
  }
  return mask;
}

}  // namespace delmesh::tet3d
