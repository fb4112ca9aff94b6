// Writers for Shewchuk's Triangle output formats, so that delmesh results feed every tool
// that reads Triangle's files:
//   .node  <#points> 2 <#attributes> <1|0>, then <id> <x> <y> [attributes] [marker]
//   .ele   <#triangles> 3 <0|1>, then <id> <v1> <v2> <v3> [regional attribute]
//   .poly  0 2 0 <1|0> (the points are in the .node), then the subsegments with markers,
//          then the holes (Triangle writes its output .poly the same way)
//   .edge  <#edges> <1|0>, then <id> <v1> <v2> [marker] (markers as in triangle_mesh_edges.h)
// A PSLG can also be written as a self-contained .node or .poly (vertices, segments, holes,
// regions), the inputs of `delmesh tri`. Coordinates are written in the shortest form that
// reads back to the same double, so write -> read round trips are bit-exact. Numbering
// starts at 1 like Triangle's, or at 0 (Triangle's -z).
#pragma once

#include <filesystem>

#include "toolkit/core/error.h"
#include "toolkit/mesh2d/pslg.h"
#include "toolkit/mesh2d/triangle_mesh.h"

namespace delmesh {

struct TriangleWriteOptions {
  /// Id of the first point, triangle, segment, ...: 1 (Triangle's default) or 0 (-z).
  int first_index = 1;
  /// Write boundary markers (Triangle's -B turns them off). Point and segment markers are
  /// written only where the mesh carries them.
  bool markers = true;
};

Expected<void> write_triangle_node(const std::filesystem::path& path, const TriangleMesh& mesh,
                                   const TriangleWriteOptions& options = {});
Expected<void> write_triangle_ele(const std::filesystem::path& path, const TriangleMesh& mesh,
                                  const TriangleWriteOptions& options = {});
Expected<void> write_triangle_poly(const std::filesystem::path& path, const TriangleMesh& mesh,
                                   const TriangleWriteOptions& options = {});
Expected<void> write_triangle_edge(const std::filesystem::path& path, const TriangleMesh& mesh,
                                   const TriangleWriteOptions& options = {});

/// The points of a PSLG (with attributes and markers) as a .node file.
Expected<void> write_pslg_node(const std::filesystem::path& path, const Pslg& pslg,
                               const TriangleWriteOptions& options = {});
/// A whole PSLG as a self-contained .poly: vertices, segments, holes and regions.
Expected<void> write_pslg_poly(const std::filesystem::path& path, const Pslg& pslg,
                               const TriangleWriteOptions& options = {});

}  // namespace delmesh
