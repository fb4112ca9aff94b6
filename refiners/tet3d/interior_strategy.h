// Per-tet radius-edge bounds for quality refinement (notes §4.3, first strategy, Figure
// 4.21): a tetrahedron not in contact with a segment or facet interior is held to B = 1, one
// with a vertex in a facet interior (and none in a segment interior) to B = √2, one with a
// vertex in a segment interior to B = 2. The guaranteed bound of §4.2.3 (B = 2) stays where
// the termination argument needs it, near the boundary, while free vertices, which beget
// no chain of shrinking insertion radii on their own (Lemma 27: C = B for a tet
// circumcenter), are held to the best bound. Each level is capped by the bound the caller
// asked for (MeshOptions::max_radius_edge), so a graded mesh meets that bound everywhere
// it can and does better in the interior. MeshOptions::interior_strategy selects it;
// InteriorStrategy::Uniform applies max_radius_edge to every tet.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "refiners/tet3d/mesh_plc.h"
#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

/// The §4.3 bound of a tet by the kinds of its vertices, before the cap.
inline constexpr double kInteriorBound = 1.0;
inline constexpr double kFacetBound = 1.4142135623730951;
inline constexpr double kSegmentBound = 2.0;

/// Radius-edge bound of tet t under the options' interior strategy.
double interior_strategy_bound(const RefineState& state, std::uint32_t t);

}  // namespace delmesh::tet3d

namespace delmesh {

/// "uniform" or "graded".
std::string_view to_string(InteriorStrategy strategy);
/// Parses "uniform" or "graded".
std::optional<InteriorStrategy> parse_interior_strategy(std::string_view name);

}  // namespace delmesh
