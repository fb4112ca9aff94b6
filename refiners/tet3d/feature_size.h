// Local feature size of the input vertices (notes §4.2.2-4.2.3), for the
// termination floors of quality_refinement.h (plc_preparation.h, kFloorFactor).
//
// The local feature size lfs(v) of an input vertex is its distance to the nearest input
// feature (vertex, segment, facet) that does not contain it. The nearest other vertex
// bounds it from above and is what the floors used alone; it misses where two features
// come close without sharing a vertex: a vertex facing a facet of its own model across a
// thin wall or a narrow slot, a segment passing close to another. A floor taken from the
// nearest vertex is then larger than the gap, refinement across the gap stops at the
// floor, and skinny tets are left there that no small input angle explains.
//
// Measured here, for each input vertex v, the nearest segment or facet
//   * `separate`: sharing no vertex with the features containing v (its star): another
//     part of the boundary across a wall or a slot, a segment passing by;
//   * `adjacent`: not containing v. This adds the features beside v's star, a segment
//     (x, y) beside the segment (v, x), a triangle beside v's fan, which come near v only
//     through the input angle at their shared vertex: |v - x| sin(angle at x).
// plc_preparation.h takes lfs(v) = min(nearest vertex, separate, max(adjacent, nearest
// vertex / 4)): the gaps between separate parts in full; the adjacent ones only down to a
// quarter of the nearest vertex, since at small input angles the floors exist precisely
// to stop refinement, not to follow the angle down (unbounded, every long thin triangle
// of occt-tr12j.stl hands its height to the floors at its corners and the quality stage
// had not ended after 260 s, against about 30 CPU s). The vertices refinement puts on a
// segment follow the gap to the segments of its facet that share no vertex with it
// (a strip narrower than the floors: narrow_facet_floor.h).
//
// The query: a bounding-volume hierarchy over the segments and the triangles of the
// facets' triangulations (a facet is the union of its triangles), nearest primitive not
// excluded, pruned by box distance. Distances are measured in floating point: they set a
// size, no geometric sign depends on them.
#pragma once

#include <vector>

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// The lower bound on lfs taken from `adjacent`, as a share of the nearest vertex distance.
inline constexpr double kAdjacentGapShare = 0.25;

/// Per tet mesh vertex id (entries of non-input vertices: infinity), the distance from
/// each input vertex to the nearest segment or facet of either kind above (infinity
/// when there is none; 0 when one touches it, which a valid PLC does not allow).
struct FeatureGaps {
  std::vector<double> separate;
  std::vector<double> adjacent;
};

/// Per tet mesh vertex id, the distance to the nearest other vertex: its shortest edge in
/// the Delaunay tetrahedralization of the input vertices (infinity for a vertex on none).
std::vector<double> nearest_vertex_distances(const RefineState& state);

/// Needs the segments and the facet triangulations of plc_preparation.h. With `below`
/// (per tet mesh vertex id), a gap of vertex v is measured only when it is shorter than
/// below[v] and is infinity otherwise: given the nearest vertex distances,
/// floor_feature_size is the same either way (a gap at least `nearest` does not lower
/// it), and the searches, pruned from that distance on, visit fewer boxes.
FeatureGaps feature_gaps(const RefineState& state, std::size_t input_vertices,
                         const std::vector<double>* below = nullptr);

/// The local feature size used for the floors from the nearest other vertex and the gaps
/// of vertex v (above); gaps of 0 are ignored, so it is positive when `nearest` is.
double floor_feature_size(double nearest, const FeatureGaps& gaps, std::uint32_t v);

}  // namespace delmesh::tet3d
