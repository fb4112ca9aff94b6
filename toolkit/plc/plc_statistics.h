// PLC statistics that predict refinement trouble (notes §3.7-3.8 and §4.2: small input
// angles between segments and small dihedral angles between facets force tiny elements
// and defeat the termination guarantees), plus entity counts. Angles are measured in
// floating point: they are reported, never used for a decision.
#pragma once

#include <cstdint>

#include "toolkit/plc/plc.h"

namespace delmesh {

struct PlcStatistics {
  std::size_t vertices = 0;
  std::size_t segments = 0;  ///< distinct edges: facet polygon edges plus Plc::segments
  std::size_t facets = 0;
  std::size_t polygons = 0;
  std::size_t holes = 0;
  std::size_t regions = 0;
  /// Smallest angle (degrees) between two segments sharing a vertex; 180 if no vertex has
  /// two segments.
  double min_segment_angle_deg = 180.0;
  std::uint32_t min_angle_vertex = ~0u;
  /// Smallest dihedral angle (degrees) between two facets sharing a segment, measured
  /// between the half-planes in which each facet leaves the segment (90 at a cube edge,
  /// 180 between coplanar neighbours); 360 if no segment has two facets.
  double min_dihedral_deg = 360.0;
  std::uint32_t min_dihedral_edge[2] = {~0u, ~0u};
  std::uint32_t min_dihedral_facets[2] = {~0u, ~0u};
};

/// Counts and angles of a PLC whose vertex indices are valid (see validate_plc()).
PlcStatistics plc_statistics(const Plc& plc);

}  // namespace delmesh
