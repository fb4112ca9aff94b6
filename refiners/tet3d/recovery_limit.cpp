// The Steiner-point bound of boundary recovery and its diagnosis (see recovery_limit.h).
#include "refiners/tet3d/recovery_limit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "refiners/tet3d/boundary_split.h"

namespace delmesh::tet3d {

namespace {

enum class FeatureKind : std::uint8_t { Vertex, Segment, Facet };

struct Feature {
  FeatureKind kind;
  std::uint32_t id;  ///< tet mesh vertex id, segment id or facet id
  bool operator==(const Feature&) const = default;
};

std::uint64_t feature_code(const Feature& f) { return (std::uint64_t{static_cast<std::uint8_t>(f.kind)} << 32) | f.id; }
Feature feature_of_code(std::uint64_t code) {
  return {static_cast<FeatureKind>(code >> 32), static_cast<std::uint32_t>(code)};
}

/// The input feature vertex v lies on (an input vertex is its own feature).
Feature feature_of(const RefineState& state, std::uint32_t v) {
  const VertexInfo& info = state.vertices[v];
  switch (info.kind) {
    case VertexKind::OnSegment: return {FeatureKind::Segment, info.owner};
    case VertexKind::OnFacet: return {FeatureKind::Facet, info.owner};
    case VertexKind::Input:
    case VertexKind::Interior:
    case VertexKind::Unused: break;
  }
  return {FeatureKind::Vertex, v};
}

bool facet_has_input_vertex(const RefineState& state, std::uint32_t facet, std::uint32_t v) {
  return state.facets[facet].has_vertex(v);
}

bool segment_touches_facet(const RefineState& state, std::uint32_t s, std::uint32_t facet) {
  const SegmentData& seg = state.segments[s];
  const auto& fs = seg.facets;
  return std::find(fs.begin(), fs.end(), facet) != fs.end() || facet_has_input_vertex(state, facet, seg.a) ||
         facet_has_input_vertex(state, facet, seg.b);
}

bool facets_touch(const RefineState& state, std::uint32_t f, std::uint32_t g) {
  for (const auto& s : state.facets[f].segments())
    for (const std::uint32_t v : s)
      if (state.vertices[v].kind == VertexKind::Input && facet_has_input_vertex(state, g, v)) return true;
  return false;
}

/// Do the two features meet (share a vertex)? Crowding between features that meet is
/// what concentric shells and the floors handle; the bound is about the others.
bool incident(const RefineState& state, const Feature& x, const Feature& y) {
  if (x == y) return true;
  if (y.kind < x.kind) return incident(state, y, x);
  switch (x.kind) {
    case FeatureKind::Vertex:
      if (y.kind == FeatureKind::Vertex) return false;
      if (y.kind == FeatureKind::Segment) return state.segments[y.id].a == x.id || state.segments[y.id].b == x.id;
      return facet_has_input_vertex(state, y.id, x.id);
    case FeatureKind::Segment:
      if (y.kind == FeatureKind::Segment) {
        const SegmentData &s = state.segments[x.id], &t = state.segments[y.id];
        return s.a == t.a || s.a == t.b || s.b == t.a || s.b == t.b;
      }
      return segment_touches_facet(state, x.id, y.id);
    case FeatureKind::Facet: return facets_touch(state, x.id, y.id);
  }
  return true;
}

std::string name(const RefineState& state, const Feature& f) {
  switch (f.kind) {
    case FeatureKind::Vertex: return "vertex " + std::to_string(f.id - 1);
    case FeatureKind::Segment:
      return "segment " + std::to_string(state.segments[f.id].a - 1) + "-" + std::to_string(state.segments[f.id].b - 1);
    case FeatureKind::Facet:
      return "facet " + std::to_string(f.id) + " (marker " + std::to_string(state.facet_markers[f.id]) + ")";
  }
  return {};
}

void add_ids(const RefineState& state, const Feature& f, std::vector<std::uint32_t>& ids) {
  switch (f.kind) {
    case FeatureKind::Vertex: ids.push_back(f.id - 1); break;
    case FeatureKind::Segment:
      ids.push_back(state.segments[f.id].a - 1);
      ids.push_back(state.segments[f.id].b - 1);
      break;
    case FeatureKind::Facet: ids.push_back(f.id); break;
  }
}

/// Distance between the segments pq and rs (closest points clamped to both).
double segment_distance(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  const Vec3 d1 = q - p, d2 = s - r, w = p - r;
  const double a = d1.dot(d1), e = d2.dot(d2), b = d1.dot(d2), c = d1.dot(w), f = d2.dot(w);
  const double denom = a * e - b * b;
  double sc = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double tc = (b * sc + f) / e;
  if (tc < 0.0 || tc > 1.0) {
    tc = std::clamp(tc, 0.0, 1.0);
    sc = std::clamp((b * tc - c) / a, 0.0, 1.0);
  }
  return ((p + sc * d1) - (r + tc * d2)).norm();
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.dot(d), 0.0, 1.0);
  return (a + t * d - p).norm();
}

std::string figure(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", x);
  return text;
}

/// Two input segments among the four holding the most recovery Steiner points: the pair
/// whose less crowded member holds the most, ties broken by the largest length / gap (the
/// shorter length; the gap is their distance when they do not meet, else the distance of
/// one's far end from the other).
struct Diagnosis {
  double ratio = 0.0;  ///< length / gap of the features named
  std::string text;
  std::vector<std::uint32_t> ids;
};

std::optional<Diagnosis> segment_diagnosis(const RefineState& state, const std::vector<std::size_t>& count) {
  std::vector<std::uint32_t> top;
  for (std::uint32_t s = 0; s < count.size(); ++s)
    if (count[s] > 0) top.push_back(s);
  std::sort(top.begin(), top.end(), [&](std::uint32_t x, std::uint32_t y) { return count[x] > count[y] || (count[x] == count[y] && x < y); });
  if (top.size() > 4) top.resize(4);
  const TetMesh& mesh = state.mesh;
  double best_ratio = 0.0;
  std::size_t best_count = 0;
  std::string best;
  std::vector<std::uint32_t> best_ids;
  for (std::size_t i = 0; i < top.size(); ++i) {
    for (std::size_t j = i + 1; j < top.size(); ++j) {
      const SegmentData &s = state.segments[top[i]], &t = state.segments[top[j]];
      const Vec3 &sa = mesh.point(s.a), &sb = mesh.point(s.b), &ta = mesh.point(t.a), &tb = mesh.point(t.b);
      const double length = std::min((sb - sa).norm(), (tb - ta).norm());
      std::uint32_t apex = kNone;
      if (s.a == t.a || s.a == t.b) apex = s.a;
      if (s.b == t.a || s.b == t.b) apex = s.b;
      double gap;
      std::string text;
      if (apex == kNone) {
        gap = segment_distance(sa, sb, ta, tb);
        text = "segments " + std::to_string(s.a - 1) + "-" + std::to_string(s.b - 1) + " and " + std::to_string(t.a - 1) +
               "-" + std::to_string(t.b - 1) + ", which run within " + figure(gap) + " of each other over " + figure(length) +
               " units";
      } else {
        const std::uint32_t fs = s.a == apex ? s.b : s.a, ft = t.a == apex ? t.b : t.a;
        const Vec3 &p = mesh.point(apex), u = mesh.point(fs) - p, w = mesh.point(ft) - p;
        gap = std::min(point_segment_distance(mesh.point(fs), ta, tb), point_segment_distance(mesh.point(ft), sa, sb));
        const double angle = std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / 3.141592653589793;
        text = "segments " + std::to_string(apex - 1) + "-" + std::to_string(fs - 1) + " and " + std::to_string(apex - 1) +
               "-" + std::to_string(ft - 1) + ", which meet at vertex " + std::to_string(apex - 1) + " at " + figure(angle) +
               " degrees and their far ends are " + figure(gap) + " apart, " + figure(length) + " units from it";
      }
      const double ratio = gap > 0.0 ? length / gap : std::numeric_limits<double>::infinity();
      const std::size_t crowd = std::min(count[top[i]], count[top[j]]);
      if (crowd < best_count || (crowd == best_count && !(ratio > best_ratio))) continue;
      best_ratio = ratio;
      best_count = crowd;
      best = "the most crowded are " + text + " (" + std::to_string(count[top[i]]) + " and " +
             std::to_string(count[top[j]]) + " Steiner points)";
      if (ratio > static_cast<double>(count[top[i]] + count[top[j]]))
        best += ": conforming boundary recovery would need about length / gap = " + figure(ratio) +
                " Steiner points on them";
      best_ids = {s.a - 1, s.b - 1, t.a - 1, t.b - 1};
    }
  }
  if (best.empty()) return std::nullopt;
  return Diagnosis{best_ratio, best, best_ids};
}

/// Mesh edges between Steiner points of one feature and vertices of another.
struct Crowding {
  std::size_t edges = 0;
  double shortest = std::numeric_limits<double>::infinity();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
};

struct PairHash {
  std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t>& k) const {
    return static_cast<std::size_t>((k.first * 0x9E3779B97F4A7C15ULL) ^ (k.second + 0x632BE59BD9B4E019ULL));
  }
};

}  // namespace

