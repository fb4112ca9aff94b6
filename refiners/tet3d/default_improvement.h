// Default mesh improvement after 3D Delaunay refinement (notes §2.2.4 and the end of
// §4.4): the improvement pass of sliver_improvement.h, run when no dihedral window is
// asked for, on the tets whose smallest dihedral angle is below kDefaultMinDihedralDeg.
//
// Radius-edge refinement alone bounds the circumradius-to-shortest-edge ratio, which a
// sliver (four nearly cocircular vertices) meets: a refined mesh keeps near-flat tets
// with dihedral angles of a few hundredths of a degree, whose element matrices are
// nearly singular. The pass's flips, smoothing, vertex insertion and vertex deletion
// remove most of them, under two rules of its own here:
//   - strict bounds (ImprovementTarget::strict_bounds): a step is made only if none of
//     the tets it makes breaks the radius-edge or volume bound of the options or is flat,
//     whatever the tets it removes; so the count of tets above the bounds (MeshStats::
//     unmet_tets) never grows, and a step that removes such a tet lowers it;
//   - a cheap schedule: kDefaultMaxPasses passes at most, kDefaultTriesPerBadTet tries
//     of each step per tet below the target.
// Like the pass with a window it changes no subsegment and no region and keeps every
// subfacet in its facet (its facet edge flips, facet_edge_flip.h, and the release of flat
// tets lying on a facet before and after it, flat_facet_tets.h, change a facet's
// triangulation only), so the boundary, its markers, the regions and the volume stay as
// they are; the mesh is no longer Delaunay afterwards. MeshOptions::improve (CLI --no-improve, TetGen -O0) turns
// it off.
#pragma once

#include <cstddef>

#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/sliver_improvement.h"

namespace delmesh::tet3d {

/// Tets with a dihedral angle below this many degrees are improved.
inline constexpr double kDefaultMinDihedralDeg = 10.0;
/// Most passes of the default run.
inline constexpr int kDefaultMaxPasses = 3;
/// Tries of each step over all passes, per tet below the target before the first pass.
inline constexpr std::size_t kDefaultTriesPerBadTet = 2;

/// The target of the default run.
ImprovementTarget default_improvement_target();

/// Improves the in-domain tets of a marked, refined state whose smallest dihedral angle
/// is below kDefaultMinDihedralDeg, never raising the number of tets above the bounds.
ImprovementStats improve_default(RefineState& state);

}  // namespace delmesh::tet3d
