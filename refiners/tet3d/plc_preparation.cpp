// PLC preparation (see plc_preparation.h).
#include "refiners/tet3d/plc_preparation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "refiners/tet3d/facet_cdt.h"
#include "refiners/tet3d/feature_size.h"
#include "refiners/tet3d/narrow_facet_floor.h"
#include "refiners/tet3d/small_angles.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/tetmesh/delaunay.h"

namespace delmesh::tet3d {

namespace {

/// Newell normal of a polygon (twice its vector area).
Vec3 newell_normal(const Plc& plc, const Plc::Polygon& poly) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = plc.points[poly[i]];
    const Vec3& b = plc.points[poly[(i + 1) % poly.size()]];
    n += a.cross(b);
  }
  return n;
}

std::string facet_name(std::size_t f) { return "facet " + std::to_string(f); }

Expected<void> build_facet(RefineState& state, std::size_t f) {
  const Plc& plc = state.plc;
  const Plc::Facet& facet = plc.facets[f];
  Vec3 normal = Vec3::Zero();
  for (const auto& poly : facet.polygons) {
    if (poly.size() < 3) continue;
    const Vec3 n = newell_normal(plc, poly);
    if (n.squaredNorm() > normal.squaredNorm()) normal = n;
  }
  if (!(normal.squaredNorm() > 0.0))
    return make_error(ErrorCode::DegenerateInput, facet_name(f) + " has no polygon with a nonzero area");
  FacetTriangulation tri(*state.facet_pool, normal);
  const Axis axis = tri.axis();

  // The facet's constrained Delaunay triangulation in its projection: vertices (tet
  // mesh ids), triangles and subsegments. A facet that is one triangle stays out of the
  // facet pool until refinement changes it (facet_triangulation.h).
  FacetCdt cdt;
  const bool lone = lone_triangle(plc, facet, axis, cdt);
  if (!lone) {
    if (auto built = triangulate_facet(plc, facet, axis, cdt); !built)
      return make_error(built.error().code, facet_name(f) + built.error().message);
    for (const std::uint32_t g : cdt.global) tri.add_vertex(g);
  }
  auto assigned = lone ? tri.assign_lone_triangle({cdt.global[0], cdt.global[1], cdt.global[2]}, cdt.triangles[0])
                       : tri.assign(cdt.triangles, cdt.constrained);
  if (!assigned) return make_error(assigned.error().code, facet_name(f) + ": " + assigned.error().message);
  tri.make_delaunay();
  for (const auto& s : cdt.constrained) {
    const std::uint64_t key = edge_key(s[0], s[1]);
    auto it = state.subsegments.find(key);
    std::uint32_t sid;
    if (it == state.subsegments.end()) {
      sid = static_cast<std::uint32_t>(state.segments.size());
      SegmentData seg;
      seg.a = s[0];
      seg.b = s[1];
      state.segments.push_back(seg);
      state.subsegments.emplace(key, sid);
    } else {
      sid = it->second;
    }
    auto& fs = state.segments[sid].facets;
    if (std::find(fs.begin(), fs.end(), static_cast<std::uint32_t>(f)) == fs.end())
      fs.push_back(static_cast<std::uint32_t>(f));
  }
  for (const Subface& t : tri.subfaces()) {
    const FaceKey key = face_key(t[0], t[1], t[2]);
    if (!state.subfaces.emplace(key, static_cast<std::uint32_t>(f)).second)
      return make_error(ErrorCode::SelfIntersection,
                        facet_name(f) + " overlaps facet " + std::to_string(state.subfaces[key]));
  }
  state.facets.push_back(std::move(tri));
  state.facet_markers.push_back(facet.marker);
  return {};
}

/// Segments whose endpoint is an input vertex shared with another segment are split
/// there on concentric shells (notes §3.8); the segments of a cluster joined by corners
/// narrower than kGridCornerDeg get the apex of the cluster's narrowest corner as their
/// grid origin where their lines pass within kGridCornerDeg of it.
void mark_shells(RefineState& state) {
  std::vector<std::uint32_t> degree(state.mesh.num_vertices(), 0);
  for (const SegmentData& seg : state.segments) {
    ++degree[seg.a];
    ++degree[seg.b];
  }
  for (SegmentData& seg : state.segments) {
    seg.shell_a = degree[seg.a] >= 2;
    seg.shell_b = degree[seg.b] >= 2;
  }
  // Clusters of segments joined by corners below kGridCornerDeg (union-find), and the
  // apex of each cluster's narrowest corner.
  std::vector<std::vector<std::uint32_t>> incident(state.mesh.num_vertices());
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    incident[state.segments[s].a].push_back(s);
    incident[state.segments[s].b].push_back(s);
  }
  auto arm = [&](std::uint32_t s, std::uint32_t v) {
    const SegmentData& seg = state.segments[s];
    const Vec3 d = state.mesh.point(seg.a == v ? seg.b : seg.a) - state.mesh.point(v);
    return Vec3(d / d.norm());
  };
  std::vector<std::uint32_t> parent(state.segments.size());
  for (std::uint32_t s = 0; s < parent.size(); ++s) parent[s] = s;
  auto root = [&](std::uint32_t s) {
    while (parent[s] != s) s = parent[s] = parent[parent[s]];
    return s;
  };
  const double limit = std::cos(kGridCornerDeg * std::numbers::pi / 180.0);
  struct Corner {
    std::uint32_t segment, apex;
    double cosine;
  };
  std::vector<Corner> narrow;
  for (std::uint32_t v = 0; v < incident.size(); ++v) {
    const auto& segs = incident[v];
    for (std::size_t i = 0; i < segs.size(); ++i)
      for (std::size_t j = i + 1; j < segs.size(); ++j) {
        const double c = arm(segs[i], v).dot(arm(segs[j], v));
        if (!(c > limit)) continue;
        narrow.push_back({segs[i], v, c});
        parent[root(segs[i])] = root(segs[j]);
      }
  }
  if (narrow.empty()) return;
  std::vector<double> cluster_cos(state.segments.size(), limit);
  std::vector<std::uint32_t> cluster_apex(state.segments.size(), kNone);
  for (const Corner& corner : narrow) {
    const std::uint32_t r = root(corner.segment);
    if (corner.cosine > cluster_cos[r]) {
      cluster_cos[r] = corner.cosine;
      cluster_apex[r] = corner.apex;
    }
  }
  const double sine = std::sin(kGridCornerDeg * std::numbers::pi / 180.0);
  for (std::uint32_t s = 0; s < state.segments.size(); ++s) {
    SegmentData& seg = state.segments[s];
    const std::uint32_t o = cluster_apex[root(s)];
    if (o == kNone) continue;
    // The apex is an end of the segment, or its line passes within kGridCornerDeg of the
    // apex, seen over the segment's length.
    const Vec3& pa = state.mesh.point(seg.a);
    const Vec3 ab = state.mesh.point(seg.b) - pa;
    if (o == seg.a || o == seg.b || ab.cross(state.mesh.point(o) - pa).norm() <= sine * ab.squaredNorm())
      seg.grid_origin = o;
  }
}

}  // namespace

