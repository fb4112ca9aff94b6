// Angle measures of CAD face tessellations (see surface_mesh_quality.h).
#include "importers/step/surface_mesh_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <utility>

#include <Eigen/Geometry>

namespace delmesh::step {

double smallest_unforced_angle_deg(const SurfaceMeshes& meshes, std::size_t face, const std::vector<Vec3>& points) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> segments;
  for (const SurfaceMeshes::Edge& edge : meshes.edges) {
    for (std::size_t k = 0; k + 1 < edge.vertices.size(); ++k) {
      segments.insert(std::minmax(edge.vertices[k], edge.vertices[k + 1]));
    }
  }
  const SurfaceMeshes::Face& mesh = meshes.faces[face];
  double smallest = std::numbers::pi;
  for (const auto& tri : mesh.triangles) {
    const std::array<std::uint32_t, 3> v{mesh.node_vertex[tri[0]], mesh.node_vertex[tri[1]], mesh.node_vertex[tri[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    int at = 0;
    double corner_min = std::numbers::pi;
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = points[v[(k + 1) % 3]] - points[v[k]];
      const Vec3 w = points[v[(k + 2) % 3]] - points[v[k]];
      const double corner = std::atan2(u.cross(w).norm(), u.dot(w));
      if (corner < corner_min) {
        corner_min = corner;
        at = k;
      }
    }
    const bool forced = segments.count(std::minmax(v[at], v[(at + 1) % 3])) > 0 &&
                        segments.count(std::minmax(v[at], v[(at + 2) % 3])) > 0;
    if (!forced) smallest = std::min(smallest, corner_min);
  }
  return smallest * 180.0 / std::numbers::pi;
}

}  // namespace delmesh::step
