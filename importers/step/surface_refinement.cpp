// Flips and longest-edge bisection on CAD face tessellations (see surface_refinement.h).
//
// Each round collects the triangles whose smallest 3D angle is below the bound and
// bisects the longest 3D edge of each: an edge inside a face is split at its midpoint in
// the parameter plane (the new node is evaluated on the surface); an edge on a CAD edge
// is split at the curve-parameter midpoint in every face using it, which keeps the
// faces' discretisations identical along shared edges. After every round, edge flips
// that raise the smallest angle of the two triangles (the max-min angle criterion, which
// in the plane yields the Delaunay triangulation) restore good connectivity. A flip or
// split is applied only if all triangles it creates are positively oriented in the
// parameter plane (exact orient2d), so every face's triangulation stays a valid
// triangulation of its parameter domain. Rounds stop when no triangle can be improved,
// the edges to split are shorter than the length floor, or the point budget is spent.
#include "importers/step/surface_refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>

#include "toolkit/predicates/predicates.h"

namespace delmesh::step {
namespace {

using Key = std::uint64_t;
using Triangle = std::array<std::uint32_t, 3>;

Key key_of(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<Key>(a) << 32) | b;
}

/// Smallest corner angle (radians) of a 3D triangle; 0 for a degenerate one.
double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto corner = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, v = r - p;
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  const double angle = std::min({corner(a, b, c), corner(b, c, a), corner(c, a, b)});
  return std::isfinite(angle) ? angle : 0.0;
}

struct Segment {
  std::size_t edge = 0;
  bool ambiguous = false;  ///< two CAD edges share these end vertices: never split
  std::vector<std::size_t> faces;
};

class Refiner {
 public:
  Refiner(SurfaceMeshes& meshes, std::vector<Vec3>& points, const SurfaceRefinementOptions& options,
          const SurfacePoint& surface_point, const EdgePoint& edge_point)
      : meshes_(meshes), points_(points), options_(options), surface_point_(surface_point),
        edge_point_(edge_point), state_(meshes.faces.size()) {}

