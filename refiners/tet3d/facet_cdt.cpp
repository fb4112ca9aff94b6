// The facet CDTs of facet_cdt.h: the general case through triangulate() on the projected
// polygons; a lone triangle directly, in the vertex order and subsegment order that
// triangulate() gives it.
#include "refiners/tet3d/facet_cdt.h"

#include <unordered_map>
#include <utility>

#include "refiners/tri2d/triangulate.h"
#include "toolkit/mesh2d/spatial_sort.h"

namespace delmesh::tet3d {

namespace {

Point2 project(const Vec3& p, Axis axis) {
  return predicates::project_onto_axis_plane(p.data(), axis);
}

}  // namespace

Expected<void> triangulate_facet(const Plc& plc, const Plc::Facet& facet, Axis axis, FacetCdt& cdt) {
  Pslg pslg;
  std::unordered_map<std::uint32_t, std::uint32_t> local;
  auto local_of = [&](std::uint32_t input) {
    const auto [it, fresh] = local.emplace(input, static_cast<std::uint32_t>(cdt.global.size()));
    if (fresh) {
      cdt.global.push_back(input + 1);
      pslg.points.push_back(project(plc.points[input], axis));
    }
    return it->second;
  };
  for (const auto& poly : facet.polygons) {
    if (poly.size() == 1) {
      local_of(poly[0]);
      continue;
    }
    const std::size_t m = poly.size() == 2 ? 1 : poly.size();
    for (std::size_t i = 0; i < m; ++i) {
      const std::uint32_t a = poly[i], b = poly[(i + 1) % poly.size()];
      if (a == b) continue;
      pslg.segments.push_back({local_of(a), local_of(b)});
    }
  }
  for (const Vec3& h : facet.holes) pslg.holes.push_back(project(h, axis));
  TriangulateOptions topt;
  topt.pslg = true;
  auto result = triangulate(pslg, topt);
  if (!result) return make_error(result.error().code, ": " + result.error().message);
  if (result->mesh.points.size() != pslg.points.size())
    return make_error(ErrorCode::SelfIntersection, ": its polygons cross each other");
  if (result->mesh.triangles.empty()) return make_error(ErrorCode::DegenerateInput, " has an empty interior");
  const auto& global = cdt.global;
  cdt.triangles.reserve(result->mesh.triangles.size());
  for (const auto& t : result->mesh.triangles) cdt.triangles.push_back({global[t[0]], global[t[1]], global[t[2]]});
  // Segments are edges of the CDT (possibly split at collinear input vertices: use the
  // CDT's own subsegments, which are the facet's boundary and internal constraints).
  for (const auto& s : result->mesh.segments) cdt.constrained.push_back({global[s[0]], global[s[1]]});
  return {};
}

bool lone_triangle(const Plc& plc, const Plc::Facet& facet, Axis axis, FacetCdt& cdt) {
  if (facet.polygons.size() != 1 || !facet.holes.empty()) return false;
  const Plc::Polygon& poly = facet.polygons[0];
  if (poly.size() != 3 || poly[0] == poly[1] || poly[1] == poly[2] || poly[0] == poly[2]) return false;
  const std::vector<Point2> points{project(plc.points[poly[0]], axis), project(plc.points[poly[1]], axis),
                                   project(plc.points[poly[2]], axis)};
  // triangulate()'s Delaunay construction starts from the first two points of this
  // order and the first point off their line, counterclockwise; its output lists that
  // triangle as built and its edges from the one opposite the first point.
  const std::vector<std::uint32_t> order = mesh2d::brio_hilbert_order(points);
  const Sign turn = predicates::orient2d(points[order[0]].data(), points[order[1]].data(), points[order[2]].data());
  if (turn == Sign::Zero) return false;
  const std::uint32_t a = poly[order[0]] + 1;
  std::uint32_t b = poly[order[1]] + 1, c = poly[order[2]] + 1;
  if (turn == Sign::Negative) std::swap(b, c);
  cdt.global = {poly[0] + 1, poly[1] + 1, poly[2] + 1};
  cdt.triangles = {{a, b, c}};
  cdt.constrained = {{b, c}, {c, a}, {a, b}};
  return true;
}

}  // namespace delmesh::tet3d
