// A point strictly inside a simple planar polygon in 3D (a facet hole loop), found by
// ear search with exact orientation tests in the coordinate plane that drops the
// dominant axis of the polygon's normal (the caller's choice). No OCCT here.
#pragma once

#include <optional>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::step {

/// The centroid of an ear of `loop` (a simple polygon, vertices in order, either
/// orientation) that no other loop vertex touches, checked to lie strictly inside the ear
/// in the projection along `axis`. nullopt if no such ear exists (a degenerate loop).
std::optional<Vec3> polygon_interior_point(const std::vector<Vec3>& loop, Axis axis);

}  // namespace delmesh::step
