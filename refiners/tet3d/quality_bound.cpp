// The automatic bound on the quality stage (see quality_bound.h).
#include "refiners/tet3d/quality_bound.h"

#include <cmath>
#include <cstdio>

#include "refiners/tet3d/volume_bound.h"

namespace delmesh::tet3d {

double volume_bound_demand(const RefineState& state) {
  if (!any_volume_bound(state)) return 0.0;
  double demand = 0.0;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = state.mesh.tet(t).v;
    const Vec3& p0 = state.mesh.point(v[0]);
    const Vec3& p1 = state.mesh.point(v[1]);
    const Vec3& p2 = state.mesh.point(v[2]);
    const Vec3& p3 = state.mesh.point(v[3]);
    const double bound = max_volume_at(state, state.tet_region[t], (p0 + p1 + p2 + p3) / 4.0);
    if (!(bound > 0.0)) continue;
    const double volume = std::abs((p1 - p0).dot((p2 - p0).cross(p3 - p0))) / 6.0;
    demand += volume / bound;
  }
  return demand;
}

std::size_t quality_steiner_bound(const RefineState& state) {
  const double vertices = static_cast<double>(state.mesh.num_vertices() - 1);
  const double demand = volume_bound_demand(state);
  const double bound = kBoundPerVertex * (vertices + demand) + kBoundBase;
  char line[160];
  std::snprintf(line, sizeof line, "mesh: quality stage bound %.0f Steiner points (V = %.0f, D = %.1f)", bound,
                vertices, demand);
  log(state.options.log, LogLevel::Info, line);
  // A demand beyond any mesh that fits in memory: the vertex cap decides.
  if (!(bound < 1e15)) return static_cast<std::size_t>(1e15);
  return static_cast<std::size_t>(bound);
}

}  // namespace delmesh::tet3d
