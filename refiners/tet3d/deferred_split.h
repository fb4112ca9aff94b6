// Subsegment splits judged after the polish that follows them, undone where the mesh left
// is worse: a compound improvement operation (notes §2.2.4 and the end of §4.4: a vertex
// inserted where it helps, then smoothing; Klingner and Shewchuk, "Aggressive tetrahedral
// mesh improvement", 2007, judge a compound operation by the mesh it leaves).
//
// The insertions on subsegments (subsegment_insertion.h) judge a split by its new tets
// against its cavity's. Where the split keeps the subsegment's ring (its vertices lie on
// segments parallel to it or on facets holding it, so the halves keep the angle at the
// subsegment) or a cap in a fold, every point of the subsegment makes more tets outside
// the window than the cavity had (on cgal-boeing, cgal-couplingdown and cgal-homer with
// [20, 150]: 1 -> 1 to 8 outside, 0 to 9 more above radius-edge 2), and no smoothing of
// the old vertices can change those angles (docs/MESHING.md, "Joint moves with a
// neighbour, and walls of any rule (polish)"). The split changes which vertices surround
// the subsegment, and the polish round after it smooths the new vertex along its segment
// and its neighbours, which the polish's rules then let repair the new tets.
//
// So, once the insertion rounds have ended (improvement_rounds.h) with tets outside the
// window away from small input angles: the state is copied (state_snapshot.h), each such
// tet gets a split on a subsegment around it, at the point of the line search with the
// best worst new tet among the points every consistency check of the insertion passes
// (SubsegmentJudgement::AfterPolish), then the polish runs once (the polish alone, as
// after the insertion rounds). The result is judged over the in-domain tets of the whole
// mesh against the state before the trial and against what the polish alone leaves from
// the same copy (its own trades move the counts at small angles and above the bounds: on
// cgal-boeing one more run of it takes the tets outside at small angles from 1661 to 1647
// and those above radius-edge 2 from 4252 to 4280, with or without the splits). It is
// kept only if fewer tets lie outside the window away from small angles
// (small_angle_tets, as the end-of-run accounting counts them) than before and than the
// polish alone leaves, no more lie outside it at small angles and no more break the
// radius-edge or volume bounds than the polish alone leaves, and the smallest and largest
// dihedral angles do not widen; otherwise the copy is put back and the run goes on as if
// nothing had been tried. The log follows the result (RefineState::log_hold,
// toolkit/core/holding_log_sink.h): the lines of the splits and the polish after them go
// out only when the trial is kept, never those of the polish alone, and an undone trial
// leaves one line with its splits and counts. At most kDeferredSplitRounds such trials,
// while they are kept.
// The splits keep every check of the insertions on subsegments (orientation by exact
// orient3d, the facets' subfacets and the segment's id on both halves, the encroachment
// and termination-floor checks), so the mesh stays valid. With [20, 150] the tets outside
// away from small angles go from 4 to 0 on cgal-boeing (two trials), 2 to 0 on
// cgal-couplingdown and 1 to 0 on cgal-homer (docs/MESHING.md, "Subsegment splits judged
// after the polish (polish)"); the copy holds a second state while a trial runs
// (peak RSS cgal-boeing 31.7 -> 50.5 MB, cgal-homer 53.2 -> 93.9 MB).
#pragma once

#include <cstddef>
#include <optional>

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/sliver_improvement.h"

namespace delmesh::tet3d {

/// Most trials of deferred splits after the insertion rounds.
inline constexpr int kDeferredSplitRounds = 2;

/// One trial (see above): the subsegment splits at the tets outside the window away from
/// small angles, then improve_slivers(state, polish); the polish's stats when the result
/// is kept, nothing when no split was made or the state was put back as it was.
std::optional<ImprovementStats> split_then_polish(RefineState& state, const ImprovementTarget& polish);

}  // namespace delmesh::tet3d
