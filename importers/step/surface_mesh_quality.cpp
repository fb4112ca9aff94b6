// Angle measures of CAD face tessellations (see surface_mesh_quality.h).
#include "importers/step/surface_mesh_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include <Eigen/Geometry>

namespace delmesh::step {

double smallest_unforced_angle_deg(const SurfaceMeshes& meshes, std::size_t face, const std::vector<Vec3>& points) {
  return smallest_unforced_angle(meshes, face, points).angle_deg;
}

UnforcedAngle smallest_unforced_angle(const SurfaceMeshes& meshes, std::size_t face, const std::vector<Vec3>& points) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> segments;
  for (const SurfaceMeshes::Edge& edge : meshes.edges) {
    for (std::size_t k = 0; k + 1 < edge.vertices.size(); ++k) {
      segments.insert(std::minmax(edge.vertices[k], edge.vertices[k + 1]));
    }
  }
  const SurfaceMeshes::Face& mesh = meshes.faces[face];
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> sides;  // local triangle sides of the face
  std::map<std::uint32_t, double> angle_sum;                      // PLC vertex -> sum of corners
  const auto corner = [&](std::uint32_t at, std::uint32_t p, std::uint32_t q) {
    const Vec3 u = points[p] - points[at];
    const Vec3 w = points[q] - points[at];
    return std::atan2(u.cross(w).norm(), u.dot(w));
  };
  for (const auto& tri : mesh.triangles) {
    const std::array<std::uint32_t, 3> v{mesh.node_vertex[tri[0]], mesh.node_vertex[tri[1]], mesh.node_vertex[tri[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int k = 0; k < 3; ++k) {
      ++sides[std::minmax(v[k], v[(k + 1) % 3])];
      angle_sum[v[k]] += corner(v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
    }
  }
  std::set<std::uint32_t> on_boundary;
  for (const auto& [side, uses] : sides) {
    if (uses != 1) continue;
    on_boundary.insert(side.first);
    on_boundary.insert(side.second);
  }
  UnforcedAngle result;
  double smallest = std::numbers::pi;
  for (const auto& tri : mesh.triangles) {
    const std::array<std::uint32_t, 3> v{mesh.node_vertex[tri[0]], mesh.node_vertex[tri[1]], mesh.node_vertex[tri[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    int at = 0;
    double corner_min = std::numbers::pi;
    for (int k = 0; k < 3; ++k) {
      const double angle = corner(v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
      if (angle < corner_min) {
        corner_min = angle;
        at = k;
      }
    }
    const bool forced = segments.count(std::minmax(v[at], v[(at + 1) % 3])) > 0 &&
                        segments.count(std::minmax(v[at], v[(at + 2) % 3])) > 0;
    if (forced) continue;
    double corner_deg = 360.0;
    for (std::uint32_t vertex : v) {
      if (on_boundary.count(vertex) > 0) corner_deg = std::min(corner_deg, angle_sum[vertex] * 180.0 / std::numbers::pi);
    }
    if (corner_deg >= kSmallFaceCornerDeg) {
      result.away_from_small_corners_deg =
          std::min(result.away_from_small_corners_deg, corner_min * 180.0 / std::numbers::pi);
    }
    if (!(corner_min < smallest)) continue;
    smallest = corner_min;
    result.corner_deg = corner_deg;
  }
  result.angle_deg = smallest * 180.0 / std::numbers::pi;
  return result;
}

std::map<std::uint32_t, double> small_face_corners(const SurfaceMeshes& meshes, std::size_t face,
                                                   const std::vector<Vec3>& points) {
  const SurfaceMeshes::Face& mesh = meshes.faces[face];
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> sides;
  std::map<std::uint32_t, double> angle_sum;
  for (const auto& tri : mesh.triangles) {
    const std::array<std::uint32_t, 3> v{mesh.node_vertex[tri[0]], mesh.node_vertex[tri[1]], mesh.node_vertex[tri[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int k = 0; k < 3; ++k) {
      ++sides[std::minmax(v[k], v[(k + 1) % 3])];
      const Vec3 u = points[v[(k + 1) % 3]] - points[v[k]];
      const Vec3 w = points[v[(k + 2) % 3]] - points[v[k]];
      angle_sum[v[k]] += std::atan2(u.cross(w).norm(), u.dot(w));
    }
  }
  std::map<std::uint32_t, double> corners;
  for (const auto& [side, uses] : sides) {
    if (uses != 1) continue;
    for (std::uint32_t vertex : {side.first, side.second}) {
      const double corner_deg = angle_sum[vertex] * 180.0 / std::numbers::pi;
      if (corner_deg < kSmallFaceCornerDeg) corners[vertex] = corner_deg;
    }
  }
  return corners;
}

}  // namespace delmesh::step
