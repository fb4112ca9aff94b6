// The floor field of the termination rule (see termination_floor.h; notes §3.8).
#include "refiners/tet3d/termination_floor.h"

#include <algorithm>
#include <limits>

namespace delmesh::tet3d {

double new_vertex_floor(const RefineState& state, const Vec3& p, double element_floor) {
  double field = std::numeric_limits<double>::infinity();
  for (const CavityFace& f : state.cavity.boundary) {
    for (const std::uint32_t w : f.v) {
      if (w == kInfiniteVertex) continue;
      field = std::min(field, state.vertices[w].floor + kFloorSlope * (state.mesh.point(w) - p).norm());
    }
  }
  if (!(field < std::numeric_limits<double>::infinity())) return element_floor;
  return std::max(element_floor, field);
}

}  // namespace delmesh::tet3d
