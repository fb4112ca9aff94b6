// PLC validation (see plc_validate.h for the checks and the method).
#include "toolkit/plc/plc_validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>

#include "toolkit/plc/box_grid.h"
#include "toolkit/plc/plc_geometry.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {
namespace {

using namespace std::string_literals;

constexpr std::size_t kKinds = static_cast<std::size_t>(PlcIssueKind::Truncated) + 1;

std::string point_text(const Vec3& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.17g, %.17g, %.17g)", p.x(), p.y(), p.z());
  return buffer;
}

std::string vertex_text(const Plc& plc, std::uint32_t v) {
  return cat("vertex ", v) + " " + point_text(plc.points[v]);
}

class Validator {
 public:
  Validator(const Plc& plc, const PlcValidationOptions& options) : plc_(plc), opt_(options) {}

  std::vector<PlcIssue> run() {
    const bool indices_ok = check_indices();
    const bool finite = check_finite();
    check_duplicates();
    if (indices_ok) check_segments();
    if (indices_ok && finite) {
      check_facets();
      if (opt_.check_intersections) {
        check_facet_self_intersections();
        check_pair_intersections();
      }
    }
    if (indices_ok) check_edges();
    if (indices_ok && finite && opt_.check_points_inside && !plc_.facets.empty()) {
      check_points(plc_.holes, PlcIssueKind::HoleOutside, "volume hole point");
      std::vector<Vec3> region_points;
      for (const auto& r : plc_.regions) region_points.push_back(r.point);
      check_points(region_points, PlcIssueKind::RegionOutside, "region point");
    }
    std::stable_sort(issues_.begin(), issues_.end(), [](const PlcIssue& a, const PlcIssue& b) {
      return a.kind < b.kind;
    });
    const std::size_t dropped = std::accumulate(dropped_.begin(), dropped_.end(), std::size_t{0});
    if (dropped > 0) {
      PlcIssue issue;
      issue.kind = PlcIssueKind::Truncated;
      issue.message = std::to_string(dropped) + " more issues not listed:";
      for (std::size_t k = 0; k < kKinds; ++k) {
        if (dropped_[k] > 0) {
          issue.message += cat(" ", dropped_[k]) + " " +
                           to_string(static_cast<PlcIssueKind>(k));
        }
      }
      issues_.push_back(std::move(issue));
    }
    return std::move(issues_);
  }

 private:
  void add(PlcIssue issue) {
    if (issues_.size() >= opt_.max_issues) {
      ++dropped_[static_cast<std::size_t>(issue.kind)];
      return;
    }
    issues_.push_back(std::move(issue));
  }

  bool check_indices() {
    const std::size_t n = plc_.points.size();
    bool ok = true;
    for (std::uint32_t f = 0; f < plc_.facets.size(); ++f) {
      for (std::size_t k = 0; k < plc_.facets[f].polygons.size(); ++k) {
        for (std::uint32_t v : plc_.facets[f].polygons[k]) {
          if (v < n) continue;
          ok = false;
          add({PlcIssueKind::InvalidIndex,
               cat("facet ", f) + cat(" polygon ", k) +
                   cat(" names vertex ", v) + " but there are " +
                   std::to_string(n) + " vertices",
               {}, {}, {f}, {}});
          break;
        }
      }
    }
    for (std::uint32_t s = 0; s < plc_.segments.size(); ++s) {
      const auto& seg = plc_.segments[s];
      if (seg.a < n && seg.b < n) continue;
      ok = false;
      add({PlcIssueKind::InvalidIndex,
           cat("segment ", s) + " names vertex " +
               std::to_string(std::max(seg.a, seg.b)) + cat(" but there are ", n) +
               " vertices",
           {}, {s}, {}, {}});
    }
    return ok;
  }

  bool check_finite() {
    bool ok = true;
    for (std::uint32_t v = 0; v < plc_.points.size(); ++v) {
      if (plc_.points[v].allFinite()) continue;
      ok = false;
      add({PlcIssueKind::NonFiniteCoordinate, vertex_text(plc_, v) + " is not finite", {v}, {}, {}, {}});
    }
    return ok;
  }

