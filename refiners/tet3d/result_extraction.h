// Result extraction: the in-domain tets of the refined tetrahedralization as a
// TetraMesh (vertices renumbered densely, tets positively oriented, region ids), and
// every subfacet bordering the domain as a boundary triangle with its facet's marker,
// oriented outward where the domain lies on one side only.
#pragma once

#include <cstdint>
#include <vector>

#include "refiners/tet3d/mesh_plc.h"
#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Fills result.mesh, result.boundary_face_facets and result.tet_at_small_angle from a
/// marked state; `small_angle` has one entry per tet slot (small_angles.h). This is the
/// state's last use: to keep the copy from adding to the peak memory, it releases the
/// facet triangulations, lookup tables, queues, per-vertex records and scratch of
/// `state` before copying the tets (only state.mesh and state.tet_region stay valid).
void extract_result(RefineState& state, const std::vector<std::uint8_t>& small_angle, MeshResult& result);

}  // namespace delmesh::tet3d
