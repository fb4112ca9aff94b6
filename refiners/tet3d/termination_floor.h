// The floor field of the termination rule (quality_refinement.h; notes §3.8, the
// Quitter's idea carried to 3D): the floor a new vertex carries.
//
// An input vertex's floor is kFloorFactor times its distance to the nearest other input
// vertex (plc_preparation.h). A Steiner vertex p created on behalf of an element
// (subsegment, subfacet, tet) takes
//   floor(p) = max( f_e,  min over the vertices w of p's cavity of floor(w) + kFloorSlope |p - w| ),
// f_e the smallest floor among the element's vertices. The second term makes the floor a
// Lipschitz field: it grows with the distance from the input vertices that set small
// floors, so one pair of nearly coincident input vertices no longer hands its floor to
// every vertex descended from its neighbourhood. (With f_e alone, the smallest floor
// spread along chains of boundary splits over whole facets: on occt-tr12j.stl the
// median floor of the 33625 vertices within 20 units of one input vertex was the
// model's minimum 0.0043, set by an input pair 0.035 apart 25 units away, and quality
// refinement inserted points down to 0.02 there without the floor ever stopping it.)
// Both terms are at least the smallest input floor f_min > 0, which is all the packing
// argument of quality_refinement.h needs; floors are never below what f_e alone gave.
#pragma once

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Growth of the floor per unit of distance from the vertex that set it. 1/32: with 1/8
/// the fields rose fast enough to leave more tets unmet than before on corpus inputs that
/// finished (gmsh-part.step 1223 unmet of 23967 tets against 891 of 44821 before; TetGen's
/// example.poly 3 against 0); with 1/32 no input checked leaves more than 6 more, and
/// occt-tr12j.stl and gmsh-t106-blade.step still finish.
inline constexpr double kFloorSlope = 1.0 / 32.0;

/// The floor of a vertex about to be inserted at p, whose cavity is prepared
/// (prepare_insertion); `element_floor` is f_e above.
double new_vertex_floor(const RefineState& state, const Vec3& p, double element_floor);

}  // namespace delmesh::tet3d
