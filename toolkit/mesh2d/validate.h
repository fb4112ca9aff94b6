// Validators for the 2D triangulation kernel: topology (neighbour links, orientation,
// ghost closure, vertex-to-triangle map) and the exact (constrained) Delaunay property
// checked edge by edge with predicates::incircle_sos (notes §2.1.1: a triangulation all
// of whose non-constrained edges are locally Delaunay is (constrained) Delaunay).
#pragma once

#include <string>
#include <vector>

#include "toolkit/mesh2d/triangulation.h"

namespace delmesh::mesh2d {

/// Every problem found, one line each; empty when the structure is consistent.
std::vector<std::string> check_topology(const Triangulation& tri);

/// Edges between two real triangles of the domain that are not locally Delaunay.
/// Subsegment edges are exempt (constrained Delaunay); ghost and outside triangles are
/// skipped.
std::vector<std::string> check_delaunay(const Triangulation& tri);

}  // namespace delmesh::mesh2d
