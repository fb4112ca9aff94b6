// The end-of-run accounting of 3D refinement (MeshStats): which in-domain tets miss a
// bound asked for and which touch a small input angle (small_angles.h), measured the way
// tet_quality_report measures the result (toolkit/quality), so that the counters agree
// with a recount on the output mesh: radius-edge ratio above the bound (quality on),
// a dihedral angle outside the window (NaN counts as outside), a volume above the volume
// bound at the circumcenter (the centroid for a tet without one).
#pragma once

#include <cstdint>
#include <vector>

#include "refiners/tet3d/mesh_plc.h"
#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Does the in-domain tet (a, b, c, d) of `region` miss a volume bound (global, per region or
/// the sizing callback, taken at its circumcenter, or its centroid without one:
/// volume_bound.h)? False at once when no volume bound applies.
bool misses_volume_bound(const RefineState& state, int region, const Vec3& a, const Vec3& b, const Vec3& c,
                         const Vec3& d);

/// Fills stats.unmet_tets, unmet_tets_at_small_angles, tets_at_small_angles,
/// outside_dihedral_at_small_angles and outside_dihedral_elsewhere from the in-domain
/// tets of a marked state; `small_angle` is small_angle_tets(state).
void count_unmet(const RefineState& state, const std::vector<std::uint8_t>& small_angle, MeshStats& stats);

}  // namespace delmesh::tet3d
