// Shared helpers of the STEP importer's surface passes (refinement, node moves and node
// merges of curved CAD faces, notes §3.4 applied to each face): an order-independent key
// for the edge between two nodes, how many faces' triangulations use each edge, and the
// corner angle of a 3D triangle.
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "importers/step/surface_refinement.h"
#include "toolkit/geometry/vec3.h"

namespace delmesh::step {

/// The same key for the edges (a, b) and (b, a).
inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// For each pair of PLC vertices joined by an edge of some face's triangulation, the number
/// of faces whose triangulation has that edge (keyed by edge_key of the PLC vertices).
inline std::unordered_map<std::uint64_t, int> count_face_edges(const SurfaceMeshes& meshes) {
  std::unordered_map<std::uint64_t, int> count;
  for (const SurfaceMeshes::Face& mesh : meshes.faces) {
    std::unordered_set<std::uint64_t> edges;
    for (const auto& t : mesh.triangles) {
      for (int k = 0; k < 3; ++k) edges.insert(edge_key(mesh.node_vertex[t[k]], mesh.node_vertex[t[(k + 1) % 3]]));
    }
    for (std::uint64_t e : edges) ++count[e];
  }
  return count;
}

/// Angle (radians) at `at` of the triangle (at, p, q); 0 where it is not finite.
inline double corner_angle(const Vec3& at, const Vec3& p, const Vec3& q) {
  const Vec3 u = p - at, w = q - at;
  const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
  return std::isfinite(angle) ? angle : 0.0;
}

}  // namespace delmesh::step
