// Floors across a facet narrower than them (see narrow_facet_floor.h).
#include "refiners/tet3d/narrow_facet_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "refiners/tet3d/plc_preparation.h"

namespace delmesh::tet3d {

namespace {

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

double segment_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 d1 = b - a, d2 = d - c, r = a - c;
  const double aa = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (!(aa > 0.0)) return point_segment_distance(a, c, d);
  if (!(e > 0.0)) return point_segment_distance(c, a, b);
  const double cc = d1.dot(r), bb = d1.dot(d2);
  const double denom = aa * e - bb * bb;
  double s = denom > 0.0 ? std::clamp((bb * f - cc * e) / denom, 0.0, 1.0) : 0.0;
  double t = (bb * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-cc / aa, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((bb - cc) / aa, 0.0, 1.0);
  }
  return ((a + s * d1) - (c + t * d2)).norm();
}

void find_narrow_partners(RefineState& state) {
  std::vector<std::vector<std::uint32_t>> of_facet(state.facets.size());
  state.narrow_partners.clear();
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    for (const std::uint32_t f : state.segments[s].facets) of_facet[f].push_back(s);
  }
  const auto point = [&state](std::uint32_t v) -> const Vec3& { return state.mesh.point(v); };
  const auto length = [&](const SegmentData& seg) { return (point(seg.b) - point(seg.a)).norm(); };
  const auto lo_x = [&](const SegmentData& seg) { return std::min(point(seg.a).x(), point(seg.b).x()); };
  const auto hi_x = [&](const SegmentData& seg) { return std::max(point(seg.a).x(), point(seg.b).x()); };
  for (std::vector<std::uint32_t>& list : of_facet) {
    if (list.size() < 4) continue;  // a triangle's edges pairwise share a vertex
    // A sweep along x: two segments within the facet's longest segment length of each
    // other overlap in x once the shorter interval is widened by that length.
    double longest = 0.0;
    for (const std::uint32_t s : list) longest = std::max(longest, length(state.segments[s]));
    std::sort(list.begin(), list.end(),
              [&](std::uint32_t x, std::uint32_t y) { return lo_x(state.segments[x]) < lo_x(state.segments[y]); });
    for (std::size_t i = 0; i < list.size(); ++i) {
      const SegmentData& s = state.segments[list[i]];
      const double reach = hi_x(s) + longest;
      for (std::size_t j = i + 1; j < list.size() && lo_x(state.segments[list[j]]) <= reach; ++j) {
        const SegmentData& q = state.segments[list[j]];
        if (s.a == q.a || s.a == q.b || s.b == q.a || s.b == q.b) continue;
        const double gap = segment_distance(point(s.a), point(s.b), point(q.a), point(q.b));
        const auto add = [&state](std::uint32_t to, std::uint32_t id) {
          std::vector<std::uint32_t>& partners = state.narrow_partners[to];
          if (std::find(partners.begin(), partners.end(), id) == partners.end()) partners.push_back(id);
        };
        if (gap < length(s)) add(list[i], list[j]);
        if (gap < length(q)) add(list[j], list[i]);
      }
    }
  }
}

double narrow_facet_floor(const RefineState& state, std::uint32_t seg, const Vec3& p) {
  double gap = std::numeric_limits<double>::infinity();
  const auto partners = state.narrow_partners.find(seg);
  if (partners == state.narrow_partners.end()) return kFloorFactor * gap;
  for (const std::uint32_t q : partners->second) {
    const SegmentData& other = state.segments[q];
    const double d = point_segment_distance(p, state.mesh.point(other.a), state.mesh.point(other.b));
    if (d > 0.0) gap = std::min(gap, d);
  }
  return kFloorFactor * gap;
}

}  // namespace delmesh::tet3d
