// The floor field of the termination rule (quality_refinement.h; notes §3.8, the
// Quitter's idea carried to 3D): the floor a new vertex carries.
//
// An input vertex's floor is kFloorFactor times its local feature size, the distance to
// the nearest input feature not containing it (feature_size.h, plc_preparation.h). In the quality stage a Steiner vertex p created on behalf of
// an element (subsegment, subfacet, tet) takes the field floor
//   floor(p) = max( f_e, min( min over w of floor(w) + kFloorSlope |p - w|,  max over w of floor(w) ) ),
// w ranging over the vertices of p's cavity and f_e the smallest floor among the
// element's vertices. The first term of the min makes the floors a Lipschitz field: it
// grows with the distance from the input vertices that set small floors, so one pair of
// nearly coincident input vertices no longer hands its floor to every vertex descended
// from its neighbourhood; the second keeps the field from rising above the floors around
// p (on inputs without small features it is then the floor of the element, as before).
// (With f_e alone the smallest floor spread along chains of boundary splits over whole
// facets: on occt-tr12j.stl the median floor of the 33625 vertices within 20 units of
// one input vertex, whose own floor is 1.05, was the model's minimum 0.0043, set by an
// input pair 0.035 apart 25 units away, and quality refinement inserted points down to
// 0.02 there without the floor ever stopping it.) A vertex on a segment is then capped by
// the gap to the segments of its facet that share no vertex with its own
// (narrow_facet_floor.h, commit_insertion): along a strip facet the field grown from the
// strip's ends would otherwise rise above the strip's width. Every floor is at least the
// smaller of the smallest input floor f_min > 0 and kFloorFactor times the smallest
// distance between two segments of a facet that share no vertex (positive in a valid PLC),
// which is all the packing argument of quality_refinement.h needs.
// Boundary recovery keeps the floors of the element alone (VertexInfo::floor, from the
// nearest input vertices); both are kept per vertex and vertex_floor (boundary_split.h)
// reads the one of the running stage. A vertex inserted by recovery takes the field term
// alone as its field floor, min( field, cap ) above, at least the smallest field floor of
// its cavity's vertices: with f_e (a recovery floor, from the nearest vertex) the input
// field floors taken from the local feature size (feature_size.h) would not reach the
// vertices recovery puts on the segments and facets near them.
// With the field in recovery too, recovery leaves more encroached subsegments as they
// are, which changes which inputs it can finish (cgal-step.off then meshes, valid, with
// 44% of its tets above the bound, instead of stopping at the recovery bound): a
// separate decision, not taken here.
#pragma once

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Growth of the floor per unit of distance from the vertex that set it. Steeper slopes
/// leave more tets above the bound away from small angles; at B 1.414 with the STEP
/// tessellation of the curved faces refined (share of tets, 1/8 -> 1/32 -> 1/128 -> 1/512):
/// pocc-io1 0.273 -> 0.125 -> 0.096 -> 0.094%, gmsh-angled 0.344 -> 0.121 -> 0.078 ->
/// 0.079%, gmsh-part 6.0 -> 3.0 -> 1.6 -> 1.3%. 1/128 still ends gmsh-t106-blade.step at
/// the default options in about 6 CPU seconds and occt-tr12j.stl in about 26.
inline constexpr double kFloorSlope = 1.0 / 128.0;

/// The field floor of a vertex about to be inserted at p, whose cavity is prepared
/// (prepare_insertion); `element_floor` is f_e above.
double new_vertex_floor(const RefineState& state, const Vec3& p, double element_floor);

}  // namespace delmesh::tet3d
