// The volume bound of 3D refinement at a point of a region (notes §4.2: the quality
// stage splits a tet above it like a skinny one; TetGen -a): the least of the global
// bound (MeshOptions::max_volume), the region's bound from the PLC
// (RefineState::region_max_volume) and the sizing callback's value there
// (MeshOptions::max_volume_at); a value <= 0 of any of them is no bound.
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh::tet3d {

/// Does any volume bound apply (global, per region or the sizing callback)? Without one
/// no tet is too big, and its circumcenter need not be computed for the test.
bool any_volume_bound(const RefineState& state);

/// The volume bound for a tet of `region` whose circumcenter (or the point that stands
/// for it) is `center`; <= 0: none.
double max_volume_at(const RefineState& state, int region, const Vec3& center);

}  // namespace delmesh::tet3d
