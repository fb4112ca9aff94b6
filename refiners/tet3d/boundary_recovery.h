// Boundary recovery and conformity by encroachment (notes §4.2.1): segments recovered by
// stitching (every missing or encroached subsegment split at its midpoint, on a
// concentric shell or on its narrow-corner cluster's grid: boundary_split.h), then
// facets (every missing or encroached subfacet split at its circumcenter, in
// Projection Lemma order, unless the circumcenter encroaches
// subsegments, which are split instead). A missing subfacet whose place is covered by
// tetrahedralization faces that share its circumcircle is not split: the facet
// triangulation is flipped to match (Figure 4.8). As §4.2.3 requires (Lemma 27), an
// encroached subfacet is split only for a vertex whose projection it holds: a vertex
// projecting outside the facet gets the subsegment between split instead (Projection
// Lemma), floor permitting, and a subfacet circumcenter outside the facet likewise splits
// the subsegment between (Lemma 17); the centroid is used only when no subsegment lies
// between (the circumcenter is outside by roundoff alone). In recovery an encroached
// (present) subfacet is split only when the new vertex respects both the recovery floor
// and the field floor of termination_floor.h (facets at small dihedral angles stop
// splitting each other where the field is above a tiny recovery floor).
//
// The same loop restores conformity during quality refinement: after any insertion the
// queues hold the subsegments and subfacets its cavity touched. A MISSING element is
// always split (the mesh must conform); one that is present but encroached is split only
// when the new vertex respects the termination floor (quality_refinement.h), otherwise
// it stays: it is still a face or edge of the tetrahedralization.
//
// With SegmentRecovery::StronglyDelaunay (mesh_plc.h) a present, encroached subsegment is
// split in recovery only when it is not strongly Delaunay (strong_segments.h, notes
// §2.1.4: once every subsegment is, a CDT exists and the facets are recovered as one),
// and on the CCDT (RefineState::constrained) a present subsegment or subfacet is never
// split for the vertices that encroach it: only when it is missing, or, in quality
// refinement, for a rejected point that encroaches it.
#pragma once

#include <cstdint>
#include <optional>

#include "refiners/tet3d/refine_state.h"
#include "toolkit/core/error.h"

namespace delmesh::tet3d {

/// The first subsegment of `facet` (as an edge key) crossed by the straight line, in the
/// facet's projection, from the centroid of its subfacet `from` to the projection of p;
/// nullopt when p projects into the closed facet (or the walk cannot decide). When p is
/// a vertex that encroaches `from` from outside the facet, this is the subsegment the
/// Projection Lemma says p encroaches (notes §4.2.3); when p is the circumcenter of `from`
/// lying outside the facet, it is the subsegment a vertex of `from` encroaches (Lemma 17).
std::optional<std::uint64_t> subsegment_toward(const RefineState& state, std::uint32_t facet, const FaceKey& from,
                                               const Vec3& p);

/// Figure 4.8: a missing subfacet next to a cocircular neighbour, where the
/// tetrahedralization holds the other diagonal. Flips the facet triangulation to match
/// (the change goes through apply_subface_change); true if done.
bool match_cocircular(RefineState& state, std::uint32_t facet, const FaceKey& key);

/// Splits until no queued subsegment or subfacet is missing or encroached; subsegments
/// first. With `segments_only`, subfacets stay queued. Error when the vertex cap is hit.
Expected<void> restore_conformity(RefineState& state, bool segments_only);

}  // namespace delmesh::tet3d
