// Concentric shells with a unit per apex (see concentric_shells.h; notes §3.8).
#include "refiners/tet3d/concentric_shells.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace delmesh::tet3d {

void mark_shells(RefineState& state) {
  const std::size_t n = state.mesh.num_vertices();
  std::vector<std::uint32_t> degree(n, 0);
  std::vector<double> shortest(n, std::numeric_limits<double>::infinity());
  for (const SegmentData& seg : state.segments) {
    ++degree[seg.a];
    ++degree[seg.b];
    const double length = (state.mesh.point(seg.a) - state.mesh.point(seg.b)).norm();
    shortest[seg.a] = std::min(shortest[seg.a], length);
    shortest[seg.b] = std::min(shortest[seg.b], length);
  }
  for (SegmentData& seg : state.segments) {
    seg.shell_a = degree[seg.a] >= 2;
    seg.shell_b = degree[seg.b] >= 2;
    if (std::isfinite(shortest[seg.a]) && shortest[seg.a] > 0.0) seg.shell_unit_a = shortest[seg.a];
    if (std::isfinite(shortest[seg.b]) && shortest[seg.b] > 0.0) seg.shell_unit_b = shortest[seg.b];
  }
}

double shell_split_distance(double unit, double length) {
  if (!(length > 0.0) || !(unit > 0.0)) return 0.0;
  const int k = static_cast<int>(std::lround(std::log2(0.5 * length / unit)));
  const double d = std::ldexp(unit, k);
  return d > 0.0 && d < length ? d : 0.0;
}

}  // namespace delmesh::tet3d
