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

/// Frees what nothing after refinement reads: the subsegment and subfacet lookup tables,
/// the queues and the cavity scratch. The driver calls it before classifying the tets at
/// small angles (small_angles.h), whose per-vertex and per-facet structures would
/// otherwise come on top of the tables at the end of the run, when memory peaks (cgal-bear
/// at radius-edge 1.414: the two tables hold 8.5 MB there). The segments, per-vertex
/// records, facet triangulations and tets stay valid.
void release_lookup_tables(RefineState& state);

/// Fills result.mesh, result.boundary_face_facets and result.tet_at_small_angle from a
/// marked state; `small_angle` has one entry per tet slot (small_angles.h). This is the
/// state's last use: to keep the copy from adding to the peak memory, it releases the
/// facet triangulations, lookup tables, queues, per-vertex records and scratch of
/// `state` before copying the tets (only state.mesh and state.tet_region stay valid).
void extract_result(RefineState& state, const std::vector<std::uint8_t>& small_angle, MeshResult& result);

}  // namespace delmesh::tet3d
