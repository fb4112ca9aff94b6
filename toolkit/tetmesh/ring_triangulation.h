// Max-min triangulation of the ring of vertices around an edge, by dynamic programming.
//
// Edge removal (notes §2.2.4 on topological transformations; Shewchuk, "Two discrete
// optimization algorithms for the topological improvement of tetrahedral meshes", 2002)
// replaces the tets around an edge ab by the tets joining each triangle of a
// triangulation of the ring around ab to a and to b. The best ring triangulation, the one
// whose worst triangle (scored by the worse of its two tets) is best, is found over all
// triangulations of the polygon ring[0..m-1] by Klincsek's dynamic programming (1980) in
// O(m^3) time: best(i, j) = max over i < k < j of min(best(i, k), best(k, j),
// quality(i, k, j)).
//
// Used by toolkit/tetmesh remove_edge (whole rings) and by refiners/tet3d
// facet_edge_flip (each side of a facet's edge).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace delmesh {

/// Triangulates the polygon with vertices 0..m-1 (its edges are (i, i+1) and (0, m-1);
/// for m < 3 there is no triangle and the result is +infinity) so that the worst
/// `triangle_quality(i, k, j)` (called with i < k < j; -infinity marks an invalid
/// triangle) is largest. Appends the triangles
/// (i, k, j) to `triangles` and returns that worst quality when it exceeds `must_exceed`;
/// otherwise returns -infinity and appends nothing. A split k is evaluated only if its
/// two sub-polygons could still beat both the best so far and must_exceed, so the
/// callback may return any value at most must_exceed for a triangle it finds too poor.
template <typename TriangleQuality>
double best_ring_triangulation(int m, double must_exceed, TriangleQuality&& triangle_quality,
                               std::vector<std::array<int, 3>>& triangles) {
  constexpr double kInvalid = -std::numeric_limits<double>::infinity();
  std::vector<double> best(static_cast<std::size_t>(m * m), std::numeric_limits<double>::infinity());
  std::vector<int> split(static_cast<std::size_t>(m * m), -1);
  auto at = [m](int i, int j) { return static_cast<std::size_t>(i * m + j); };
  for (int len = 2; len < m; ++len) {
    for (int i = 0; i + len < m; ++i) {
      const int j = i + len;
      double value = kInvalid;
      for (int k = i + 1; k < j; ++k) {
        const double sub = std::min(best[at(i, k)], best[at(k, j)]);
        if (!(sub > value) || !(sub > must_exceed)) continue;
        const double q = std::min(sub, triangle_quality(i, k, j));
        if (q > value) {
          value = q;
          split[at(i, j)] = k;
        }
      }
      best[at(i, j)] = value;
    }
  }
  const double result = best[at(0, m - 1)];
  if (result == kInvalid || !(result > must_exceed)) return kInvalid;
  std::vector<std::pair<int, int>> todo{{0, m - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j - i < 2) continue;
    const int k = split[at(i, j)];
    triangles.push_back({i, k, j});
    todo.push_back({i, k});
    todo.push_back({k, j});
  }
  return result;
}

}  // namespace delmesh
