// The constrained Delaunay triangulation of one PLC facet in its projection onto a
// coordinate plane (notes §4.2.1: each facet starts as the 2D CDT of its polygons), from
// which PLC preparation (plc_preparation.h) builds the facet's FacetTriangulation: the
// general 2D CDT of refiners/tri2d, and a shortcut for a facet that is one triangle, the
// facet of every input triangle of a surface mesh, which gives the same result without
// building a 2D triangulation.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/facet/facet_triangulation.h"
#include "toolkit/plc/plc.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

/// A facet's constrained Delaunay triangulation in its projection, in tet mesh vertex ids
/// (input id + 1): its vertices in the order of their first appearance in the facet's
/// polygons, its triangles, and its subsegments (the facet's boundary and internal
/// constraints, split at collinear input vertices).
struct FacetCdt {
  std::vector<std::uint32_t> global;
  std::vector<Subface> triangles;
  std::vector<std::array<std::uint32_t, 2>> constrained;
};

/// The general case: the 2D CDT of the facet projected along `axis` (refiners/tri2d).
/// Error messages start with ": " or " " to follow the facet's name.
Expected<void> triangulate_facet(const Plc& plc, const Plc::Facet& facet, Axis axis, FacetCdt& cdt);

/// A facet that is one triangle (one polygon of three distinct vertices, no holes) whose
/// projection is not degenerate (exact orient2d): fills `cdt` exactly as
/// triangulate_facet would and returns true. False, with `cdt` untouched, for any other
/// facet.
bool lone_triangle(const Plc& plc, const Plc::Facet& facet, Axis axis, FacetCdt& cdt);

}  // namespace delmesh::tet3d
