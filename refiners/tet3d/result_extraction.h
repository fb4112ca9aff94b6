// Result extraction: the in-domain tets of the refined tetrahedralization as a
// TetraMesh (vertices renumbered densely, tets positively oriented, region ids), and
// every subfacet bordering the domain as a boundary triangle with its facet's marker,
// oriented outward where the domain lies on one side only.
#pragma once

#include "refiners/tet3d/mesh_plc.h"
#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Fills result.mesh and result.boundary_face_facets from a marked state.
void extract_result(RefineState& state, MeshResult& result);

}  // namespace delmesh::tet3d
