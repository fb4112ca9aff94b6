// End-of-run accounting (see unmet_tets.h).
#include "refiners/tet3d/unmet_tets.h"

#include <cmath>

#include "refiners/tet3d/volume_bound.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::tet3d {

bool misses_volume_bound(const RefineState& state, int region, const Vec3& a, const Vec3& b, const Vec3& c,
                         const Vec3& d) {
  if (!any_volume_bound(state)) return false;
  const auto center = tet_circumcenter(a, b, c, d);
  const double bound = max_volume_at(state, region, center ? *center : Vec3((a + b + c + d) / 4.0));
  return bound > 0.0 && std::abs(signed_volume(a, b, c, d)) > bound;
}

void count_unmet(const RefineState& state, const std::vector<std::uint8_t>& small_angle, MeshStats& stats) {
  stats.unmet_tets = stats.unmet_tets_at_small_angles = stats.tets_at_small_angles = 0;
  stats.outside_dihedral_at_small_angles = stats.outside_dihedral_elsewhere = 0;
  const MeshOptions& options = state.options;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = state.mesh.tet(t).v;
    const Vec3 &a = state.mesh.point(v[0]), &b = state.mesh.point(v[1]), &c = state.mesh.point(v[2]),
               &d = state.mesh.point(v[3]);
    const bool small = small_angle[t] != 0;
    const bool outside = outside_dihedral_window(a, b, c, d, options.min_dihedral_deg, options.max_dihedral_deg);
    bool unmet = outside || (options.quality && !(radius_edge_ratio(a, b, c, d) <= options.max_radius_edge));
    if (!unmet) unmet = misses_volume_bound(state, state.tet_region[t], a, b, c, d);
    stats.tets_at_small_angles += small;
    if (outside) ++(small ? stats.outside_dihedral_at_small_angles : stats.outside_dihedral_elsewhere);
    if (unmet) {
      ++stats.unmet_tets;
      stats.unmet_tets_at_small_angles += small;
    }
  }
}

}  // namespace delmesh::tet3d
