// The volume bound at a point of a region (see volume_bound.h; notes §4.2).
#include "refiners/tet3d/volume_bound.h"

#include <algorithm>

namespace delmesh::tet3d {

bool any_volume_bound(const RefineState& state) {
  return state.options.max_volume > 0.0 || !state.region_max_volume.empty() || bool(state.options.max_volume_at);
}

double max_volume_at(const RefineState& state, int region, const Vec3& center) {
  double bound = state.options.max_volume > 0.0 ? state.options.max_volume : -1.0;
  if (const auto it = state.region_max_volume.find(region); it != state.region_max_volume.end())
    bound = bound > 0.0 ? std::min(bound, it->second) : it->second;
  if (state.options.max_volume_at) {
    const double local = state.options.max_volume_at(center);
    if (local > 0.0) bound = bound > 0.0 ? std::min(bound, local) : local;
  }
  return bound;
}

}  // namespace delmesh::tet3d