Expected<void> prepare_plc(RefineState& state) {
  const Plc& plc = state.plc;
  for (std::size_t i = 0; i < plc.points.size(); ++i) {
    const Vec3& p = plc.points[i];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
      return make_error(ErrorCode::InvalidInput, "point " + std::to_string(i) + " has a non-finite coordinate");
  }
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    if (plc.facets[f].polygons.empty()) return make_error(ErrorCode::InvalidInput, facet_name(f) + " has no polygon");
    for (const auto& poly : plc.facets[f].polygons)
      for (const std::uint32_t v : poly)
        if (v >= plc.points.size())
          return make_error(ErrorCode::InvalidInput,
                            facet_name(f) + " refers to point " + std::to_string(v) + " which does not exist");
  }
  for (std::size_t s = 0; s < plc.segments.size(); ++s) {
    const auto& seg = plc.segments[s];
    if (seg.a >= plc.points.size() || seg.b >= plc.points.size())
      return make_error(ErrorCode::InvalidInput, "segment " + std::to_string(s) + " refers to a missing point");
    if (seg.a == seg.b)
      return make_error(ErrorCode::DegenerateInput, "segment " + std::to_string(s) + " has equal endpoints");
  }
  if (plc.facets.empty()) return make_error(ErrorCode::InvalidInput, "the PLC has no facets");

  DelaunayOptions dopt;
  dopt.seed = state.options.seed;
  auto del = delaunay_tetrahedralize(plc.points, dopt);
  if (!del) return del.error();
  if (del->num_duplicates > 0) {
    for (std::size_t i = 0; i < del->duplicate_of.size(); ++i)
      if (del->duplicate_of[i] != kNone)
        return make_error(ErrorCode::DuplicateVertex, "points " + std::to_string(del->duplicate_of[i]) + " and " +
                                                          std::to_string(i) + " coincide");
  }
  state.mesh = std::move(del->mesh);
  state.vertices.assign(state.mesh.num_vertices(), VertexInfo{});
  state.vertices[0].kind = VertexKind::Unused;
  state.tet_region.assign(state.mesh.tet_slots(), kRegionUnknown);

  const std::vector<double> nearest = nearest_vertex_distances(state);

  state.facets.reserve(plc.facets.size());
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    auto built = build_facet(state, f);
    if (!built) return built;
  }
  for (std::size_t s = 0; s < plc.segments.size(); ++s) {
    const std::uint32_t a = plc.segments[s].a + 1, b = plc.segments[s].b + 1;
    const std::uint64_t key = edge_key(a, b);
    auto it = state.subsegments.find(key);
    if (it == state.subsegments.end()) {
      SegmentData seg;
      seg.a = a;
      seg.b = b;
      seg.marker = plc.segments[s].marker;
      state.subsegments.emplace(key, static_cast<std::uint32_t>(state.segments.size()));
      state.segments.push_back(seg);
    } else {
      state.segments[it->second].marker = plc.segments[s].marker;
    }
  }
  // Local feature size (feature_size.h): the nearest other vertex, or nearer gaps to
  // segments and facets that do not contain the vertex.
  const FeatureGaps gaps = feature_gaps(state, plc.points.size(), &nearest);
  for (std::uint32_t v = 1; v < state.mesh.num_vertices(); ++v) {
    const double lfs = floor_feature_size(nearest[v], gaps, v);
    state.vertices[v].floor = std::isfinite(nearest[v]) ? kFloorFactor * nearest[v] : 0.0;
    state.vertices[v].field_floor = std::isfinite(lfs) ? kFloorFactor * lfs : 0.0;
  }
  find_narrow_partners(state);
  mark_shells(state);
  classify_small_angles(state);
  for (const SegmentData& seg : state.segments) state.subsegment_queue.push_back({seg.a, seg.b});
  if (state.options.region_max_volume)
    for (const auto& r : plc.regions)
      if (r.max_volume > 0.0) state.region_max_volume[r.id] = r.max_volume;
  state.vertex_cap = plc.points.size() + 30'000'000;
  return {};
}

}  // namespace delmesh::tet3d
