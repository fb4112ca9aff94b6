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
// nothing had been tried.
// Where the splits at every such tet together are refused and more than one tet was
// tried, the split at each tet alone is tried in turn, and the first one kept ends the
// trial: one split may make new tets above the radius-edge bound that the others' gains
// do not excuse (occt-tr12j with [20, 150]: the splits at its 5 tets together left 3 but
// 6 more tets above radius-edge 2 than the polish alone); once the splits together are
// refused, later trials try the tets alone only. Such a trial's polish, and the
// polish alone it is judged against, run around the tet: they start from the tets outside
// the window within kTrialPolishRings rings of the tet's vertices and the new vertex
// (ImprovementTarget::start_tets), not from every such tet of the mesh, and work on from
// the tets their steps make or change, so they read and change a neighbourhood of the
// split only. A run of the polish over the whole mesh per tet cost occt-tr12j +55% of CPU
// for its 5 tets, where thousands of tets lie outside the window at small angles for
// the polish to work on; with the polish of every trial run around its splits (the
// trials together's too), its 12 runs of the polish in trials took less CPU than the 2
// runs of the whole polish before (mesh_plc 59.4 against 61.0 s, single runs). The
// trials together keep the whole polish: its run over the whole mesh is what lowers the
// tets outside at small angles where those trials are kept (cgal-boeing 1652 -> 1633,
// cgal-couplingdown 1161 -> 1138 against the polish around the splits).
// The judgement over the whole mesh reads only the changed tets: a slot holding the same
// four vertices in the same region, none of them moved or given another record, holds a
// tet whose classes (outside the window; touching a small angle, which small_angles.h
// decides from the tet's vertices, their records and the input's segments and facets;
// above a bound) are those it had before the trial, so the
// counts after it are the counts before less the changed slots' old classes plus their
// new tets' classes, and the mesh's extreme angles stay within those before exactly when
// the changed tets' do. So a trial at one tet costs a polish around it, copies put back
// and linear scans (the changed slots, the small-angle marks), not a run of the polish
// over the whole mesh. At most kDeferredSplitRounds such trials, while they are kept.
// The log follows the result (RefineState::log_hold, toolkit/core/holding_log_sink.h): the
// lines of a trial's splits and the polish after them go out only when the trial is kept,
// never those of the polish alone it is judged against, and an undone trial leaves one
// line with its splits and counts.
// The splits keep every check of the insertions on subsegments (orientation by exact
// orient3d, the facets' subfacets and the segment's id on both halves, the encroachment
// and termination-floor checks), and the polish every check of its steps, so the mesh
// stays valid. The copy holds a second state while a trial runs (peak RSS cgal-boeing
// 31.7 -> 50.5 MB, cgal-homer 53.2 -> 93.9 MB when the trials came in).
#pragma once

#include <cstddef>
#include <optional>

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/sliver_improvement.h"

namespace delmesh::tet3d {

/// Most trials of deferred splits after the insertion rounds.
inline constexpr int kDeferredSplitRounds = 2;
/// Rings of tets around the split at one tet whose tets outside the window the polish
/// after it, and the polish alone it is judged against, start from (see above).
inline constexpr int kTrialPolishRings = 3;

/// One trial (see above): the subsegment splits at the tets outside the window away from
/// small angles, together (where `together` is true) and then, where refused, at each tet
/// alone, each followed by improve_slivers(state, polish) (around the tet for a tet
/// alone); the polish's stats when a result is kept (bad_before and bad_after counted
/// over the whole mesh), nothing when no split was made or the state was put back as it
/// was. `together` becomes false where the splits together are refused: a later trial
/// then tries the tets alone only (on occt-tr12j and occt-propeller with [20, 150] the
/// second trial's splits together were refused as the first's, two runs of the whole
/// polish each).
std::optional<ImprovementStats> split_then_polish(RefineState& state, const ImprovementTarget& polish,
                                                  bool& together);

}  // namespace delmesh::tet3d
