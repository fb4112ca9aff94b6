// Circumcenter constructions (see circumcenter.h). Shewchuk's formulas, "Lecture Notes
// on Geometric Robustness" §4: the center relative to vertex a,
//   triangle: ((|u|^2 v - |v|^2 u) x (u x v)) / (2 |u x v|^2),  u = b - a, v = c - a
//   tetrahedron: (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2 u.(v x w)).
#include "toolkit/geometry/circumcenter.h"

#include <cmath>

namespace delmesh {

std::optional<Vec3> triangle_circumcenter(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a;
  const Vec3 uxv = u.cross(v);
  const double denom = 2.0 * uxv.squaredNorm();
  if (denom == 0.0 || !std::isfinite(denom)) return std::nullopt;
  const Vec3 offset = (u.squaredNorm() * v - v.squaredNorm() * u).cross(uxv) / denom;
  if (!offset.allFinite()) return std::nullopt;
  return a + offset;
}

std::optional<Vec3> tet_circumcenter(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double denom = 2.0 * u.dot(v.cross(w));
  if (denom == 0.0 || !std::isfinite(denom)) return std::nullopt;
  const Vec3 offset = (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / denom;
  if (!offset.allFinite()) return std::nullopt;
  return a + offset;
}

int dominant_axis(const Vec3& normal) {
  const Vec3 m = normal.cwiseAbs();
  if (m.x() >= m.y() && m.x() >= m.z()) return 0;
  return m.y() >= m.z() ? 1 : 2;
}

}  // namespace delmesh
