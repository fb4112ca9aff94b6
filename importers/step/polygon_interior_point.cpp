// Interior point of a simple polygon by ear search (see polygon_interior_point.h).
//
// Two-ears theorem (Meisters 1975): a simple polygon with more than three vertices has
// two non-overlapping ears. An ear at vertex i is a convex corner (prev, i, next) whose
// closed triangle contains no other vertex of the polygon; its interior then lies inside
// the polygon, so its centroid does too (verified exactly after rounding).
#include "importers/step/polygon_interior_point.h"

#include <cstddef>

namespace delmesh::step {
namespace {

Sign orient(const Vec3& a, const Vec3& b, const Vec3& c, Axis axis) {
  return predicates::orient2d_projected(a.data(), b.data(), c.data(), axis);
}

/// Exact lexicographic order of the projected coordinates (the two kept axes).
bool lex_less(const Vec3& a, const Vec3& b, Axis axis) {
  const int i = (static_cast<int>(axis) + 1) % 3;
  const int j = (static_cast<int>(axis) + 2) % 3;
  return a[i] < b[i] || (a[i] == b[i] && a[j] < b[j]);
}

/// Closed triangle (a, b, c) of orientation `s` contains p.
bool in_closed_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p, Sign s, Axis axis) {
  return orient(a, b, p, axis) != -s && orient(b, c, p, axis) != -s && orient(c, a, p, axis) != -s;
}

}  // namespace

std::optional<Vec3> polygon_interior_point(const std::vector<Vec3>& loop, Axis axis) {
  const std::size_t n = loop.size();
  if (n < 3) return std::nullopt;
  // The lexicographically smallest vertex is a convex hull vertex: the turn there gives
  // the orientation of the polygon.
  std::size_t lowest = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (lex_less(loop[i], loop[lowest], axis)) lowest = i;
  }
  const Sign orientation = orient(loop[(lowest + n - 1) % n], loop[lowest], loop[(lowest + 1) % n], axis);
  if (orientation == Sign::Zero) return std::nullopt;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (lowest + k) % n;
    const Vec3& a = loop[(i + n - 1) % n];
    const Vec3& b = loop[i];
    const Vec3& c = loop[(i + 1) % n];
    if (orient(a, b, c, axis) != orientation) continue;
    bool empty = true;
    for (std::size_t j = 0; j < n && empty; ++j) {
      if (j == i || j == (i + 1) % n || j == (i + n - 1) % n) continue;
      if (in_closed_triangle(a, b, c, loop[j], orientation, axis)) empty = false;
    }
    if (!empty) continue;
    const Vec3 centroid = (a + b + c) / 3.0;
    if (orient(a, b, centroid, axis) == orientation && orient(b, c, centroid, axis) == orientation &&
        orient(c, a, centroid, axis) == orientation) {
      return centroid;
    }
  }
  return std::nullopt;
}

}  // namespace delmesh::step
