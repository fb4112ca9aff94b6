// Tets bearing a small input angle (see angle_bearing.h; notes §3.8).
#include "refiners/tet3d/angle_bearing.h"

#include <cmath>
#include <algorithm>
#include <limits>
#include <numbers>

namespace delmesh::tet3d {

bool bears_small_angle(const RefineState& state, std::uint32_t t, double radius_edge) {
  const TetMesh& mesh = state.mesh;
  const auto& v = mesh.tet(t).v;
  int bi = 0, bj = 1;
  double shortest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      const double d = (mesh.point(v[i]) - mesh.point(v[j])).squaredNorm();
      if (d < shortest) {
        shortest = d;
        bi = i;
        bj = j;
      }
    }
  }
  const VertexInfo& x = state.vertices[v[bi]];
  const VertexInfo& y = state.vertices[v[bj]];
  if (x.kind != VertexKind::OnSegment || y.kind != VertexKind::OnSegment || x.owner == y.owner) return false;
  const SegmentData& s1 = state.segments[x.owner];
  const SegmentData& s2 = state.segments[y.owner];
  std::uint32_t apex = kNone;
  if (s1.a == s2.a || s1.a == s2.b) {
    apex = s1.a;
  } else if (s1.b == s2.a || s1.b == s2.b) {
    apex = s1.b;
  }
  if (apex == kNone || mesh.local_index(t, apex) < 0) return false;
  const Vec3& a = mesh.point(apex);
  const Vec3 d1 = mesh.point(v[bi]) - a, d2 = mesh.point(v[bj]) - a;
  const double n1 = d1.norm(), n2 = d2.norm();
  if (!(n1 > 0.0 && n2 > 0.0)) return false;
  // alpha below 90 degrees with sin alpha < kBearingMargin / (2 B).
  const double cos_alpha = d1.dot(d2) / (n1 * n2);
  const double sin_alpha = d1.cross(d2).norm() / (n1 * n2);
  return cos_alpha > 0.0 && 2.0 * radius_edge * sin_alpha < kBearingMargin;
}

double tessellation_min_angle_deg(double radius_edge) {
  constexpr double kImporterDefaultDeg = 20.0;
  if (!(radius_edge > 0.0)) return kImporterDefaultDeg;
  const double sine = kBearingMargin / (2.0 * radius_edge);
  if (!(sine < 1.0)) return 30.0;
  return std::clamp(std::ceil(std::asin(sine) * 180.0 / std::numbers::pi), kImporterDefaultDeg, 30.0);
}

}  // namespace delmesh::tet3d