  void check_duplicates() {
    const auto& P = plc_.points;
    std::vector<std::uint32_t> order(P.size());
    std::iota(order.begin(), order.end(), 0u);
    auto less = [&](std::uint32_t a, std::uint32_t b) {
      return std::lexicographical_compare(P[a].data(), P[a].data() + 3, P[b].data(), P[b].data() + 3);
    };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return less(a, b) || (!less(b, a) && a < b);
    });
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i + 1;
      while (j < order.size() && P[order[j]] == P[order[i]]) ++j;
      if (j - i > 1) {
        PlcIssue issue{PlcIssueKind::DuplicateVertex, "vertices", {}, {}, {}, {}};
        for (std::size_t k = i; k < j; ++k) {
          issue.vertices.push_back(order[k]);
          issue.message += cat(" ", order[k]);
        }
        issue.message += " are all at "s + point_text(P[order[i]]);
        add(std::move(issue));
      }
      i = j;
    }
  }

  void check_segments() {
    for (std::uint32_t s = 0; s < plc_.segments.size(); ++s) {
      const auto& seg = plc_.segments[s];
      if (plc_.points[seg.a] != plc_.points[seg.b]) continue;
      add({PlcIssueKind::DegenerateSegment,
           cat("segment ", s) + " has equal endpoints: " + vertex_text(plc_, seg.a) +
               " and "s + vertex_text(plc_, seg.b),
           {seg.a, seg.b}, {s}, {}, {}});
    }
  }

  void check_facets() {
    const auto& P = plc_.points;
    frames_.assign(plc_.facets.size(), std::nullopt);
    for (std::uint32_t f = 0; f < plc_.facets.size(); ++f) {
      const auto& facet = plc_.facets[f];
      const std::string name = cat("facet ", f);
      if (facet.polygons.empty()) {
        add({PlcIssueKind::DegenerateFacet, name + " has no polygon", {}, {}, {f}, {}});
        continue;
      }
      for (std::size_t k = 0; k < facet.polygons.size(); ++k) {
        const auto& polygon = facet.polygons[k];
        const std::string where = name + cat(" polygon ", k);
        if (polygon.empty()) {
          add({PlcIssueKind::DegenerateFacet, where + " is empty", {}, {}, {f}, {}});
          continue;
        }
        std::vector<std::uint32_t> sorted = polygon;
        std::sort(sorted.begin(), sorted.end());
        const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
        if (dup != sorted.end()) {
          add({PlcIssueKind::DegenerateFacet, where + " repeats " + vertex_text(plc_, *dup),
               {*dup}, {}, {f}, {}});
          continue;
        }
        if (polygon.size() == 2 && P[polygon[0]] == P[polygon[1]]) {
          add({PlcIssueKind::DegenerateFacet, where + " is a segment of zero length",
               {polygon[0], polygon[1]}, {}, {f}, {}});
        }
        if (polygon.size() >= 3) {
          bool all_collinear = true;
          for (std::size_t i = 2; i < polygon.size() && all_collinear; ++i) {
            all_collinear = collinear(P[polygon[0]], P[polygon[1]], P[polygon[i]]) &&
                            (P[polygon[0]] != P[polygon[1]] || i + 1 == polygon.size());
          }
          if (all_collinear) {
            add({PlcIssueKind::DegenerateFacet,
                 where + " has zero area (all its vertices are collinear), first " +
                     vertex_text(plc_, polygon[0]),
                 polygon, {}, {f}, {}});
          }
        }
      }
      const auto frame = facet_frame(plc_, facet);
      if (!frame) {
        add({PlcIssueKind::DegenerateFacet, name + " has no three non-collinear vertices", {},
             {}, {f}, {}});
        continue;
      }
      PlcIssue off{PlcIssueKind::NonPlanarFacet, "", {}, {}, {f}, {}};
      for (const auto& polygon : facet.polygons) {
        for (std::uint32_t v : polygon) {
          if (side_of_plane(plc_, *frame, P[v]) == Sign::Zero) continue;
          if (std::find(off.vertices.begin(), off.vertices.end(), v) == off.vertices.end()) {
            off.vertices.push_back(v);
          }
        }
      }
      if (!off.vertices.empty()) {
        off.message = name + cat(" is not planar: ", off.vertices.size()) +
                      cat(" vertices off the plane of vertices ", frame->a) + ", " +
                      std::to_string(frame->b) + cat(", ", frame->c) + ", first " +
                      vertex_text(plc_, off.vertices.front());
        add(std::move(off));
        continue;
      }
      frames_[f] = frame;
    }
  }

  Box3 facet_box(const Plc::Facet& facet) const {
    Box3 box;
    for (const auto& polygon : facet.polygons)
      for (std::uint32_t v : polygon) box.extend(plc_.points[v]);
    return box;
  }

  void report_intersection(const std::string& what, std::vector<std::uint32_t> vertices,
                           std::vector<std::uint32_t> segments, std::vector<std::uint32_t> facets) {
    std::string message = what;
    if (!vertices.empty()) {
      message += " (at the edge";
      for (std::uint32_t v : vertices) message += " "s + vertex_text(plc_, v);
      message += ")";
    }
    add({PlcIssueKind::Intersection, message, std::move(vertices), std::move(segments),
         std::move(facets), {}});
  }

  void check_facet_self_intersections() {
    for (std::uint32_t f = 0; f < plc_.facets.size(); ++f) {
      if (!frames_[f]) continue;
      const auto& facet = plc_.facets[f];
      if (facet.polygons.size() == 1 && facet.polygons[0].size() <= 3) continue;
      struct Edge {
        std::uint32_t a, b;
        Box3 box;
      };
      std::vector<Edge> edges;
      for_each_facet_edge(facet, [&](std::uint32_t a, std::uint32_t b) {
        Box3 box;
        box.extend(plc_.points[a]);
        box.extend(plc_.points[b]);
        edges.push_back({a, b, box});
      });
      std::sort(edges.begin(), edges.end(),
                [](const Edge& x, const Edge& y) { return x.box.lo.x() < y.box.lo.x(); });
      bool found = false;
      for (std::size_t i = 0; i < edges.size() && !found; ++i) {
        for (std::size_t j = i + 1; j < edges.size() && edges[j].box.lo.x() <= edges[i].box.hi.x(); ++j) {
          if (!edges[i].box.overlaps(edges[j].box)) continue;
          if (segments_meet_improperly(plc_, edges[i].a, edges[i].b, edges[j].a, edges[j].b,
                                       &*frames_[f])) {
            report_intersection(cat("facet ", f) + " is not a simple polygon: edges " +
                                    std::to_string(edges[i].a) + cat("-", edges[i].b) +
                                    cat(" and ", edges[j].a) + "-" +
                                    std::to_string(edges[j].b) + " cross",
                                {edges[i].a, edges[i].b, edges[j].a, edges[j].b}, {}, {f});
            found = true;
            break;
          }
        }
      }
    }
  }

  /// First edge of `f` that meets facet `g` improperly, as (a, b), or nullopt.
  std::optional<std::pair<std::uint32_t, std::uint32_t>> improper_edge(std::uint32_t f,
                                                                       std::uint32_t g) const {
    std::optional<std::pair<std::uint32_t, std::uint32_t>> found;
    const auto& P = plc_.points;
    const Box3& gbox = boxes_[g];
    for_each_facet_edge(plc_.facets[f], [&](std::uint32_t a, std::uint32_t b) {
      if (found) return;
      Box3 ebox;
      ebox.extend(P[a]);
      ebox.extend(P[b]);
      if (!ebox.overlaps(gbox)) return;
      if (segment_facet_contact(plc_, plc_.facets[g], *frames_[g], a, b, P[a], P[b]) ==
          Contact::Improper) {
        found = std::make_pair(a, b);
      }
    });
    if (found) return found;
    for (const auto& polygon : plc_.facets[f].polygons) {
      if (polygon.size() != 1) continue;
      const std::uint32_t w = polygon[0];
      if (segment_facet_contact(plc_, plc_.facets[g], *frames_[g], w, w, P[w], P[w]) ==
          Contact::Improper) {
        return std::make_pair(w, w);
      }
    }
    return std::nullopt;
  }

  /// Do the vertices of g that f does not share lie strictly on one side of f's plane,
  /// and is every edge of g between two shared vertices also an edge of f? Then g meets
  /// f's plane only at shared vertices and shared edges, so the pair needs no further test.
  /// (An edge of g joining two vertices of f that is no edge of f lies in f's plane and
  /// may run along f's boundary through another vertex of f: a T-junction.)
  bool separated_by_plane(std::uint32_t f, std::uint32_t g) const {
    const Plc::Facet& ff = plc_.facets[f];
    Sign side = Sign::Zero;
    for (const auto& polygon : plc_.facets[g].polygons) {
      for (std::uint32_t v : polygon) {
        if (has_vertex(ff, v)) continue;
        const Sign s = side_of_plane(plc_, *frames_[f], plc_.points[v]);
        if (s == Sign::Zero || (side != Sign::Zero && s != side)) return false;
        side = s;
      }
    }
    if (side == Sign::Zero) return false;
    bool chord = false;
    for_each_facet_edge(plc_.facets[g], [&](std::uint32_t a, std::uint32_t b) {
      if (chord || !has_vertex(ff, a) || !has_vertex(ff, b)) return;
      bool is_edge = false;
      for_each_facet_edge(ff, [&](std::uint32_t x, std::uint32_t y) {
        if ((x == a && y == b) || (x == b && y == a)) is_edge = true;
      });
      chord = !is_edge;
    });
    return !chord;
  }

  static bool has_vertex(const Plc::Facet& facet, std::uint32_t v) {
    for (const auto& polygon : facet.polygons) {
      for (std::uint32_t w : polygon) {
        if (w == v) return true;
      }
    }
    return false;
  }

  void check_pair_intersections() {
    const std::size_t nf = plc_.facets.size();
    std::vector<Box3> boxes(nf + plc_.segments.size());
    for (std::size_t f = 0; f < nf; ++f) {
      if (frames_[f]) boxes[f] = facet_box(plc_.facets[f]);
    }
    for (std::size_t s = 0; s < plc_.segments.size(); ++s) {
      const auto& seg = plc_.segments[s];
      if (plc_.points[seg.a] == plc_.points[seg.b]) continue;
      boxes[nf + s].extend(plc_.points[seg.a]);
      boxes[nf + s].extend(plc_.points[seg.b]);
    }
    boxes_ = boxes;
    const BoxGrid grid(std::move(boxes));
    const auto& P = plc_.points;
    grid.for_each_overlapping_pair([&](std::uint32_t i, std::uint32_t j) {
      if (i < nf && j < nf) {
        if (separated_by_plane(i, j) || separated_by_plane(j, i)) return;
        auto edge = improper_edge(i, j);
        std::uint32_t on = i;
        if (!edge) {
          edge = improper_edge(j, i);
          on = j;
        }
        if (!edge) return;
        std::vector<std::uint32_t> vs{edge->first};
        if (edge->second != edge->first) vs.push_back(edge->second);
        report_intersection(cat("facets ", i) + cat(" and ", j) +
                                " intersect other than along shared segments and vertices: an edge of facet "s +
                                std::to_string(on) + " meets the other facet",
                            std::move(vs), {}, {i, j});
      } else if (i < nf) {
        const std::uint32_t s = j - static_cast<std::uint32_t>(nf);
        const auto& seg = plc_.segments[s];
        if (segment_facet_contact(plc_, plc_.facets[i], *frames_[i], seg.a, seg.b, P[seg.a],
                                  P[seg.b]) == Contact::Improper) {
          report_intersection(cat("segment ", s) + cat(" meets facet ", i) +
                                  " other than at a shared vertex or as one of its edges",
                              {seg.a, seg.b}, {s}, {i});
        }
      } else {
        const std::uint32_t s = i - static_cast<std::uint32_t>(nf);
        const std::uint32_t t = j - static_cast<std::uint32_t>(nf);
        const auto& a = plc_.segments[s];
        const auto& b = plc_.segments[t];
        if (segments_meet_improperly(plc_, a.a, a.b, b.a, b.b)) {
          report_intersection(cat("segments ", s) + cat(" and ", t) +
                                  " meet other than at a shared endpoint",
                              {a.a, a.b, b.a, b.b}, {s, t}, {});
        }
      }
    });
  }

  void check_edges() {
    struct Incidence {
      std::uint64_t key;
      std::uint32_t facet;
    };
    auto key_of = [](std::uint32_t a, std::uint32_t b) {
      return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
    };
    std::vector<Incidence> loop_edges;
    std::vector<std::uint64_t> all_edges;
    for (std::uint32_t f = 0; f < plc_.facets.size(); ++f) {
      for (const auto& polygon : plc_.facets[f].polygons) {
        for_each_polygon_edge(polygon, [&](std::uint32_t a, std::uint32_t b) {
          all_edges.push_back(key_of(a, b));
          if (polygon.size() >= 3 && a != b) loop_edges.push_back({key_of(a, b), f});
        });
      }
    }
    std::sort(loop_edges.begin(), loop_edges.end(), [](const Incidence& x, const Incidence& y) {
      return x.key < y.key || (x.key == y.key && x.facet < y.facet);
    });
    for (std::size_t i = 0; i < loop_edges.size();) {
      std::size_t j = i;
      std::vector<std::uint32_t> facets;
      while (j < loop_edges.size() && loop_edges[j].key == loop_edges[i].key) {
        if (facets.empty() || facets.back() != loop_edges[j].facet) facets.push_back(loop_edges[j].facet);
        ++j;
      }
      const auto a = static_cast<std::uint32_t>(loop_edges[i].key >> 32);
      const auto b = static_cast<std::uint32_t>(loop_edges[i].key & 0xffffffffu);
      if (opt_.require_closed && facets.size() == 1) {
        add({PlcIssueKind::OpenBoundary,
             cat("edge ", a) + cat("-", b) + " " +
                 point_text(plc_.points[a]) + " " + point_text(plc_.points[b]) +
                 cat(" bounds only facet ", facets[0]) + ": the boundary is not closed",
             {a, b}, {}, facets, {}});
      }
      if (opt_.require_manifold && facets.size() > 2) {
        add({PlcIssueKind::NonManifoldEdge,
             cat("edge ", a) + cat("-", b) + " " +
                 point_text(plc_.points[a]) + " " + point_text(plc_.points[b]) + " bounds " +
                 std::to_string(facets.size()) + " facets",
             {a, b}, {}, facets, {}});
      }
      i = j;
    }
    if (opt_.allow_free_segments) return;
    std::sort(all_edges.begin(), all_edges.end());
    for (std::uint32_t s = 0; s < plc_.segments.size(); ++s) {
      const auto& seg = plc_.segments[s];
      if (std::binary_search(all_edges.begin(), all_edges.end(), key_of(seg.a, seg.b))) continue;
      add({PlcIssueKind::FreeSegment,
           cat("segment ", s) + cat(" (", seg.a) + "-" +
               std::to_string(seg.b) + ") bounds no facet",
           {seg.a, seg.b}, {s}, {}, {}});
    }
  }

  /// Does the segment from p to q meet any (planar, non-degenerate) facet?
  bool ray_hits(const BoxGrid& grid, const Vec3& p, const Vec3& q) const {
    Box3 box;
    box.extend(p);
    box.extend(q);
    bool hit = false;
    grid.for_each_overlapping(box, [&](std::uint32_t f) {
      if (hit || !frames_[f]) return;
      hit = segment_facet_contact(plc_, plc_.facets[f], *frames_[f], kNoVertex, kNoVertex, p, q) !=
            Contact::None;
    });
    return hit;
  }

  void check_points(const std::vector<Vec3>& points, PlcIssueKind kind, const char* what) {
    if (points.empty()) return;
    if (frames_.size() != plc_.facets.size()) frames_.assign(plc_.facets.size(), std::nullopt);
    std::vector<Box3> boxes(plc_.facets.size());
    Box3 all;
    for (std::size_t f = 0; f < plc_.facets.size(); ++f) {
      if (!frames_[f]) continue;
      boxes[f] = facet_box(plc_.facets[f]);
      all.extend(boxes[f].lo);
      all.extend(boxes[f].hi);
    }
    if (all.lo.x() > all.hi.x()) return;
    const BoxGrid grid(std::move(boxes));
    for (std::uint32_t i = 0; i < points.size(); ++i) {
      const Vec3& p = points[i];
      if (!p.allFinite()) {
        add({kind, std::string(what) + cat(" ", i) + " " + point_text(p) + " is not finite",
             {}, {}, {}, {i}});
        continue;
      }
      bool escapes = false;
      for (int k = 0; k < 3 && !escapes; ++k) {
        const double span = std::max(all.hi[k] - all.lo[k], 1.0);
        for (int dir = -1; dir <= 1 && !escapes; dir += 2) {
          Vec3 q = p;
          q[k] = dir > 0 ? std::max(all.hi[k], p[k]) + span : std::min(all.lo[k], p[k]) - span;
          escapes = !ray_hits(grid, p, q);
        }
      }
      if (escapes) {
        add({kind, std::string(what) + cat(" ", i) + " " + point_text(p) +
                       " lies outside the domain (a ray from it meets no facet)",
             {}, {}, {}, {i}});
      }
    }
  }

  const Plc& plc_;
  const PlcValidationOptions& opt_;
  std::vector<PlcIssue> issues_;
  std::array<std::size_t, kKinds> dropped_{};
  std::vector<std::optional<FacetFrame>> frames_;
  std::vector<Box3> boxes_;
};

