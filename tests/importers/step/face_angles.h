// Angle measures shared by the unit tests of the STEP importer's surface passes
// (surface refinement, node moves, node merges): the smallest corner of a 3D triangle
// and of a face's triangulation, in degrees, from importers/step/triangle_corners.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numbers>
#include <vector>

#include "importers/step/triangle_corners.h"

namespace delmesh::step {

/// Smallest corner of the triangle (a, b, c), degrees.
inline double min_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)}) * 180.0 / std::numbers::pi;
}

/// Smallest corner over the triangles of face f, degrees.
inline double face_min_angle_deg(const SurfaceMeshes& meshes, std::size_t f, const std::vector<Vec3>& points) {
  double smallest = 180.0;
  const auto& v = meshes.faces[f].node_vertex;
  for (const auto& t : meshes.faces[f].triangles) {
    smallest = std::min(smallest, min_angle_deg(points[v[t[0]]], points[v[t[1]]], points[v[t[2]]]));
  }
  return smallest;
}

}  // namespace delmesh::step
