// Triangle angles (see triangle_angles.h).
#include "toolkit/mesh2d/triangle_angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace delmesh {
namespace {

double angle_at(const Point2& apex, const Point2& p, const Point2& q) {
  const double ux = p[0] - apex[0], uy = p[1] - apex[1];
  const double vx = q[0] - apex[0], vy = q[1] - apex[1];
  const double cross = ux * vy - uy * vx;
  const double dot = ux * vx + uy * vy;
  if (cross == 0.0 && dot == 0.0) return 0.0;
  return std::atan2(std::abs(cross), dot) * (180.0 / std::numbers::pi);
}

}  // namespace

std::array<double, 3> triangle_angles_deg(const Point2& a, const Point2& b, const Point2& c) {
  return {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
}

double triangle_min_angle_deg(const Point2& a, const Point2& b, const Point2& c) {
  const auto angles = triangle_angles_deg(a, b, c);
  return std::min({angles[0], angles[1], angles[2]});
}

AngleRange mesh_angle_range(const TriangleMesh& mesh) {
  AngleRange range;
  if (mesh.triangles.empty()) return range;
  range.min_deg = 180.0;
  for (const auto& t : mesh.triangles) {
    const auto angles = triangle_angles_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    range.min_deg = std::min({range.min_deg, angles[0], angles[1], angles[2]});
    range.max_deg = std::max({range.max_deg, angles[0], angles[1], angles[2]});
  }
  return range;
}

}  // namespace delmesh
