// Radius-edge polish: smoothing of the interior vertices of the tets left above the
// radius-edge bound away from small input angles (issue 5 item 9; notes §2.2.4,
// optimization-based smoothing, with the radius-edge ratio as the objective; notes §4.2
// for the bound).
//
// Quality refinement leaves a tet above the bound B where every point that would split it
// is refused by the termination floors (quality_refinement.h), and the improvement pass
// after it (default_improvement.h, improvement_rounds.h) judges tets by their dihedral
// angles, so it leaves such a tet as it is when its angles are fine. On the corpus at
// B = 1.414 most tets left this way away from small angles (small_angles.h) have an
// interior vertex whose move lifts them with nothing else in the star crossing the bound
// (cgal-boeing's two share one 0.002 above a facet): the 14 of docs/MESHING.md ("The 14,
// one by one") go to 2 (occt-tr12j 7 -> 0, occt-propeller 3 -> 2, cgal-boeing 2 -> 0,
// occt-sh2 1 -> 0, cgal-knot2 1 -> 0; "The radius-edge polish" there), with the same
// vertices and tets.
//
// For each in-domain tet above the bound touching no small angle, in tet order, each of
// its interior vertices (on no segment or facet, all of its star's tets in the tet's
// region: moving it changes no boundary, region or small-angle mark) is moved by a compass
// search: from the vertex, the 26 directions toward the neighbours of a cube's centre at a
// step of a quarter of the tet's shortest edge, the best point taken while
// one gains, the step halved where none does, at most kPolishHalvings halvings and
// kPolishSteps steps. The objective is the largest radius-edge ratio among the star's
// tets touching no small angle; a point is allowed only if
//   - every tet of the star stays positively oriented (exact orient3d);
//   - no tet of the star that meets the radius-edge bound and the volume bounds misses
//     one there (unmet_tets.h), and no tet above the radius-edge bound gets a larger
//     ratio: MeshStats::unmet_tets never grows, at small angles or away from them;
//   - no tet of the star inside the improvement's dihedral window [low, high] (the
//     options' window, or the default improvement's [10, 180]) leaves it, and no tet
//     outside it gets a smaller window dihedral sine (toolkit/quality): the tets outside
//     the window never grow in number nor get worse.
// The move is made where the objective falls by at least kPolishMinGain. Only vertex
// positions change (no tet is made or removed, so tet slots and small-angle marks stay
// valid); the mesh is no longer Delaunay where a vertex moved.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// Most steps of a compass search, and halvings of its step.
inline constexpr int kPolishSteps = 100;
inline constexpr int kPolishHalvings = 10;
/// Least fall of the objective for a move to be made.
inline constexpr double kPolishMinGain = 1e-4;

struct RadiusEdgePolishStats {
  std::size_t tets_before = 0;  ///< in-domain tets above the bound touching no small angle
  std::size_t tets_after = 0;   ///< of which still above it
  std::size_t moves = 0;        ///< vertices moved
};

/// Polishes the in-domain tets above options.max_radius_edge of a marked, refined state
/// whose entry in `small_angle` (small_angle_tets(state), one per tet slot) is 0, under the
/// dihedral window [low_deg, high_deg].
RadiusEdgePolishStats polish_radius_edge(RefineState& state, const std::vector<std::uint8_t>& small_angle,
                                         double low_deg, double high_deg);

}  // namespace delmesh::tet3d