  SurfaceRefinementStats run() {
    build_segments();
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) prepare_face(f);
    stats_.min_angle_before_deg = smallest_angle_deg();
    const std::size_t budget_end = points_.size() + options_.max_new_points;
    const double bound = options_.min_angle_deg * std::numbers::pi / 180.0;
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) flip_face(f);
    for (int round = 0; round < 64; ++round) {
      // The worst triangles of the whole model first, so the budget goes where it matters.
      std::vector<std::tuple<double, std::size_t, std::size_t>> bad;
      for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
        if (!state_[f].refinable) continue;
        for (std::size_t t = 0; t < face(f).triangles.size(); ++t) {
          const double q = quality(f, face(f).triangles[t]);
          if (q < bound) bad.emplace_back(q, f, t);
        }
      }
      std::sort(bad.begin(), bad.end());
      bool split_any = false;
      for (const auto& [q, f, t] : bad) {
        if (points_.size() >= budget_end) break;
        if (quality(f, face(f).triangles[t]) >= bound) continue;
        split_any = split_longest_edge(f, t) || split_any;
      }
      for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
        if (state_[f].touched) flip_face(f);
        state_[f].touched = false;
      }
      if (!split_any || points_.size() >= budget_end) break;
    }
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      if (state_[f].reversed) {
        for (Triangle& t : face(f).triangles) std::swap(t[1], t[2]);
      }
    }
    stats_.min_angle_after_deg = smallest_angle_deg();
    return stats_;
  }

 private:
  struct FaceState {
    bool refinable = false;  ///< flips and interior splits (UV-valid, refine requested)
    bool uv_valid = false;   ///< all triangles positively oriented in the parameter plane
    bool reversed = false;   ///< triangles were reversed to orient them positively
    bool touched = false;    ///< split since the last flip pass
    std::unordered_map<Key, std::array<std::int64_t, 2>> edge_triangles;  ///< local edge -> triangles
    std::unordered_map<Key, std::vector<Key>> segment_edges;  ///< CAD segment -> local edges on it
  };

  SurfaceMeshes::Face& face(std::size_t f) { return meshes_.faces[f]; }

  Sign uv_orient(std::size_t f, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const auto& uv = face(f).uv;
    return predicates::orient2d(uv[a].data(), uv[b].data(), uv[c].data());
  }

  Vec3 position(std::size_t f, std::uint32_t local) { return points_[face(f).node_vertex[local]]; }

  bool degenerate(std::size_t f, const Triangle& t) {
    const auto& v = face(f).node_vertex;
    return v[t[0]] == v[t[1]] || v[t[1]] == v[t[2]] || v[t[2]] == v[t[0]];
  }

  /// Smallest 3D angle; +infinity for triangles refinement leaves alone (degenerate ones
  /// at poles collapse on purpose).
  double quality(std::size_t f, const Triangle& t) {
    if (degenerate(f, t)) return std::numeric_limits<double>::infinity();
    return min_angle(position(f, t[0]), position(f, t[1]), position(f, t[2]));
  }

  double smallest_angle_deg() {
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      if (!face(f).refine) continue;
      for (const Triangle& t : face(f).triangles) smallest = std::min(smallest, quality(f, t));
    }
    return std::isfinite(smallest) ? smallest * 180.0 / std::numbers::pi : 180.0;
  }

  void build_segments() {
    for (std::size_t e = 0; e < meshes_.edges.size(); ++e) {
      const auto& v = meshes_.edges[e].vertices;
      for (std::uint32_t vertex : v) vertex_edges_[vertex].push_back(e);
      for (std::size_t k = 0; k + 1 < v.size(); ++k) {
        if (v[k] == v[k + 1]) continue;
        auto [it, inserted] = segments_.try_emplace(key_of(v[k], v[k + 1]));
        if (inserted) {
          it->second.edge = e;
        } else if (it->second.edge != e) {
          it->second.ambiguous = true;
        }
      }
    }
  }

  void add_triangle_edges(std::size_t f, std::size_t t) {
    const Triangle& tri = face(f).triangles[t];
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = state_[f].edge_triangles.try_emplace(key_of(tri[k], tri[(k + 1) % 3]),
                                                                 std::array<std::int64_t, 2>{-1, -1});
      (it->second[0] < 0 ? it->second[0] : it->second[1]) = static_cast<std::int64_t>(t);
    }
  }

  void remove_triangle_edges(std::size_t f, std::size_t t) {
    const Triangle& tri = face(f).triangles[t];
    for (int k = 0; k < 3; ++k) {
      const Key key = key_of(tri[k], tri[(k + 1) % 3]);
      auto it = state_[f].edge_triangles.find(key);
      if (it == state_[f].edge_triangles.end()) continue;
      if (it->second[0] == static_cast<std::int64_t>(t)) it->second[0] = it->second[1];
      it->second[1] = -1;
      if (it->second[0] < 0) state_[f].edge_triangles.erase(it);
    }
  }

  void register_segment_edge(std::size_t f, std::uint32_t i, std::uint32_t j) {
    const auto& v = face(f).node_vertex;
    auto it = segments_.find(key_of(v[i], v[j]));
    if (it == segments_.end()) return;
    state_[f].segment_edges[it->first].push_back(key_of(i, j));
    if (std::find(it->second.faces.begin(), it->second.faces.end(), f) == it->second.faces.end()) {
      it->second.faces.push_back(f);
    }
  }

  void prepare_face(std::size_t f) {
    FaceState& state = state_[f];
    int positive = 0, negative = 0;
    for (const Triangle& t : face(f).triangles) {
      const Sign s = uv_orient(f, t[0], t[1], t[2]);
      positive += s == Sign::Positive;
      negative += s == Sign::Negative;
    }
    // Flat triangles (zero area in the parameter plane) are tolerated: flips remove them.
    const int n = static_cast<int>(face(f).triangles.size());
    if (positive == 0 && negative > 0) {
      for (Triangle& t : face(f).triangles) std::swap(t[1], t[2]);
      state.reversed = true;
    }
    state.uv_valid = n > 0 && (positive == 0 || negative == 0) && positive + negative > 0;
    state.refinable = state.uv_valid && face(f).refine;
    for (std::size_t t = 0; t < face(f).triangles.size(); ++t) add_triangle_edges(f, t);
    for (const auto& [key, tris] : state.edge_triangles) {
      register_segment_edge(f, static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key));
    }
  }

  /// Rotates `t` so that it starts with edge (a, b) in its own order; false if it holds
  /// the edge the other way round.
  static bool rotate_to(Triangle& t, std::uint32_t a, std::uint32_t b) {
    for (int k = 0; k < 3; ++k) {
      if (t[0] == a && t[1] == b) return true;
      std::rotate(t.begin(), t.begin() + 1, t.end());
    }
    return false;
  }

  void flip_face(std::size_t f) {
    if (!state_[f].refinable) return;
    for (int pass = 0; pass < 32; ++pass) {
      std::vector<Key> edges;
      for (const auto& [key, tris] : state_[f].edge_triangles) {
        if (tris[1] >= 0) edges.push_back(key);
      }
      std::sort(edges.begin(), edges.end());
      std::size_t flips = 0;
      for (Key key : edges) flips += try_flip(f, key) ? 1 : 0;
      stats_.flips += flips;
      if (flips == 0) break;
    }
  }

  bool is_segment(std::size_t f, std::uint32_t i, std::uint32_t j) {
    const auto& v = face(f).node_vertex;
    return segments_.count(key_of(v[i], v[j])) > 0;
  }

  bool try_flip(std::size_t f, Key key) {
    FaceState& state = state_[f];
    auto it = state.edge_triangles.find(key);
    if (it == state.edge_triangles.end() || it->second[1] < 0) return false;
    const auto p = static_cast<std::uint32_t>(key >> 32);
    const auto q = static_cast<std::uint32_t>(key);
    if (is_segment(f, p, q)) return false;
    const std::size_t t1 = static_cast<std::size_t>(it->second[0]);
    const std::size_t t2 = static_cast<std::size_t>(it->second[1]);
    Triangle a = face(f).triangles[t1];
    Triangle b = face(f).triangles[t2];
    if (!rotate_to(a, p, q)) {
      if (!rotate_to(a, q, p)) return false;
    }
    if (!rotate_to(b, a[1], a[0])) return false;
    const std::uint32_t k = a[2], l = b[2];
    if (k == l || state.edge_triangles.count(key_of(k, l)) > 0 || is_segment(f, k, l)) return false;
    const Triangle n1{a[0], l, k}, n2{a[1], k, l};
    if (degenerate(f, a) || degenerate(f, b) || degenerate(f, n1) || degenerate(f, n2)) return false;
    if (uv_orient(f, n1[0], n1[1], n1[2]) != Sign::Positive ||
        uv_orient(f, n2[0], n2[1], n2[2]) != Sign::Positive) {
      return false;
    }
    const double before = std::min(quality(f, a), quality(f, b));
    const double after = std::min(quality(f, n1), quality(f, n2));
    if (!(after > before + 1e-9)) return false;
    remove_triangle_edges(f, t1);
    remove_triangle_edges(f, t2);
    face(f).triangles[t1] = n1;
    face(f).triangles[t2] = n2;
    add_triangle_edges(f, t1);
    add_triangle_edges(f, t2);
    return true;
  }

  /// Longest 3D edge of a triangle as (local i, local j, length).
  std::tuple<std::uint32_t, std::uint32_t, double> longest_edge(std::size_t f, const Triangle& tri) {
    int longest = 0;
    double length = -1.0;
    for (int k = 0; k < 3; ++k) {
      const double l = (position(f, tri[(k + 1) % 3]) - position(f, tri[k])).norm();
      if (l > length) {
        length = l;
        longest = k;
      }
    }
    return {tri[longest], tri[(longest + 1) % 3], length};
  }

  /// Rivara's longest-edge propagation path (LEPP): walk to the neighbour across the
  /// longest edge while that neighbour has a longer edge, then bisect the terminal edge
  /// (shared longest edge of two triangles, or a CAD segment). Bisecting only longest
  /// edges never lets angles fall below half the smallest angle already there.
  bool split_longest_edge(std::size_t f, std::size_t t) {
    std::size_t current = t;
    for (int step = 0; step < 256; ++step) {
      const auto [i, j, length] = longest_edge(f, face(f).triangles[current]);
      if (!(length > options_.min_edge_length)) return false;
      const auto& v = face(f).node_vertex;
      const Key global = key_of(v[i], v[j]);
      if (segments_.count(global) > 0) {
        const auto local = state_[f].segment_edges.find(global);
        if (local == state_[f].segment_edges.end() ||
            std::find(local->second.begin(), local->second.end(), key_of(i, j)) == local->second.end()) {
          return false;
        }
        return split_segment(global);
      }
      if (on_one_cad_edge(v[i], v[j])) return false;
      const auto adjacent = state_[f].edge_triangles.find(key_of(i, j));
      if (adjacent == state_[f].edge_triangles.end() || adjacent->second[1] < 0) return false;
      const auto other = static_cast<std::size_t>(
          adjacent->second[0] == static_cast<std::int64_t>(current) ? adjacent->second[1] : adjacent->second[0]);
      const auto [oi, oj, other_length] = longest_edge(f, face(f).triangles[other]);
      if (key_of(oi, oj) == key_of(i, j) || other_length <= length) return split_interior_edge(f, i, j);
      current = other;
    }
    return false;
  }

  /// a and b are two apart on one CAD edge: the chord of a flat triangle BRepMesh leaves
  /// along a boundary, whose midpoint would duplicate the boundary node between them.
  bool on_one_cad_edge(std::uint32_t a, std::uint32_t b) const {
    const auto ea = vertex_edges_.find(a);
    const auto eb = vertex_edges_.find(b);
    if (ea == vertex_edges_.end() || eb == vertex_edges_.end()) return false;
    for (std::size_t e : ea->second) {
      if (std::find(eb->second.begin(), eb->second.end(), e) == eb->second.end()) continue;
      const auto& v = meshes_.edges[e].vertices;
      for (std::size_t k = 0; k + 2 < v.size(); ++k) {
        if ((v[k] == a && v[k + 2] == b) || (v[k] == b && v[k + 2] == a)) return true;
      }
    }
    return false;
  }

  /// The triangles on local edge (i, j) of face f, each split by local node m: checks
  /// that all new triangles are positively oriented in the parameter plane.
  bool split_is_valid(std::size_t f, std::uint32_t i, std::uint32_t j, const Point2& uv_m) {
    if (!state_[f].uv_valid) return true;
    auto it = state_[f].edge_triangles.find(key_of(i, j));
    if (it == state_[f].edge_triangles.end()) return false;
    const auto& uv = face(f).uv;
    for (std::int64_t t : it->second) {
      if (t < 0) continue;
      Triangle tri = face(f).triangles[static_cast<std::size_t>(t)];
      if (!rotate_to(tri, i, j) && !rotate_to(tri, j, i)) return false;
      const double* m = uv_m.data();
      if (predicates::orient2d(uv[tri[0]].data(), m, uv[tri[2]].data()) != Sign::Positive ||
          predicates::orient2d(m, uv[tri[1]].data(), uv[tri[2]].data()) != Sign::Positive) {
        return false;
      }
    }
    return true;
  }

  /// Splitting the triangles on local edge (i, j) of face f at 3D point p keeps every
  /// new triangle at least half as good as the triangle it comes from (bisection of a
  /// longest edge does; a point off the chord on a curved surface may not).
  bool keeps_angles(std::size_t f, std::uint32_t i, std::uint32_t j, const Vec3& p) {
    auto it = state_[f].edge_triangles.find(key_of(i, j));
    if (it == state_[f].edge_triangles.end()) return false;
    for (std::int64_t t : it->second) {
      if (t < 0) continue;
      Triangle tri = face(f).triangles[static_cast<std::size_t>(t)];
      if (degenerate(f, tri)) continue;
      if (!rotate_to(tri, i, j)) rotate_to(tri, j, i);
      const double before = quality(f, tri);
      const Vec3 a = position(f, tri[0]), b = position(f, tri[1]), c = position(f, tri[2]);
      if (std::min(min_angle(a, p, c), min_angle(p, b, c)) < 0.5 * before) return false;
    }
    return true;
  }

  /// Splits the triangles on local edge (i, j) of face f at a new local node.
  void apply_split(std::size_t f, std::uint32_t i, std::uint32_t j, const Point2& uv_m,
                   std::uint32_t vertex) {
    SurfaceMeshes::Face& mesh = face(f);
    state_[f].touched = true;
    const auto m = static_cast<std::uint32_t>(mesh.uv.size());
    mesh.uv.push_back(uv_m);
    mesh.node_vertex.push_back(vertex);
    const std::array<std::int64_t, 2> tris = state_[f].edge_triangles.at(key_of(i, j));
    for (std::int64_t t : tris) {
      if (t < 0) continue;
      const auto index = static_cast<std::size_t>(t);
      Triangle tri = mesh.triangles[index];
      if (!rotate_to(tri, i, j)) rotate_to(tri, j, i);
      remove_triangle_edges(f, index);
      mesh.triangles[index] = {tri[0], m, tri[2]};
      mesh.triangles.push_back({m, tri[1], tri[2]});
      add_triangle_edges(f, index);
      add_triangle_edges(f, mesh.triangles.size() - 1);
    }
  }

  bool split_interior_edge(std::size_t f, std::uint32_t i, std::uint32_t j) {
    auto it = state_[f].edge_triangles.find(key_of(i, j));
    if (it == state_[f].edge_triangles.end() || it->second[1] < 0) return false;
    const auto& uv = face(f).uv;
    const Point2 uv_m{0.5 * (uv[i][0] + uv[j][0]), 0.5 * (uv[i][1] + uv[j][1])};
    if (!split_is_valid(f, i, j, uv_m)) return false;
    const Vec3 p = surface_point_(f, uv_m);
    if (!p.allFinite() || !keeps_angles(f, i, j, p)) return false;
    points_.push_back(p);
    apply_split(f, i, j, uv_m, static_cast<std::uint32_t>(points_.size() - 1));
    ++stats_.interior_splits;
    return true;
  }

  bool split_segment(Key key) {
    auto found = segments_.find(key);
    if (found == segments_.end() || found->second.ambiguous) return false;
    const Segment segment = found->second;
    const auto a = static_cast<std::uint32_t>(key >> 32);
    const auto b = static_cast<std::uint32_t>(key);
    SurfaceMeshes::Edge& edge = meshes_.edges[segment.edge];
    std::size_t k = 0;
    while (k + 1 < edge.vertices.size() && key_of(edge.vertices[k], edge.vertices[k + 1]) != key) ++k;
    if (k + 1 >= edge.vertices.size()) return false;
    // Local edges on the segment in every face, with the parameter-plane midpoints.
    struct LocalSplit {
      std::size_t face;
      std::uint32_t i, j;
      Point2 uv;
    };
    std::vector<LocalSplit> splits;
    for (std::size_t f : segment.faces) {
      auto local = state_[f].segment_edges.find(key);
      if (local == state_[f].segment_edges.end()) continue;
      for (Key local_key : local->second) {
        const auto i = static_cast<std::uint32_t>(local_key >> 32);
        const auto j = static_cast<std::uint32_t>(local_key);
        const auto& uv = face(f).uv;
        splits.push_back({f, i, j, {0.5 * (uv[i][0] + uv[j][0]), 0.5 * (uv[i][1] + uv[j][1])}});
        if (!split_is_valid(f, i, j, splits.back().uv)) return false;
      }
    }
    const double t = 0.5 * (edge.parameters[k] + edge.parameters[k + 1]);
    const Vec3 p = edge_point_(segment.edge, t);
    if (!p.allFinite()) return false;
    for (const LocalSplit& split : splits) {
      if (!keeps_angles(split.face, split.i, split.j, p)) return false;
    }
    points_.push_back(p);
    const auto m = static_cast<std::uint32_t>(points_.size() - 1);
    edge.vertices.insert(edge.vertices.begin() + static_cast<std::ptrdiff_t>(k) + 1, m);
    vertex_edges_[m].push_back(segment.edge);
    edge.parameters.insert(edge.parameters.begin() + static_cast<std::ptrdiff_t>(k) + 1, t);
    segments_.erase(found);
    Segment first = segment, second = segment;
    segments_[key_of(a, m)] = first;
    segments_[key_of(m, b)] = second;
    for (std::size_t f : segment.faces) state_[f].segment_edges.erase(key);
    for (const LocalSplit& s : splits) {
      apply_split(s.face, s.i, s.j, s.uv, m);
      const auto local_m = static_cast<std::uint32_t>(face(s.face).uv.size() - 1);
      const auto& v = face(s.face).node_vertex;
      state_[s.face].segment_edges[key_of(v[s.i], m)].push_back(key_of(s.i, local_m));
      state_[s.face].segment_edges[key_of(m, v[s.j])].push_back(key_of(local_m, s.j));
    }
    ++stats_.boundary_splits;
    return true;
  }

  SurfaceMeshes& meshes_;
  std::vector<Vec3>& points_;
  SurfaceRefinementOptions options_;
  const SurfacePoint& surface_point_;
  const EdgePoint& edge_point_;
  std::vector<FaceState> state_;
  std::unordered_map<Key, Segment> segments_;
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> vertex_edges_;  ///< CAD edges through a vertex
  SurfaceRefinementStats stats_;
};

}  // namespace

SurfaceRefinementStats refine_surface_meshes(SurfaceMeshes& meshes, std::vector<Vec3>& points,
                                             const SurfaceRefinementOptions& options,
                                             const SurfacePoint& surface_point,
                                             const EdgePoint& edge_point) {
  return Refiner(meshes, points, options, surface_point, edge_point).run();
}

}  // namespace delmesh::step
