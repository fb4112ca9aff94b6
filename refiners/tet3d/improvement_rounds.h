// Rounds of the improvement pass with a dihedral window (notes §2.2.4 and the end of §4.4;
// Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement", 2007: repeat the
// schedule while it improves the mesh).
//
// One run of the pass (sliver_improvement.h) ends at the limits improvement_schedule.h
// sets: its passes stop when one gains little, each step has a budget of tries, and the
// polish after them (step 5) ends after kPolishRounds rounds, a round that removes no
// tet, or its budget of tries; a failed smoothing, flip, insertion or deletion is not
// retried in that run on stars that did not change (change_clock.h, and once per four
// vertices). The polish's last moves change the stars around the tets left outside the
// window after their own smoothing was tried there, so a try that failed before may
// succeed now. Later rounds run the pass again on fresh records, with no tries for the
// passes' steps (ImprovementTarget::tries_per_bad_tet 0: its first pass makes no step),
// so only its polish works, from the tets left outside the window (its one scan of the
// mesh finds them). The polish adds no tet outside the window to any star it changes, so
// a later round never ends with more such tets than it started with. Rounds stop after
// kMaxImprovementRounds runs in all or after a round that removes none.
// Measured with [20, 150] (bench_dihedral_classify --window 20 150, tets outside the
// window away from small input angles, one run -> three rounds): occt-sh2 32 -> 22,
// cgal-couplingdown 38 -> 26, cgal-homer 13 -> 12, cgal-armadillo 9 -> 8, cgal-dino 6 -> 4,
// td-slit-1 6 -> 5, trimesh-tray-bottom 4 -> 4, cgal-anchor 134 -> 103, cgal-boeing
// 73 -> 57, gmsh-netgen-hinge 63 -> 55; 378 -> 296 in all. Later rounds of the whole
// pass (with the passes' tries) left 19, 30, 10, 7, 0, 3, 4, 144, 46 and 55 (318 in all):
// their passes trade tets within a star, which on cgal-anchor raised the count away from
// small angles in every round (134, 147, 144, then 169 and 192 in a fourth and fifth),
// and on the sharp wedge of the unit tests raised the count outside the window.
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/sliver_improvement.h"

namespace delmesh::tet3d {

/// Most runs of the improvement pass with a window.
inline constexpr int kMaxImprovementRounds = 3;
/// Most rounds of insertions on subfacets and subsegments, each followed by a run of the
/// polish alone.
inline constexpr int kInsertionRounds = 2;

/// improve_slivers(state), then its polish alone on the tets left outside the window, at
/// most kMaxImprovementRounds runs in all, while a run removes at least one such tet; then
/// vertices on the subfacets of the tets left (subfacet_insertion.h), then on the
/// subsegments of those still left (subsegment_insertion.h) and, where any was inserted,
/// one more run of the polish alone around them; these insertions and run at most
/// kInsertionRounds times, while any is inserted (the polish's run changes the stars
/// around the tets left: cgal-anchor 38 -> 36 tets outside [20, 150] away from small
/// angles with a second round, no change on the other inputs of issue 6's list).
/// Then, where tets outside the window away from small angles are left, subsegment splits
/// at them judged after the polish run that follows them and undone where the mesh is
/// worse, together or, where refused, at one tet alone (deferred_split.h), at most
/// kDeferredSplitRounds times while they are kept.
/// The stats add the runs' moves, passes and tries; bad_before and bad_after_passes are the first
/// run's, bad_after the last one's. state.stage_steiner counts the vertices the rounds
/// inserted and did not delete again.
ImprovementStats improve_in_rounds(RefineState& state);

}  // namespace delmesh::tet3d