std::size_t recovery_vertex_limit(const RefineState& state) {
  return state.mesh.num_vertices() + kRecoveryBase + kRecoveryPerInput * (state.plc.points.size() + state.subfaces.size());
}

Error recovery_limit_error(const RefineState& state) {
  const TetMesh& mesh = state.mesh;
  const std::uint32_t first_steiner = static_cast<std::uint32_t>(state.plc.points.size()) + 1;
  std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, Crowding, PairHash> pairs;
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (std::uint32_t t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.is_dead(t) || mesh.is_infinite(t)) continue;
    const auto& v = mesh.tet(t).v;
    for (const auto& e : kEdge) {
      std::uint32_t u = v[e[0]], w = v[e[1]];
      if (u < first_steiner && w < first_steiner) continue;
      if (u < w) std::swap(u, w);  // u is a Steiner point
      const Feature fu = feature_of(state, u), fw = feature_of(state, w);
      if (fu == fw) continue;
      Crowding& c = pairs[{feature_code(fu), feature_code(fw)}];
      ++c.edges;
      c.shortest = std::min(c.shortest, (mesh.point(u) - mesh.point(w)).norm());
      c.lo = c.lo.cwiseMin(mesh.point(u));
      c.hi = c.hi.cwiseMax(mesh.point(u));
    }
  }
  const std::size_t steiner = mesh.num_vertices() - first_steiner;
  std::vector<std::size_t> on_segment(state.segments.size(), 0);
  for (std::uint32_t v = first_steiner; v < mesh.num_vertices(); ++v)
    if (state.vertices[v].kind == VertexKind::OnSegment) ++on_segment[state.vertices[v].owner];
  const std::string text = "boundary recovery stopped at its bound of " + std::to_string(steiner) +
                           " Steiner points (" + std::to_string(kRecoveryBase) + " + " +
                           std::to_string(kRecoveryPerInput) + " per input vertex and input subfacet)";
  // Two candidates: the pair of the most crowded segments (segment_diagnosis), and among
  // the nonincident features with many tet edges between their points (at least a
  // twentieth of the most), the pair with the largest stretch / distance. The one with
  // the larger length / gap is named.
  std::optional<Diagnosis> best = segment_diagnosis(state, on_segment);
  std::size_t most_edges = 0;
  for (const auto& [key, c] : pairs) most_edges = std::max(most_edges, c.edges);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> keys;
  for (const auto& [key, c] : pairs)
    if (20 * c.edges >= most_edges) keys.push_back(key);
  std::sort(keys.begin(), keys.end());
  for (const auto& key : keys) {
    const Feature x = feature_of_code(key.first), y = feature_of_code(key.second);
    if (incident(state, x, y)) continue;
    const Crowding& c = pairs.at(key);
    double distance = c.shortest;
    if (x.kind == FeatureKind::Segment && y.kind == FeatureKind::Segment) {
      const SegmentData &s = state.segments[x.id], &r = state.segments[y.id];
      distance = segment_distance(mesh.point(s.a), mesh.point(s.b), mesh.point(r.a), mesh.point(r.b));
    }
    const double length = (c.hi - c.lo).norm();
    const double ratio = distance > 0.0 ? length / distance : std::numeric_limits<double>::infinity();
    if (best && !(ratio > best->ratio)) continue;
    const bool area = x.kind == FeatureKind::Facet || y.kind == FeatureKind::Facet;
    const double need = area ? ratio * ratio : ratio;
    Diagnosis d;
    d.ratio = ratio;
    d.text = "the most crowded pair is " + name(state, x) + " and " + name(state, y) +
             ": their Steiner points come within " + figure(distance) + " of each other over a stretch of " +
             figure(length) + " units (" + std::to_string(c.edges) + " tet edges between them)";
    if (need > static_cast<double>(steiner))
      d.text += ": conforming boundary recovery would need about " +
                std::string(area ? "(length / distance)^2" : "length / distance") + " = " + figure(need) +
                " Steiner points there";
    add_ids(state, x, d.ids);
    add_ids(state, y, d.ids);
    best = d;
  }
  Error error = make_error(ErrorCode::Unsupported, text);
  if (best) {
    error.message += ": " + best->text + "; a constrained recovery (--facet-recovery ccdt) would need none";
    error.entity_ids = best->ids;
  }
  return error;
}

