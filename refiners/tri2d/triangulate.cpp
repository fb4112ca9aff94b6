// triangulate(): input checks, Delaunay triangulation, segment recovery, hole and
// concavity removal, regions, refinement, and conversion to a TriangleMesh (see
// triangulate.h; notes ch. 3).
#include "refiners/tri2d/triangulate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "refiners/tri2d/refine.h"
#include "toolkit/mesh2d/cdt.h"
#include "toolkit/mesh2d/triangulation.h"

namespace delmesh {

namespace {

using mesh2d::kNone;

bool finite(const Point2& p) { return std::isfinite(p[0]) && std::isfinite(p[1]); }

Expected<void> check_input(const Pslg& in, const TriangulateOptions& options) {
  for (std::size_t i = 0; i < in.points.size(); ++i) {
    if (!finite(in.points[i])) {
      Error e = make_error(ErrorCode::InvalidInput,
                           "point " + std::to_string(i) + " has a non-finite coordinate");
      e.entity_ids = {static_cast<std::uint32_t>(i)};
      return e;
    }
  }
  if (in.points.size() > 0xFFFFFFF0u)
    return make_error(ErrorCode::Unsupported, "too many points for 32-bit vertex ids");
  for (std::size_t s = 0; s < in.segments.size(); ++s) {
    for (std::uint32_t v : in.segments[s]) {
      if (v >= in.points.size()) {
        Error e = make_error(ErrorCode::InvalidInput,
                             "segment " + std::to_string(s) + " names missing vertex " +
                                 std::to_string(v));
        e.entity_ids = {static_cast<std::uint32_t>(s)};
        return e;
      }
    }
  }
  for (std::size_t h = 0; h < in.holes.size(); ++h) {
    if (!finite(in.holes[h])) {
      Error e = make_error(ErrorCode::InvalidInput,
                           "hole " + std::to_string(h) + " has a non-finite coordinate");
      e.entity_ids = {static_cast<std::uint32_t>(h)};
      return e;
    }
  }
  for (std::size_t r = 0; r < in.regions.size(); ++r) {
    if (!finite(in.regions[r].point)) {
      Error e = make_error(ErrorCode::InvalidInput,
                           "region " + std::to_string(r) + " has a non-finite coordinate");
      e.entity_ids = {static_cast<std::uint32_t>(r)};
      return e;
    }
  }
  if (options.quality && !(options.min_angle_deg >= 0.0 && options.min_angle_deg < 60.0))
    return make_error(ErrorCode::InvalidOption, "minimum angle must be in [0, 60) degrees");
  if (!in.point_markers.empty() && in.point_markers.size() != in.points.size())
    return make_error(ErrorCode::InvalidInput, "point marker count differs from point count");
  if (!in.segment_markers.empty() && in.segment_markers.size() != in.segments.size())
    return make_error(ErrorCode::InvalidInput, "segment marker count differs from segment count");
  if (in.num_point_attributes < 0 ||
      in.point_attributes.size() != in.points.size() * static_cast<std::size_t>(in.num_point_attributes))
    return make_error(ErrorCode::InvalidInput, "point attribute count differs from point count");
  return {};
}

// Cosines of the smallest and largest angles of triangle abc (law of cosines: the
// smallest angle is opposite the shortest edge, the largest opposite the longest).
void extreme_cosines(const Point2& a, const Point2& b, const Point2& c, double& cos_min_angle,
                     double& cos_max_angle) {
  const auto sq = [](const Point2& p, const Point2& q) {
    return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]);
  };
  double l[3] = {sq(b, c), sq(c, a), sq(a, b)};
  std::sort(l, l + 3);
  cos_min_angle = (l[1] + l[2] - l[0]) / (2.0 * std::sqrt(l[1] * l[2]));
  cos_max_angle = (l[0] + l[1] - l[2]) / (2.0 * std::sqrt(l[0] * l[1]));
}

double degrees_from_cosine(double c) {
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

}  // namespace

