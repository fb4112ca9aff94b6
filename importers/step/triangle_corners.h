// Shared helpers of the STEP importer's surface passes (refinement, node moves and node
// merges of curved CAD faces, notes §3.4 applied to each face): an order-independent key
// for the edge between two nodes, and the corner angle of a 3D triangle.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>

#include "toolkit/geometry/vec3.h"

namespace delmesh::step {

/// The same key for the edges (a, b) and (b, a).
inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

/// Angle (radians) at `at` of the triangle (at, p, q); 0 where it is not finite.
inline double corner_angle(const Vec3& at, const Vec3& p, const Vec3& q) {
  const Vec3 u = p - at, w = q - at;
  const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
  return std::isfinite(angle) ? angle : 0.0;
}

}  // namespace delmesh::step