Error split_point_error(const RefineState& state, std::uint32_t a, std::uint32_t b) {
  const TetMesh& mesh = state.mesh;
  const Location& at = state.cavity.location;
  const Vec3 split = subsegment_split_point(state, a, b);
  const bool too_short = below_split_resolution(state, a, b, split);
  const std::uint32_t met =
      !too_short && at.kind == LocationKind::OnVertex ? mesh.vertex(at.tet, at.i)
      : (split - mesh.point(a)).norm() <= (split - mesh.point(b)).norm() ? a
                                                                         : b;
  const Vec3& p = mesh.point(met);
  std::uint32_t nearest = 1;
  for (std::uint32_t v = 1; v <= state.plc.points.size(); ++v)
    if ((mesh.point(v) - p).squaredNorm() < (mesh.point(nearest) - p).squaredNorm()) nearest = v;
  const std::uint32_t* seg = subsegment_of(state, a, b);
  const Feature segment{FeatureKind::Segment, seg ? *seg : 0};
  Error error = make_error(
      ErrorCode::Unsupported,
      "boundary recovery reached the resolution of double precision: the split point of a subsegment of " +
          name(state, segment) + " (length " + figure((mesh.point(a) - mesh.point(b)).norm()) + ") " +
          (too_short ? "would make a piece shorter than 2^-30 of its coordinates, next to a vertex on "
                     : "coincides with a Steiner point on ") +
          name(state, feature_of(state, met)) + ", " +
          figure((mesh.point(nearest) - p).norm()) + " from input vertex " + std::to_string(nearest - 1) +
          "; the features meeting there (at small angles, or nearly touching) make conforming recovery split ever "
          "closer to it");
  add_ids(state, segment, error.entity_ids);
  error.entity_ids.push_back(nearest - 1);
  return error;
}

}  // namespace delmesh::tet3d