Expected<TriangulateResult> triangulate(const Pslg& input, const TriangulateOptions& options) {
  try {
    if (auto ok = check_input(input, options); !ok) return ok.error();
    const auto t0 = std::chrono::steady_clock::now();
    TriangulateResult result;
    result.stats.input_points = input.points.size();

    mesh2d::Triangulation tri;
    {
      std::size_t estimate = input.points.size();
      if (options.max_area > 0) {
        double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
        for (const Point2& p : input.points)
          for (int k = 0; k < 2; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
          }
        const double boxes = (hi[0] - lo[0]) * (hi[1] - lo[1]) / options.max_area;
        if (boxes < 1e9) estimate += static_cast<std::size_t>(boxes);
      }
      tri.reserve(estimate);
    }
    if (auto ok = tri.build_delaunay(input.points); !ok) return ok.error();
    result.stats.duplicate_points = tri.num_duplicates;
    if (tri.num_duplicates > 0) {
      log(options.log, LogLevel::Warning,
          std::to_string(tri.num_duplicates) + " duplicate point(s) merged");
    }

    mesh2d::SubsegmentOwners owners;
    if (options.pslg && !input.segments.empty()) {
      std::vector<std::array<std::uint32_t, 2>> segs;
      segs.reserve(input.segments.size());
      std::size_t zero_length = 0;
      for (auto s : input.segments) {
        for (auto& v : s)
          if (tri.duplicate_of[v] != kNone) v = tri.duplicate_of[v];
        zero_length += s[0] == s[1];
        segs.push_back(s);
      }
      if (zero_length > 0)
        log(options.log, LogLevel::Warning,
            std::to_string(zero_length) + " zero-length segment(s) ignored");
      mesh2d::CdtStats cdt_stats;
      if (auto ok = mesh2d::insert_segments(tri, segs, owners, cdt_stats); !ok) return ok.error();
      result.stats.segment_crossings = cdt_stats.crossings;
      if (cdt_stats.crossings > 0)
        log(options.log, LogLevel::Warning,
            std::to_string(cdt_stats.crossings) + " segment crossing(s) split at new vertices");
    }

    const bool track_regions =
        !input.regions.empty() && (options.region_attributes || options.region_max_area);
    mesh2d::DomainOptions dom;
    dom.keep_convex_hull = options.keep_convex_hull || !options.pslg;
    dom.track_regions = track_regions;
    auto domain = mesh2d::classify_domain(tri, options.pslg ? input.holes : std::vector<Point2>{},
                                          input.regions, dom);
    if (!domain) return domain.error();
    for (const auto& e : domain->boundary_edges) owners.set(e[0], e[1], tri2d::kHullSegment);
    if (tri.count_in_domain() == 0)
      log(options.log, LogLevel::Warning,
          "no triangle is left inside the segments (do they enclose a region? keep_convex_hull "
          "keeps the convex hull)");
    for (std::size_t r : domain->unused_regions)
      log(options.log, LogLevel::Warning,
          "region " + std::to_string(r) + " lies outside the domain and is ignored");
    const auto t1 = std::chrono::steady_clock::now();
    result.stats.seconds_triangulate = std::chrono::duration<double>(t1 - t0).count();

    const bool refine = options.quality || options.max_area > 0 ||
                        static_cast<bool>(options.max_area_at) ||
                        (options.region_max_area && track_regions);
    std::vector<double> attributes;  // interpolated for Steiner vertices by refinement
    if (refine) {
      std::vector<std::uint8_t> kind(tri.points.size(), tri2d::kInputVertex);
      tri2d::classify_input_vertices(tri, kind);
      tri2d::RefineParams params;
      params.quality = options.quality;
      params.min_angle_deg = options.min_angle_deg;
      params.max_area = options.max_area;
      if (options.region_max_area && track_regions) {
        params.region_max_area.assign(input.regions.size() + 1, -1.0);
        for (std::size_t r = 0; r < input.regions.size(); ++r)
          params.region_max_area[r + 1] = input.regions[r].max_area;
      }
      params.max_area_at = options.max_area_at;
      params.chew = options.chew;
      params.off_centers = options.off_centers;
      params.relaxed_boundary = options.relaxed_boundary;
      params.max_steiner_points = options.max_steiner_points;
      params.log = options.log;
      if (input.num_point_attributes > 0) {
        attributes = input.point_attributes;
        attributes.resize(tri.points.size() * static_cast<std::size_t>(input.num_point_attributes),
                          0.0);
        params.attributes = &attributes;
        params.num_attributes = input.num_point_attributes;
      }
      const tri2d::RefineOutcome out = tri2d::refine(tri, owners, kind, params);
      result.stats.unmet_triangles = out.unmet_triangles;
      if (out.unmet_triangles > 0 || out.budget_exhausted) result.status = MeshStatus::Partial;
    }
    result.stats.steiner_points = tri.points.size() - input.points.size();
    const auto t2 = std::chrono::steady_clock::now();
    result.stats.seconds_refine = std::chrono::duration<double>(t2 - t1).count();

    // ---- output ----
    TriangleMesh& mesh = result.mesh;
    const std::size_t nv = tri.points.size();
    mesh.point_markers.assign(nv, 0);
    if (!input.point_markers.empty())
      std::copy(input.point_markers.begin(), input.point_markers.end(), mesh.point_markers.begin());
    mesh.num_point_attributes = input.num_point_attributes;
    if (attributes.empty()) attributes = input.point_attributes;
    attributes.resize(nv * static_cast<std::size_t>(input.num_point_attributes), 0.0);
    mesh.point_attributes = std::move(attributes);
    mesh.holes = input.holes;
    const std::size_t ntri = tri.count_in_domain();
    mesh.triangles.reserve(ntri);
    if (options.region_attributes && track_regions) mesh.triangle_attributes.reserve(ntri);
    double cos_min = -1.0, cos_max = 1.0;
    for (std::uint32_t t = 0; t < tri.num_slots(); ++t) {
      if (!tri.in_domain(t)) continue;
      const std::uint32_t a = tri.tv[3 * t], b = tri.tv[3 * t + 1], c = tri.tv[3 * t + 2];
      mesh.triangles.push_back({a, b, c});
      if (options.region_attributes && track_regions) {
        const std::uint32_t r = tri.region[t];
        mesh.triangle_attributes.push_back(r == 0 ? 0.0 : input.regions[r - 1].attribute);
      }
      const Point2 &pa = tri.points[a], &pb = tri.points[b], &pc = tri.points[c];
      double cmin, cmax;
      extreme_cosines(pa, pb, pc, cmin, cmax);
      cos_min = std::max(cos_min, cmin);
      cos_max = std::min(cos_max, cmax);
      for (std::uint32_t i = 0; i < 3; ++i) {
        if (!tri.subseg(t, i)) continue;
        const std::uint32_t u = tri.tn[3 * t + i] / 3;
        const std::uint32_t x = tri.org(t, i), y = tri.dest(t, i);
        if (tri.in_domain(u) && u < t) continue;  // reported from the other side
        const std::uint32_t owner = owners.get(x, y);
        int marker = 1;
        if (owner < input.segments.size()) {
          marker = input.segment_markers.empty() ? (tri.in_domain(u) ? 0 : 1)
                                                  : input.segment_markers[owner];
        }
        mesh.segments.push_back({x, y});
        mesh.segment_markers.push_back(marker);
      }
    }
    // Steiner vertices on segments (and unmarked input vertices on marked segments) take
    // the segment's marker.
    for (std::size_t s = 0; s < mesh.segments.size(); ++s) {
      const int m = mesh.segment_markers[s];
      if (m == 0) continue;
      for (std::uint32_t v : mesh.segments[s])
        if (mesh.point_markers[v] == 0 && (v >= input.points.size() || input.point_markers.empty()))
          mesh.point_markers[v] = m;
    }
    result.stats.min_angle_deg = mesh.triangles.empty() ? 0.0 : degrees_from_cosine(cos_min);
    result.stats.max_angle_deg = mesh.triangles.empty() ? 0.0 : degrees_from_cosine(cos_max);
    mesh.points = std::move(tri.points);
    return result;
  } catch (const InternalError& e) {
    return make_error(ErrorCode::InvalidInput, std::string("triangulation failed: ") + e.what());
  } catch (const std::bad_alloc&) {
    return make_error(ErrorCode::InvalidInput, "out of memory while triangulating");
  }
}

}  // namespace delmesh
