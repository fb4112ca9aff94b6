// The automatic bound on the quality stage: the last resort that makes "never hang" hold
// by construction for any input (quality_refinement.h, docs/MESHING.md "Termination").
//
// The floors of the termination rule (termination_floor.h) bound the number of quality
// vertices by a packing argument, but that bound can be astronomically large when an
// input has a tiny feature, and tets above a volume bound (or a sizing callback that
// shrinks without limit) need no floor at all. So the quality stage also stops after
//   kBoundPerVertex * (V + D) + kBoundBase
// Steiner points, V the vertices of the recovered mesh (after boundary recovery) and D
// the demand of the volume bounds: the sum over the in-domain tets of the recovered mesh
// of volume / (volume bound at the tet's centroid), where a bound applies. When it is
// reached the result is the valid mesh refined so far, flagged Partial with its unmet
// tets counted (MeshStats::budget_exhausted and quality_bound_reached).
// Measured before the bound existed, the runs that finish at the default options use at
// most 2.4 V quality Steiner points on the corpus inputs checked (fandisk, bear, busted,
// sphere, mechanism, io1, part: 0.0 to 2.4 V), and TetGen's example.poly with its region
// volume bounds 4745 points for V = 218 and D = 12538 (a bound of 122044). At radius-edge
// 1.414 two corpus surfaces need more: cgal-couplingdown.off finishes with 163344 points
// (10.6 V, V = 15355) and occt-sh2.stl with 290183 (8.7 V); with 8 V they stopped at the
// bound with 9290 and 899 tets above it away from small angles (22 and 46 when they
// finish), so the factor is 16. On inputs that would otherwise refine for hours the bound
// ends the stage after a number of points proportional to the recovered mesh.
#pragma once

#include <cstddef>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

inline constexpr double kBoundPerVertex = 16.0;
inline constexpr double kBoundBase = 20000.0;

/// Quality-stage Steiner points allowed for the recovered, marked mesh of `state`; also
/// reported, with V and D, as an Info message on the options' log.
std::size_t quality_steiner_bound(const RefineState& state);

/// D above: the demand of the volume bounds on the current mesh (0 without bounds).
double volume_bound_demand(const RefineState& state);

}  // namespace delmesh::tet3d
