// Minimal TetGen .node reader and .node/.ele writers for point sets and their
// tetrahedralizations (TetGen 1.5 file formats: `.node` =
// "<#points> <dim=3> <#attributes> <#markers 0|1>" then "<i> <x> <y> <z> [attrs] [marker]";
// `.ele` = "<#tets> <4> <#attributes>" then "<i> <n1> <n2> <n3> <n4>"; `#` starts a
// comment). Full .poly/.smesh reading lives in the importers.
//
// Reading: points are taken bit for bit (shortest round-trip decimal parsing); attributes
// and markers are read and dropped; the first index may be 0 or 1 and indices must then
// be consecutive. Every error names file:line.
// Writing: 1-based indices (TetGen's default), coordinates in shortest round-trip form
// (re-reading gives the same doubles), no attributes, no markers.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/geometry/vec3.h"
#include "toolkit/tetmesh/tet_mesh.h"

namespace delmesh {

struct NodeFile {
  std::vector<Vec3> points;
  int first_index = 1;  ///< 0 or 1, as found in the file
};

/// Reads a 3D TetGen .node file.
Expected<NodeFile> read_node_file(const std::filesystem::path& path);

/// Writes points as a .node file, point i numbered i + 1.
Expected<void> write_node_file(const std::filesystem::path& path, std::span<const Vec3> points);

/// Writes the finite tets of `mesh` as an .ele file. Vertex v of the mesh is written as
/// index v - 1 + first_index: with the vertex numbering of delaunay_tetrahedralize
/// (vertex i + 1 = input point i) and first_index 1, the indices refer to the lines of a
/// .node file written by write_node_file.
Expected<void> write_ele_file(const std::filesystem::path& path, const TetMesh& mesh,
                              int first_index = 1);

}  // namespace delmesh
