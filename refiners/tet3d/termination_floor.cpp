// The floor field of the termination rule (see termination_floor.h; notes §3.8).
#include "refiners/tet3d/termination_floor.h"

#include <algorithm>
#include <limits>

namespace delmesh::tet3d {

double new_vertex_floor(const RefineState& state, const Vec3& p, double element_floor) {
  double field = std::numeric_limits<double>::infinity();
  double cap = 0.0;
  for (const CavityFace& f : state.cavity.boundary) {
    for (const std::uint32_t w : f.v) {
      if (w == kInfiniteVertex) continue;
      const double floor = state.vertices[w].field_floor;
      field = std::min(field, floor + kFloorSlope * (state.mesh.point(w) - p).norm());
      cap = std::max(cap, floor);
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
