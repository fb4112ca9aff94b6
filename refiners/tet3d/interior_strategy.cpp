// Per-tet radius-edge bounds of the §4.3 interior strategy (see interior_strategy.h).
#include "refiners/tet3d/interior_strategy.h"

#include <algorithm>

namespace delmesh::tet3d {

double interior_strategy_bound(const RefineState& state, std::uint32_t t) {
  const double cap = state.options.max_radius_edge;
  if (state.options.interior_strategy == InteriorStrategy::Uniform) return cap;
  bool on_segment = false, on_facet = false;
  for (const std::uint32_t v : state.mesh.tet(t).v) {
    const VertexKind kind = state.vertices[v].kind;
    on_segment = on_segment || kind == VertexKind::OnSegment;
    on_facet = on_facet || kind == VertexKind::OnFacet;
  }
  const double level = on_segment ? kSegmentBound : on_facet ? kFacetBound : kInteriorBound;
  return std::min(cap, level);
}

}  // namespace delmesh::tet3d

namespace delmesh {

std::string_view to_string(InteriorStrategy strategy) {
  switch (strategy) {
    case InteriorStrategy::Uniform:
      return "uniform";
    case InteriorStrategy::Graded:
      return "graded";
  }
  return "uniform";
}

std::optional<InteriorStrategy> parse_interior_strategy(std::string_view name) {
  if (name == "uniform") return InteriorStrategy::Uniform;
  if (name == "graded") return InteriorStrategy::Graded;
  return std::nullopt;
}

}  // namespace delmesh
