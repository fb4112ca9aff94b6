// Topology and Delaunay validators (see validate.h).
#include "toolkit/mesh2d/validate.h"

#include "toolkit/predicates/predicates.h"

namespace delmesh::mesh2d {

namespace {

std::string tri_name(std::uint32_t t) { return "triangle " + std::to_string(t); }

}  // namespace

std::vector<std::string> check_topology(const Triangulation& tri) {
  std::vector<std::string> issues;
  const std::uint32_t n = tri.num_slots();
  if (tri.tv.size() != 3u * n || tri.tn.size() != 3u * n) {
    issues.push_back("array sizes disagree");
    return issues;
  }
  for (std::uint32_t t = 0; t < n && issues.size() < 100; ++t) {
    if (!tri.alive(t)) continue;
    int ghosts = 0;
    bool ids_ok = true;
    for (std::uint32_t i = 0; i < 3; ++i) {
      const std::uint32_t v = tri.tv[3 * t + i];
      if (v == kGhost) {
        ++ghosts;
      } else if (v >= tri.points.size()) {
        issues.push_back(tri_name(t) + ": vertex id out of range");
        ids_ok = false;
      }
    }
    if (ghosts != (tri.ghost(t) ? 1 : 0)) issues.push_back(tri_name(t) + ": ghost flag/vertex mismatch");
    if (ghosts == 0 && ids_ok) {
      const auto& P = tri.points;
      if (predicates::orient2d(P[tri.tv[3 * t]].data(), P[tri.tv[3 * t + 1]].data(),
                               P[tri.tv[3 * t + 2]].data()) != Sign::Positive)
        issues.push_back(tri_name(t) + ": not counterclockwise");
    }
    for (std::uint32_t i = 0; i < 3; ++i) {
      const std::uint32_t ref = tri.tn[3 * t + i];
      if (ref >= 3u * n) {
        issues.push_back(tri_name(t) + ": neighbour out of range");
        continue;
      }
      const std::uint32_t u = ref / 3, j = ref % 3;
      if (!tri.alive(u)) issues.push_back(tri_name(t) + ": neighbour is dead");
      if (tri.tn[ref] != 3 * t + i) issues.push_back(tri_name(t) + ": neighbour link not mutual");
      if (tri.org(t, i) != tri.dest(u, j) || tri.dest(t, i) != tri.org(u, j))
        issues.push_back(tri_name(t) + ": shared edge endpoints differ");
      if (tri.subseg(t, i) != tri.subseg(u, j))
        issues.push_back(tri_name(t) + ": subsegment mark on one side only");
    }
  }
  for (std::size_t v = 0; v < tri.vt.size() && issues.size() < 100; ++v) {
    const std::uint32_t t = tri.vt[v];
    if (t == kNone) continue;
    if (t >= n || !tri.alive(t) ||
        (tri.tv[3 * t] != v && tri.tv[3 * t + 1] != v && tri.tv[3 * t + 2] != v))
      issues.push_back("vertex " + std::to_string(v) + ": vertex-to-triangle map is stale");
  }
  return issues;
}

std::vector<std::string> check_delaunay(const Triangulation& tri) {
  std::vector<std::string> issues;
  const auto& P = tri.points;
  for (std::uint32_t t = 0; t < tri.num_slots() && issues.size() < 100; ++t) {
    if (!tri.in_domain(t)) continue;
    for (std::uint32_t i = 0; i < 3; ++i) {
      if (tri.subseg(t, i)) continue;
      const std::uint32_t ref = tri.tn[3 * t + i];
      const std::uint32_t u = ref / 3;
      if (!tri.in_domain(u)) continue;
      const std::uint32_t a = tri.tv[3 * t], b = tri.tv[3 * t + 1], c = tri.tv[3 * t + 2];
      const std::uint32_t d = tri.tv[ref];
      if (predicates::incircle_sos(P[a].data(), P[b].data(), P[c].data(), P[d].data(), a, b, c,
                                   d) == Sign::Positive)
        issues.push_back(tri_name(t) + ": edge " + std::to_string(i) + " is not locally Delaunay");
    }
  }
  return issues;
}

}  // namespace delmesh::mesh2d
