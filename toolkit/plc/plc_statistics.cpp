// PLC angle statistics (see plc_statistics.h).
//
// Dihedral angles: for facet F and an edge (a, b) of one of its loops L, the direction in
// which F leaves the edge is d = n_L x (b - a) where n_L is L's Newell normal (the
// interior of a loop lies to the left of its edges seen from n_L); for a hole loop (a
// loop after the first in a facet that has hole points) the facet lies outside the loop
// and d is negated. The dihedral angle between two facets at the edge is the angle
// between their d vectors.
#include "toolkit/plc/plc_statistics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <vector>

namespace delmesh {
namespace {

std::uint64_t key_of(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

double angle_deg(const Vec3& u, const Vec3& v) {
  const double c = u.cross(v).norm();
  const double d = u.dot(v);
  return std::atan2(c, d) * 180.0 / std::numbers::pi;
}

Vec3 newell_normal(const std::vector<Vec3>& P, const Plc::Polygon& loop) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec3& p = P[loop[i]];
    const Vec3& q = P[loop[(i + 1) % loop.size()]];
    n += Vec3((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
              (p.x() - q.x()) * (p.y() + q.y()));
  }
  return n;
}

}  // namespace

PlcStatistics plc_statistics(const Plc& plc) {
  PlcStatistics stats;
  const auto& P = plc.points;
  stats.vertices = P.size();
  stats.facets = plc.facets.size();
  stats.holes = plc.holes.size();
  stats.regions = plc.regions.size();

  struct Side {
    std::uint64_t key;
    std::uint32_t facet;
    Vec3 direction;
  };
  std::vector<std::uint64_t> edges;
  std::vector<Side> sides;
  for (std::uint32_t f = 0; f < plc.facets.size(); ++f) {
    const auto& facet = plc.facets[f];
    for (std::size_t k = 0; k < facet.polygons.size(); ++k) {
      const auto& polygon = facet.polygons[k];
      ++stats.polygons;
      if (std::any_of(polygon.begin(), polygon.end(), [&](std::uint32_t v) { return v >= P.size(); })) {
        continue;
      }
      if (polygon.size() == 2) edges.push_back(key_of(polygon[0], polygon[1]));
      if (polygon.size() < 3) continue;
      Vec3 n = newell_normal(P, polygon);
      if (k > 0 && !facet.holes.empty()) n = -n;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const std::uint32_t a = polygon[i], b = polygon[(i + 1) % polygon.size()];
        edges.push_back(key_of(a, b));
        sides.push_back({key_of(a, b), f, n.cross(P[b] - P[a])});
      }
    }
  }
  for (const auto& s : plc.segments) edges.push_back(key_of(s.a, s.b));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  stats.segments = edges.size();

  // Smallest angle between segments at a vertex: group edge directions by vertex.
  std::vector<std::uint32_t> start(P.size() + 1, 0);
  for (std::uint64_t e : edges) {
    const auto a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
    if (a == b || a >= P.size() || b >= P.size()) continue;
    ++start[a + 1];
    ++start[b + 1];
  }
  for (std::size_t v = 0; v < P.size(); ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1), other(start.back());
  for (std::uint64_t e : edges) {
    const auto a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
    if (a == b || a >= P.size() || b >= P.size()) continue;
    other[fill[a]++] = b;
    other[fill[b]++] = a;
  }
  for (std::uint32_t v = 0; v < P.size(); ++v) {
    for (std::uint32_t i = start[v]; i < start[v + 1]; ++i) {
      for (std::uint32_t j = i + 1; j < start[v + 1]; ++j) {
        const double angle = angle_deg(P[other[i]] - P[v], P[other[j]] - P[v]);
        if (angle < stats.min_segment_angle_deg) {
          stats.min_segment_angle_deg = angle;
          stats.min_angle_vertex = v;
        }
      }
    }
  }

  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) { return x.key < y.key; });
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].key == sides[i].key) ++j;
    for (std::size_t x = i; x < j; ++x) {
      for (std::size_t y = x + 1; y < j; ++y) {
        if (sides[x].facet == sides[y].facet) continue;
        const double angle = angle_deg(sides[x].direction, sides[y].direction);
        if (angle < stats.min_dihedral_deg) {
          stats.min_dihedral_deg = angle;
          stats.min_dihedral_edge[0] = static_cast<std::uint32_t>(sides[i].key >> 32);
          stats.min_dihedral_edge[1] = static_cast<std::uint32_t>(sides[i].key);
          stats.min_dihedral_facets[0] = sides[x].facet;
          stats.min_dihedral_facets[1] = sides[y].facet;
        }
      }
    }
    i = j;
  }
  return stats;
}

}  // namespace delmesh
