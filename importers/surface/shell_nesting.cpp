// Exact point-in-shell tests and interior points of shells (surface_importer.h, step 7).
//
// Ray parity: a segment from p to a point q far outside the shell's bounding box crosses
// the shell an odd number of times iff p is inside. Each face is fanned into triangles
// (a fan of a planar simple polygon covers each point of the polygon an odd number of
// times iff the point is inside it). A crossing counts only when it is proper: p and q
// strictly on opposite sides of the triangle's plane and the line pq strictly inside the
// triangle (three orient3d of equal sign). Any touching of an edge or vertex makes the
// ray undecided and the next of a fixed list of generic directions is tried.
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "importers/surface/surface_mesh.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::surface {
namespace {

using predicates::orient2d_projected;
using predicates::orient3d;

constexpr double kDirections[][3] = {
    {1.0, 0.3711, 0.1234},  {-0.2718, 1.0, 0.5772},  {0.1414, -0.7321, 1.0},
    {-1.0, -0.4142, 0.2236}, {0.6931, 0.1618, -1.0}, {-0.3333, -1.0, -0.7071},
};

/// Is p (lying in the plane of a, b, c) in the closed triangle abc?
bool in_closed_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  for (Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
    const Sign s = orient2d_projected(a.data(), b.data(), c.data(), axis);
    if (s == Sign::Zero) continue;
    const Sign s1 = orient2d_projected(a.data(), b.data(), p.data(), axis);
    const Sign s2 = orient2d_projected(b.data(), c.data(), p.data(), axis);
    const Sign s3 = orient2d_projected(c.data(), a.data(), p.data(), axis);
    return s1 != -s && s2 != -s && s3 != -s;
  }
  return false;  // degenerate triangle: covers no area
}

enum class Hit { Miss, Cross, Undecided };

Hit ray_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Sign sp = orient3d(a.data(), b.data(), c.data(), p.data());
  if (sp == Sign::Zero) return in_closed_triangle(a, b, c, p) ? Hit::Undecided : Hit::Miss;
  const Sign sq = orient3d(a.data(), b.data(), c.data(), q.data());
  if (sq == sp || sq == Sign::Zero) return Hit::Miss;  // q is outside the bounding box
  const Sign o1 = orient3d(p.data(), q.data(), a.data(), b.data());
  const Sign o2 = orient3d(p.data(), q.data(), b.data(), c.data());
  const Sign o3 = orient3d(p.data(), q.data(), c.data(), a.data());
  const bool has_pos = o1 == Sign::Positive || o2 == Sign::Positive || o3 == Sign::Positive;
  const bool has_neg = o1 == Sign::Negative || o2 == Sign::Negative || o3 == Sign::Negative;
  if (has_pos && has_neg) return Hit::Miss;
  if (o1 == Sign::Zero || o2 == Sign::Zero || o3 == Sign::Zero) return Hit::Undecided;
  return Hit::Cross;
}

}  // namespace

Containment point_in_shell(const PolygonSurface& surface, std::uint32_t s, const Vec3& p) {
  Vec3 lo = p, hi = p;
  for (std::size_t f = 0; f < surface.size(); ++f) {
    if (surface.shell[f] != s) continue;
    for (std::size_t k = 0; k < surface.degree(f); ++k) {
      lo = lo.cwiseMin(surface.points[surface.face(f)[k]]);
      hi = hi.cwiseMax(surface.points[surface.face(f)[k]]);
    }
  }
  const double reach = 2.0 * (hi - lo).norm() + 1.0;
  for (const auto& d : kDirections) {
    const Vec3 q = p + reach * Vec3(d[0], d[1], d[2]);
    bool undecided = false, odd = false;
    for (std::size_t f = 0; f < surface.size() && !undecided; ++f) {
      if (surface.shell[f] != s) continue;
      const std::uint32_t* v = surface.face(f);
      for (std::size_t k = 1; k + 1 < surface.degree(f); ++k) {
        const Hit hit = ray_triangle(p, q, surface.points[v[0]], surface.points[v[k]],
                                     surface.points[v[k + 1]]);
        if (hit == Hit::Undecided) {
          undecided = true;
          break;
        }
        if (hit == Hit::Cross) odd = !odd;
      }
    }
    if (!undecided) return odd ? Containment::Inside : Containment::Outside;
  }
  return Containment::Unknown;
}

std::optional<Vec3> interior_point(const PolygonSurface& surface, std::uint32_t s,
                                   const std::vector<std::uint32_t>& children) {
  std::vector<std::uint32_t> faces;
  for (std::uint32_t f = 0; f < surface.size(); ++f) {
    if (surface.shell[f] == s) faces.push_back(f);
  }
  // Try faces spread over the shell, largest first within a sample.
  const std::size_t stride = std::max<std::size_t>(1, faces.size() / 16);
  std::vector<std::uint32_t> sample;
  for (std::size_t i = 0; i < faces.size(); i += stride) sample.push_back(faces[i]);
  auto area = [&](std::uint32_t f) {
    const std::uint32_t* v = surface.face(f);
    const Vec3& a = surface.points[v[0]];
    return (surface.points[v[1]] - a).cross(surface.points[v[2]] - a).norm();
  };
  std::sort(sample.begin(), sample.end(), [&](std::uint32_t x, std::uint32_t y) { return area(x) > area(y); });
  for (std::uint32_t f : sample) {
    const std::uint32_t* v = surface.face(f);
    const Vec3& a = surface.points[v[0]];
    const Vec3& b = surface.points[v[1]];
    const Vec3& c = surface.points[v[2]];
    const Vec3 n = (b - a).cross(c - a);
    if (!(n.norm() > 0)) continue;
    const Vec3 centroid = (a + b + c) / 3.0;
    const double edge = std::min({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    for (double scale : {0.25, 0.025, 0.0025}) {
      const Vec3 p = centroid - n.normalized() * (edge * scale);
      if (point_in_shell(surface, s, p) != Containment::Inside) continue;
      bool in_child = false;
      for (std::uint32_t child : children) {
        if (point_in_shell(surface, child, p) != Containment::Outside) in_child = true;
      }
      if (!in_child) return p;
    }
  }
  return std::nullopt;
}

}  // namespace delmesh::surface
