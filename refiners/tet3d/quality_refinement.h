// Quality refinement of the marked domain (notes §4.2.1, §4.2.3, §3.8): skinny tets
// (circumradius-to-shortest-edge ratio above B) and tets above a volume bound (global,
// per region, or a sizing callback at the circumcenter) are split at their
// circumcenters, worst first. Priorities and rejection rules of §4.2.1: encroached
// subsegments first, then encroached subfacets, then tets; a tet circumcenter that
// encroaches subsegments is rejected and those are split; one that encroaches a
// subfacet is rejected and the subfacet whose prism holds it (Projection Lemma), if it
// encroaches that one too, else the encroached subfacet itself, is split at its
// circumcenter, unless that circumcenter encroaches subsegments, which are split
// instead; when it projects outside the facet, the subsegment between is split if it
// encroaches that one (boundary_recovery.h), else the encroached subfacet itself. (The
// Projection Lemma promises an encroached subsegment between, but only for a facet whose
// subsegments are all unencroached, which the floors do not keep; leaving such tets as
// they were made 310 of the 591 tets left above 1.414 on pocc-eight-cyl.stp.) The tet is then
// looked at afresh: subfacets that appeared meanwhile are not split for the rejected
// circumcenter. When the floor refuses every split on the encroached subfacet's behalf
// (its circumcenter too close to a vertex, or encroaching a subsegment too short to
// split: the arms of a narrow corner, a thin wedge), the tet's circumcenter itself is
// inserted if it lies in the tet's region, at least the floor off the subfacet's plane
// (a thinner tet on the subfacet could not be repaired: its splits are below the floor;
// without this condition gmsh-part.step with the window [20, 150] had 5 tets outside it
// away from small angles instead of 2), and its cavity deletes no subfacet: it
// encroaches no subsegment, so it deletes none, and the subfacet stays encroached as the
// floors leave others. Leaving such tets made the 5 tets above 1.414 away from small
// input angles on cgal-boeing.off (needle fans with 2.2 degree corners; 2 now) and the 8
// on cgal-dino.off (2 now).
// When the circumcenter is refused there (within a floor of the subfacet's plane, outside
// the tet's region, or deleting a subfacet), or lies outside the tet's region with nothing
// split for it, the tet is split at another point of its circumsphere (split_inside): the
// first of a few points on the segments from the circumcenter to the tet's centroid and
// to each of its vertices that lies in the tet's region, encroaches no subsegment, lies
// at least the floor off the plane of every subfacet it encroaches, deletes no subfacet
// and has an insertion radius of at least the floor (tets above 1.414 away from small
// angles: occt-tr12j 26 -> 10, occt-propeller 13 -> 5, cgal-couplingdown 11 -> 4), then of
// points toward 26 fixed directions of the circumsphere (occt-sh2 9 -> 1); when none
// qualifies but one in the tet's region, clear of its vertices and deleting no subfacet
// encroaches subsegments, those are split, floor permitting, as for the circumcenter
// (cgal-homer 2 -> 0, cgal-anchor 1 -> 0). A circumcenter
// whose cavity holds a vertex nearer than the floor (its circumsphere not empty) goes to
// split_inside too (cgal-couplingdown 4 -> 0 with both).
//
// Termination for any input (the Quitter's idea, §3.8, carried to 3D)
//   Every vertex v carries a floor f(v) > 0. An input vertex's floor is kFloorFactor
//   times its local feature size, its distance to the nearest input vertex, segment or
//   facet that does not contain it (feature_size.h; positive in a valid PLC, else the
//   nearest vertex is taken); in this stage a Steiner vertex
//   p created for an element (tet, subfacet, subsegment) gets the larger of the smallest
//   floor among the element's vertices and min over its cavity's vertices w of
//   f(w) + kFloorSlope |p - w|, capped by the largest f(w) (termination_floor.h): a
//   Lipschitz floor field, so a small floor stays near the input feature that set it
//   instead of spreading over whole facets through chains of splits; a vertex put on a
//   segment beside a narrower part of its facet takes at most kFloorFactor times its
//   distance to the segments of the facet that share no vertex with its own
//   (narrow_facet_floor.h), at least kFloorFactor d_min, d_min > 0 the smallest distance
//   between two such segments.
//   A skinny tet t with floor f(t) = min over its vertices is split (or
//   has subfacets/subsegments split on its behalf) only if the new vertex's insertion
//   radius (its distance to the nearest vertex: the circumradius for a tet, the nearest
//   cavity vertex for a subfacet circumcenter, half the subsegment for a midpoint) is at
//   least f(t); otherwise t is left as it is and counted as unmet. The same floor governs
//   subsegments and subfacets that are present but encroached (boundary_recovery.h):
//   they are split only above the floor of their vertices and the encroaching vertex.
//   Only MISSING subsegments and subfacets are split unconditionally, since the mesh
//   must conform; a vertex inserted for quality encroaches nothing (it was checked), so
//   it deletes no subsegment or subfacet, and missing elements arise only from
//   boundary splits, which are themselves floored; a circumcenter inserted for a tet whose
//   encroached subfacet could not be split (above) deletes none, and its insertion radius
//   (the distance to the nearest vertex of its cavity, checked: the circumradius while the
//   circumsphere is empty) is at least the floor; a point split_inside inserts instead deletes
//   none either, and its insertion radius is checked against the floor; the subsegments it
//   splits for a point that encroaches them are floored like the circumcenter's. Every floor is at least f_min, the
//   smaller of the smallest input floor and kFloorFactor d_min, so every vertex inserted after recovery either respects a
//   floor (>= f_min, away from all earlier vertices) or restores a missing element
//   created by such a vertex; a bounded domain holds finitely many points f_min apart
//   (a packing argument). Without encroached subfacets a circumcenter outside
//   its tet's region always encroaches one (§4.2.1); since floors may leave subfacets
//   encroached, the circumcenter is located first (a cheap walk) and, if it falls
//   outside the tet's region, a subfacet face of the tet that the circumcenter
//   encroaches is split (floored); failing that, a subfacet face of the tet whose own
//   circumcenter lies inside the tet's circumsphere is split (floored): the
//   insertion deletes the tet. These are the nearly flat tets on a planar facet with all
//   four vertices on its boundary (the cocircular vertices of a cylinder's cap), whose
//   circumcenter lies far off the facet, beyond every equatorial sphere (136 of the 591
//   tets left above 1.414 on pocc-eight-cyl.stp were such). Any other tet whose
//   circumcenter lies outside is left unmet; a subfacet is never split for a point that
//   neither encroaches it nor kills the tet. Every vertex these rules add respects a
//   floor, so the packing argument above covers them. Where no small input angle exists the insertion
//   radii of §4.2.3 do not approach the floors and the bound B is met; near a small
//   angle the cycle of ever-shorter edges (§3.8, Figure 3.34) is cut at the floor.
//   Tets above a volume bound need no floor: their circumradius is bounded below by the
//   bound itself. The vertices split for them have no element floor (0) but still get
//   the field term above, at least f_min, so they never hand a zero floor to later
//   skinny-tet splits (a zero floor, inherited, switched the rule off: TetGen's
//   example.poly with its region volume bounds at B 1.414 then inserted 261000
//   subfacet points about 1e-6 apart without end).
//   Tets bad only by their dihedral angles (a dihedral window, MeshOptions::
//   min_dihedral_deg / max_dihedral_deg) are split like skinny tets, after them, but
//   §4.4 knows no termination guarantee for that: on faceted surfaces a sliver split can
//   breed new slivers for as long as the floors allow. So a sliver is split only under
//   three rules: its circumradius is at least its floor f(t), as for a skinny tet; its
//   circumcenter encroaches no subsegment or subfacet and lies in its region (else it is
//   left: no boundary element is ever split for a sliver); and a budget of
//   kSliverSplitsPerVertex times the vertices present when this stage starts is not
//   spent (sliver_improvement.h). The sliver splits are therefore finitely many, a
//   fixed fraction of the mesh, on any input, and the argument above covers every other
//   vertex; slivers left are the improvement pass's (improvement_schedule.h bounds its
//   work).
//   The packing bound can be astronomically large (f_min tiny next to the domain), and
//   a sizing callback may ask for ever smaller tets; so the stage also stops at an
//   automatic bound on its Steiner points, proportional to the recovered mesh and the
//   demand of the volume bounds (quality_bound.h): a valid mesh flagged Partial. A
//   Steiner budget (MeshOptions::max_steiner_points) stops it earlier when given.
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

struct QualityOutcome {
  /// The Steiner budget ran out: MeshOptions::max_steiner_points or the automatic bound.
  bool budget_exhausted = false;
  /// The automatic bound of quality_bound.h was reached.
  bool bound_reached = false;
};

/// Refines the marked domain. Requires mark_domain and an empty conformity queue.
Expected<QualityOutcome> refine_quality(RefineState& state, std::size_t input_vertices);

/// Radius-edge ratio bound in effect for tet t (the options' bound, or the per-tet level
/// of the §4.3 interior strategy: interior_strategy.h).
double radius_edge_bound(const RefineState& state, std::uint32_t t);

}  // namespace delmesh::tet3d
