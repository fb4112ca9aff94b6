// The edges of a 2D triangle mesh, each listed once, with the boundary marker Triangle
// gives them in its .edge files: the marker of the subsegment the edge lies on (when the
// mesh carries segment markers), else 1 for an edge on the boundary of the triangulation,
// else 0.
#pragma once

#include <cstdint>
#include <vector>

#include "toolkit/mesh2d/triangle_mesh.h"

namespace delmesh {

struct MeshEdge {
  std::uint32_t a = 0;  ///< smaller point id
  std::uint32_t b = 0;  ///< larger point id
  int marker = 0;
  bool is_segment = false;   ///< lies on an input segment (a subsegment of the mesh)
  bool is_boundary = false;  ///< has a triangle on one side only
};

/// Every edge of the triangles of `mesh`, sorted by (a, b). Expects consistent arrays
/// (check_mesh_arrays). Segments that are not edges of any triangle are not listed.
std::vector<MeshEdge> mesh_edges(const TriangleMesh& mesh);

}  // namespace delmesh
