// PLC validation: checks that a Plc satisfies the conditions of notes §2.1.4 (planar,
// segment-bounded facets that meet only at shared segments and vertices) and the ones a
// tetrahedral mesher needs (closed boundary, region and hole points inside the domain).
// Every check is exact (toolkit/predicates); every problem is reported, with entity ids.
//
// Intersection checks: a uniform grid over facet and segment bounding boxes (box_grid.h)
// gives candidate pairs; each pair is tested exactly with segment_facet_contact() on the
// edges of one facet against the other facet and vice versa (plc_geometry.h). Two facets
// in general position intersect, if at all, in segments of their planes' common line whose
// endpoints lie on an edge of one of them, so edge-against-facet tests find every
// improper intersection, including coplanar overlaps where an edge of one facet runs
// along a diagonal of the other between two of its vertices.
//
// Points outside the domain: from a hole or region point, six axis-parallel rays (segments
// to beyond the PLC's bounding box) are tested exactly against every facet; a point from
// which some ray meets no facet at all lies in the unbounded component of space minus the
// facets and is reported. This test never reports a point that is enclosed by a closed
// boundary; it may miss points in a pocket of a non-convex domain (which the mesher's
// region marking then leaves empty).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

enum class PlcIssueKind : std::uint8_t {
  InvalidIndex,         ///< a polygon or segment names a vertex that does not exist
  NonFiniteCoordinate,  ///< NaN or infinite vertex coordinate
  DuplicateVertex,      ///< two vertices at the same position
  DegenerateSegment,    ///< segment with equal endpoints
  DegenerateFacet,      ///< no polygon, repeated vertex in a loop, collinear loop or facet
  NonPlanarFacet,       ///< a facet vertex off the facet's plane
  Intersection,         ///< facets/segments meeting other than at shared vertices/segments
  OpenBoundary,         ///< an edge on only one facet (when a closed boundary is required)
  NonManifoldEdge,      ///< an edge on three or more facets (when a manifold is required)
  FreeSegment,          ///< a segment on no facet (when free segments are not allowed)
  HoleOutside,          ///< a volume hole point outside the domain
  RegionOutside,        ///< a region point outside the domain
  Truncated,            ///< more issues than PlcValidationOptions::max_issues
};

const char* to_string(PlcIssueKind kind);

struct PlcIssue {
  PlcIssueKind kind = PlcIssueKind::InvalidIndex;
  std::string message;                  ///< names the entities and coordinates
  std::vector<std::uint32_t> vertices;  ///< ids into Plc::points
  std::vector<std::uint32_t> segments;  ///< ids into Plc::segments
  std::vector<std::uint32_t> facets;    ///< ids into Plc::facets
  std::vector<std::uint32_t> points;    ///< ids into Plc::holes or Plc::regions
};

struct PlcValidationOptions {
  /// Every facet edge must lie on at least two facets (a watertight boundary).
  bool require_closed = true;
  /// Every facet edge must lie on at most two facets (no internal facets).
  bool require_manifold = false;
  /// Segments of Plc::segments that bound no facet are allowed (volume constraints).
  bool allow_free_segments = true;
  /// Run the exact intersection checks (the costly part on large inputs).
  bool check_intersections = true;
  /// Check that hole and region points lie inside the domain.
  bool check_points_inside = true;
  /// Stop collecting after this many issues (one final Truncated issue says how many
  /// more of each kind were found).
  std::size_t max_issues = 200;
};

/// Checks the PLC; an empty result means valid. Issues come grouped by kind in the order
/// of PlcIssueKind. Never throws on bad input.
std::vector<PlcIssue> validate_plc(const Plc& plc, const PlcValidationOptions& options = {});

/// An Error summarizing validation issues (code from the first issue's kind, message
/// listing the first `max_listed` issues and the number of the others).
Error issues_to_error(const std::vector<PlcIssue>& issues, std::size_t max_listed = 10);

}  // namespace delmesh
