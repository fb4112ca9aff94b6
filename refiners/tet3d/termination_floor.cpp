// The floor field of the termination rule (see termination_floor.h; notes §3.8).
#include "refiners/tet3d/termination_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace delmesh::tet3d {

double new_vertex_floor(const RefineState& state, const Vec3& p, double element_floor) {
  double field = std::numeric_limits<double>::infinity();
  double cap = 0.0;
  // The floor and squared distance of a vertex giving the minimum so far. Every rounded
  // step of floor + kFloorSlope sqrt(d2) is monotone, so a vertex with neither a smaller
  // floor nor a smaller d2 cannot lower the minimum: skipped without a square root (each
  // boundary vertex is met on several faces, and floors vary slowly).
  double best_floor = std::numeric_limits<double>::infinity();
  double best_d2 = std::numeric_limits<double>::infinity();
  for (const CavityFace& f : state.cavity.boundary) {
    for (const std::uint32_t w : f.v) {
      if (w == kInfiniteVertex) continue;
      const double floor = state.vertices[w].field_floor;
      cap = std::max(cap, floor);
      if (floor >= field) continue;
      const double d2 = (state.mesh.point(w) - p).squaredNorm();
      if (floor >= best_floor && d2 >= best_d2) continue;
      const double value = floor + kFloorSlope * std::sqrt(d2);
      if (value < field) {
        field = value;
        best_floor = floor;
        best_d2 = d2;
      }
    }
  }
  if (!(field < std::numeric_limits<double>::infinity())) return element_floor;
  // Boundary recovery's element floors come from the nearest input vertices (recovery
  // stays as it was); its vertices take the field alone, which is at least the smallest
  // field floor around them.
  if (!state.collect_new_tets) return std::min(field, cap);
  return std::max(element_floor, std::min(field, cap));
}

}  // namespace delmesh::tet3d
