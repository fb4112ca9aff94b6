// Vertex insertion on a subsegment for the polish of the improvement pass (notes §2.2.4
// and the end of §4.4; §4.2.1 and Figure 4.5 for the subsegment split; Klingner and
// Shewchuk, "Aggressive tetrahedral mesh improvement", 2007, which insert vertices on the
// boundary too).
//
// A tet left outside the dihedral window with an edge on a segment keeps that edge
// through the pass and the insertions on subfacets (subfacet_insertion.h), whose points
// lie inside a subfacet and may not encroach a subsegment. Here, for each in-domain tet
// left outside the window that touches no small input angle (small_angles.h), each
// subsegment that is an edge of a tet around one of its vertices, has ends touching no
// small angle and crosses its circumsphere (so that a vertex there has the tet in its
// Bowyer–Watson cavity) gets a vertex tried at refinement's split point of the
// subsegment (subsegment_split_point) when that lies in the sphere, then at the points
// 1/6, ..., 5/6 of the part in the sphere, each moved along the subsegment by a line
// search (both directions, the step from an eighth of the subsegment halved up to 6
// times, at most 32 evaluations) that raises the judged worst new tet, and inserted
// through refinement's split (boundary_split.h: split_subsegment, which updates every
// facet holding the segment and keeps the segment's id on both pieces) at the best point
// met that passes every check of the would-be result, made with nothing changed:
//   - in each facet holding the segment, the split of the subfacets on the subsegment
//     gives triangles strictly counterclockwise in the facet's projection (exact
//     orient2d_projected), and the Lawson flips after it are replayed with the facet's
//     own exact test (incircle_in_plane, as subfacet_insertion.cpp does for a subfacet
//     split), which gives the subfacets the split removes in every facet;
//   - the Bowyer–Watson cavity of the point, constrained to the facets of the segment
//     (prepare_insertion with the segment as its site), holds the bad tet and every tet
//     around the subsegment, deletes exactly those subfacets and no other, keeps every
//     other subsegment as an edge of its boundary and no edge inside a facet's removed
//     region, and every finite new tet is positively oriented (exact orient3d);
//   - the point encroaches no other subsegment and no subfacet of a facet not holding the
//     segment among the cavity's, and its insertion radius is at least the least
//     termination floor of the subsegment's ends (termination_floor.h), so the split
//     keeps refinement's floors;
//   - judged as subfacet_insertion.h judges its insertions (the polish's rules: the
//     worst new tet touching no small angle beats the worst cavity tet touching none by
//     kMinSubsegmentInsertionGain, nothing touching one gets worse, no more tets outside
//     the window of either kind and no more above the radius-edge bound).
// The split is then made without the facets' own flips and the checked flips after it, so
// the facets get the subfacets the cavity was checked against. Each bad tet is tried once
// (the subsegments around it, six starting points each, each search bounded), so the work
// is bounded by the bad tets at the start. improvement_rounds.h runs it after the insertions on
// subfacets and, where either inserted, one more round of the polish, which smooths the
// new vertices' neighbours.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "refiners/tet3d/boundary_insertion.h"
#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Least gain in the worst window dihedral sine for an insertion on a subsegment (the
/// polish's kMinFlipGain, as for subfacets).
inline constexpr double kMinSubsegmentInsertionGain = 1e-4;

/// How an insertion on a subsegment is judged.
enum class SubsegmentJudgement {
  /// By the polish's rules on the new tets against the cavity's (above).
  AtInsertion,
  /// After the polish that follows it (deferred_split.h, which undoes it where the mesh
  /// left is worse): every consistent point passes (the same checks but the judgement's
  /// gain and count rules), the line search still raising the worst new tet.
  AfterPolish,
};

/// Inserts vertices on the subsegments of the in-domain tets outside the options'
/// dihedral window that touch no small input angle, where that raises the worst tet
/// around them (see above), or under `judgement`. Returns the number of vertices
/// inserted; `bad_tets`, when given, gets the vertices of such tets when it started (in
/// the order of their slots). With `only`, tries only the only-th of those tets
/// (BoundaryInserter::run).
std::size_t insert_on_subsegments(RefineState& state,
                                  SubsegmentJudgement judgement = SubsegmentJudgement::AtInsertion,
                                  std::vector<std::array<std::uint32_t, 4>>* bad_tets = nullptr,
                                  std::size_t only = BoundaryInserter::kEveryTet);

}  // namespace delmesh::tet3d