ErrorCode code_of(PlcIssueKind kind) {
  switch (kind) {
    case PlcIssueKind::InvalidIndex:
    case PlcIssueKind::NonFiniteCoordinate:
    case PlcIssueKind::FreeSegment:
    case PlcIssueKind::HoleOutside:
    case PlcIssueKind::RegionOutside:
    case PlcIssueKind::Truncated: return ErrorCode::InvalidInput;
    case PlcIssueKind::DuplicateVertex: return ErrorCode::DuplicateVertex;
    case PlcIssueKind::DegenerateSegment:
    case PlcIssueKind::DegenerateFacet: return ErrorCode::DegenerateInput;
    case PlcIssueKind::NonPlanarFacet: return ErrorCode::NonPlanarFacet;
    case PlcIssueKind::Intersection: return ErrorCode::SelfIntersection;
    case PlcIssueKind::OpenBoundary: return ErrorCode::OpenBoundary;
    case PlcIssueKind::NonManifoldEdge: return ErrorCode::NonManifold;
  }
  return ErrorCode::InvalidInput;
}

}  // namespace

const char* to_string(PlcIssueKind kind) {
  switch (kind) {
    case PlcIssueKind::InvalidIndex: return "InvalidIndex";
    case PlcIssueKind::NonFiniteCoordinate: return "NonFiniteCoordinate";
    case PlcIssueKind::DuplicateVertex: return "DuplicateVertex";
    case PlcIssueKind::DegenerateSegment: return "DegenerateSegment";
    case PlcIssueKind::DegenerateFacet: return "DegenerateFacet";
    case PlcIssueKind::NonPlanarFacet: return "NonPlanarFacet";
    case PlcIssueKind::Intersection: return "Intersection";
    case PlcIssueKind::OpenBoundary: return "OpenBoundary";
    case PlcIssueKind::NonManifoldEdge: return "NonManifoldEdge";
    case PlcIssueKind::FreeSegment: return "FreeSegment";
    case PlcIssueKind::HoleOutside: return "HoleOutside";
    case PlcIssueKind::RegionOutside: return "RegionOutside";
    case PlcIssueKind::Truncated: return "Truncated";
  }
  return "Unknown";
}

std::vector<PlcIssue> validate_plc(const Plc& plc, const PlcValidationOptions& options) {
  return Validator(plc, options).run();
}

Error issues_to_error(const std::vector<PlcIssue>& issues, std::size_t max_listed) {
  if (issues.empty()) return make_error(ErrorCode::InvalidInput, "no issue");
  std::string message = cat("invalid PLC: ", issues.size()) + " issue(s)";
  for (std::size_t i = 0; i < issues.size() && i < max_listed; ++i) {
    message += cat("\n  ", to_string(issues[i].kind)) + ": " + issues[i].message;
  }
  if (issues.size() > max_listed) {
    message += cat("\n  ... and ", issues.size() - max_listed) + " more";
  }
  Error error = make_error(code_of(issues.front().kind), std::move(message));
  const auto& first = issues.front();
  error.entity_ids = !first.facets.empty() ? first.facets : first.vertices;
  return error;
}

}  // namespace delmesh
