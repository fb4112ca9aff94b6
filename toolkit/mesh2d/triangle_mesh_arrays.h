// Consistency of a TriangleMesh's plain arrays: every per-point and per-triangle array has
// the right length and every index names an existing point. The writers check this first,
// so an inconsistent mesh built by a library user is refused with an Error instead of being
// read out of bounds.
#pragma once

#include "toolkit/core/error.h"
#include "toolkit/mesh2d/triangle_mesh.h"

namespace delmesh {

/// Error (InvalidInput, naming the first offending triangle or segment) when the arrays of
/// `mesh` do not fit together.
Expected<void> check_mesh_arrays(const TriangleMesh& mesh);

}  // namespace delmesh
