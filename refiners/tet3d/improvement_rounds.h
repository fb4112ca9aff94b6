// Rounds of the improvement pass with a dihedral window (notes §2.2.4 and the end of §4.4;
// Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement", 2007: repeat the
// schedule while it improves the mesh).
//
// One run of the pass (sliver_improvement.h) ends at the limits improvement_schedule.h
// sets: its passes stop when one gains little, each step has a budget of tries, vertex
// insertion is tried once per four vertices and a failed flip, smoothing or deletion is
// not retried on stars that did not change (change_clock.h). The polish at its end
// moves the vertices around the tets still outside the window after the last flips,
// insertions and deletions were tried there, so the steps that failed before the polish
// may succeed on the stars it left. Another run, on a fresh schedule and fresh records,
// starts from the tets left outside the window (its one scan of the mesh finds them) and
// tries them again. Rounds stop after kMaxImprovementRounds or after a round that
// removes no tet from the window's outside (a round can only gain where the one before
// changed the stars around the tets it left). A later round's passes may trade tets
// within a star as the first run's do, so a round can end with more tets outside the
// window than it started with (the sharp wedge of the unit tests: 1073 -> 1082, all but
// 2 of them at small input angles, 3 away from them before); the rounds then stop.
// Measured with [20, 150] (bench_dihedral_classify --window 20 150, tets outside the
// window away from small input angles, one run -> three rounds): occt-sh2 32 -> 19,
// cgal-couplingdown 38 -> 30, cgal-homer 13 -> 10, cgal-armadillo 9 -> 7, cgal-dino
// 6 -> 0, td-slit-1 6 -> 3, trimesh-tray-bottom 4 -> 4 (its second round removes none);
// outside the window in all 1218 -> 895, 1325 -> 1083, 456 -> 378, 118 -> 72,
// 224 -> 159, 146 -> 106 and 4 -> 4. Five rounds left occt-sh2 22, cgal-couplingdown 24,
// cgal-homer 17 (its fourth round raised the count), cgal-dino 0, td-slit-1 4,
// trimesh-tray-bottom 4; later rounds of the polish alone (no tries for the passes), in
// the order of the first list, 22, 26, 12, 8, 4, 5 and 4.
#pragma once

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/sliver_improvement.h"

namespace delmesh::tet3d {

/// Most runs of the improvement pass with a window.
inline constexpr int kMaxImprovementRounds = 3;

/// improve_slivers(state) repeated on the tets left outside the window, at most
/// kMaxImprovementRounds times, while a run removes at least one such tet. The stats
/// add the runs' moves, passes and tries; bad_before and bad_after_passes are the first
/// run's, bad_after the last one's. state.stage_steiner counts the vertices the rounds
/// inserted and did not delete again.
ImprovementStats improve_in_rounds(RefineState& state);

}  // namespace delmesh::tet3d
