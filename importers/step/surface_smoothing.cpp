// Local optimisation of CAD face tessellations (see surface_smoothing.h).
#include "importers/step/surface_smoothing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <Eigen/Geometry>

#include "importers/step/surface_mesh_quality.h"
#include "importers/step/triangle_corners.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::step {
namespace {

using Key = std::uint64_t;
using Triangle = std::array<std::uint32_t, 3>;

/// A move or flip may not turn a triangle farther than this (radians) from the surface
/// normal at its parameter centroid, unless it already was.
constexpr double kMaxNormalDeviation = std::numbers::pi / 2.0;
/// A move or flip may bend the face (the angle between the normals of two triangles
/// sharing an edge it changes) up to this (radians, 30 degrees), or as sharply as before.
constexpr double kMaxBend = std::numbers::pi / 6.0;
/// Compass search: evaluations per node and move, and the smallest step as a fraction
/// of the first.
constexpr int kMaxEvaluations = 40;
constexpr double kSmallestStep = 1.0 / 64.0;
/// A move or flip must raise the smallest angle by more than this (radians).
constexpr double kGain = 1e-9;
/// Flip sweeps per pass.
constexpr int kFlipSweeps = 4;

/// The three corners of 3D triangle (a, b, c).
std::array<double, 3> corners(const Vec3& a, const Vec3& b, const Vec3& c) {
  return {corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)};
}

Vec3 unit_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0.0 ? Vec3(n / length) : Vec3(Vec3::Zero());
}

double angle_between(const Vec3& m, const Vec3& n) {
  if (m.isZero() || n.isZero()) return 0.0;
  return std::atan2(m.cross(n).norm(), m.dot(n));
}

class Smoother {
 public:
  Smoother(SurfaceMeshes& meshes, std::vector<Vec3>& points, const SurfaceSmoothingOptions& options,
           const SurfacePoint& surface_point, const SurfaceNormal& surface_normal)
      : meshes_(meshes), points_(points), options_(options), surface_point_(surface_point),
        surface_normal_(surface_normal), bound_(options.min_angle_deg * std::numbers::pi / 180.0) {}

  SurfaceSmoothingStats run() {
    for (const SurfaceMeshes::Edge& edge : meshes_.edges) {
      for (std::uint32_t v : edge.vertices) on_cad_edge_.insert(v);
      for (std::size_t k = 0; k + 1 < edge.vertices.size(); ++k) segments_.insert(edge_key(edge.vertices[k], edge.vertices[k + 1]));
    }
    global_edges_ = count_face_edges(meshes_);
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      if (meshes_.faces[f].refine) smooth_face(f);
    }
    return stats_;
  }

 private:
  struct FaceData {
    Sign orientation = Sign::Zero;
    std::vector<bool> movable;                                    ///< local node
    std::unordered_set<std::uint32_t> small_corners;             ///< PLC vertices
    std::vector<std::vector<std::uint32_t>> star;                ///< local node -> triangles
    std::unordered_map<Key, std::array<std::int64_t, 2>> edge_triangles;  ///< local edge
  };

  SurfaceMeshes::Face& face(std::size_t f) { return meshes_.faces[f]; }
  const Vec3& position(std::size_t f, std::uint32_t local) const { return points_[meshes_.faces[f].node_vertex[local]]; }

  bool degenerate(std::size_t f, const Triangle& t) const {
    const auto& v = meshes_.faces[f].node_vertex;
    return v[t[0]] == v[t[1]] || v[t[1]] == v[t[2]] || v[t[2]] == v[t[0]];
  }

  /// The triangle's smallest angle is fixed by the input: it lies between two CAD
  /// segments, or the triangle touches a small face corner.
  bool forced(std::size_t f, const FaceData& data, const Triangle& t, const std::array<Vec3, 3>& p) const {
    const auto& v = meshes_.faces[f].node_vertex;
    for (int k = 0; k < 3; ++k) {
      if (data.small_corners.count(v[t[k]]) > 0) return true;
    }
    const std::array<double, 3> a = corners(p[0], p[1], p[2]);
    const int k = static_cast<int>(std::min_element(a.begin(), a.end()) - a.begin());
    return segments_.count(edge_key(v[t[k]], v[t[(k + 1) % 3]])) > 0 && segments_.count(edge_key(v[t[k]], v[t[(k + 2) % 3]])) > 0;
  }

  double normal_deviation(std::size_t f, const FaceData& data, const std::array<Vec3, 3>& p,
                          const std::array<Point2, 3>& uv) const {
    if (!surface_normal_) return 0.0;
    const Point2 centre{(uv[0][0] + uv[1][0] + uv[2][0]) / 3.0, (uv[0][1] + uv[1][1] + uv[2][1]) / 3.0};
    const Vec3 surface = surface_normal_(f, centre);
    if (!surface.allFinite()) return 0.0;
    // Su x Sv is the normal of triangles positively oriented in the parameter plane.
    const double side = data.orientation == Sign::Positive ? 1.0 : -1.0;
    return angle_between(side * unit_normal(p[0], p[1], p[2]), surface);
  }

  void build(std::size_t f, FaceData& data) {
    const SurfaceMeshes::Face& mesh = face(f);
    data.star.assign(mesh.uv.size(), {});
    data.edge_triangles.clear();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Triangle& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) {
        data.star[tri[k]].push_back(static_cast<std::uint32_t>(t));
        auto [it, inserted] = data.edge_triangles.try_emplace(edge_key(tri[k], tri[(k + 1) % 3]), std::array<std::int64_t, 2>{-1, -1});
        (it->second[0] < 0 ? it->second[0] : it->second[1]) = static_cast<std::int64_t>(t);
      }
    }
  }

  void smooth_face(std::size_t f) {
    SurfaceMeshes::Face& mesh = face(f);
    FaceData data;
    int positive = 0, negative = 0;
    for (const Triangle& t : mesh.triangles) {
      const Sign s = predicates::orient2d(mesh.uv[t[0]].data(), mesh.uv[t[1]].data(), mesh.uv[t[2]].data());
      positive += s == Sign::Positive;
      negative += s == Sign::Negative;
    }
    if ((positive > 0) == (negative > 0)) return;  // not a valid triangulation of its parameter domain
    data.orientation = positive > 0 ? Sign::Positive : Sign::Negative;
    // Nodes on CAD edges, and nodes whose PLC vertex has several copies (a pole), stay.
    std::unordered_map<std::uint32_t, int> copies;
    for (std::uint32_t v : mesh.node_vertex) ++copies[v];
    data.movable.assign(mesh.uv.size(), false);
    for (std::size_t n = 0; n < mesh.uv.size(); ++n) {
      data.movable[n] = on_cad_edge_.count(mesh.node_vertex[n]) == 0 && copies[mesh.node_vertex[n]] == 1;
    }
    // Small face corners, as the quality measure sees them.
    {
      std::unordered_map<Key, int> sides;
      std::unordered_map<std::uint32_t, double> angle_sum;
      for (const Triangle& t : mesh.triangles) {
        if (degenerate(f, t)) continue;
        const std::array<double, 3> a = corners(position(f, t[0]), position(f, t[1]), position(f, t[2]));
        for (int k = 0; k < 3; ++k) {
          ++sides[edge_key(mesh.node_vertex[t[k]], mesh.node_vertex[t[(k + 1) % 3]])];
          angle_sum[mesh.node_vertex[t[k]]] += a[k];
        }
      }
      for (const auto& [side, uses] : sides) {
        if (uses != 1) continue;
        for (const auto v : {static_cast<std::uint32_t>(side >> 32), static_cast<std::uint32_t>(side)}) {
          if (angle_sum[v] * 180.0 / std::numbers::pi < kSmallFaceCornerDeg) data.small_corners.insert(v);
        }
      }
    }
    for (int pass = 0; pass < options_.passes; ++pass) {
      build(f, data);
      std::size_t changes = flip_sweeps(f, data);
      build(f, data);
      for (std::uint32_t n = 0; n < mesh.uv.size(); ++n) {
        if (data.movable[n] && move_node(f, data, n)) ++changes;
      }
      if (changes == 0) break;
    }
  }

  /// Star of node n with n at (uv, p): the smallest angle of its triangles that are not
  /// forced, or nothing if the position is not allowed.
  struct StarState {
    double objective = std::numeric_limits<double>::infinity();
    std::vector<double> forced_min;   ///< per star triangle, its smallest angle if forced (else +inf)
    std::vector<double> deviation;    ///< per star triangle
    double max_bend = 0.0;
  };

  std::optional<StarState> evaluate(std::size_t f, const FaceData& data, std::uint32_t n, const Point2& uv_n,
                                    const Vec3& p_n, const StarState* before) const {
    const SurfaceMeshes::Face& mesh = meshes_.faces[f];
    StarState state;
    const auto& star = data.star[n];
    state.forced_min.assign(star.size(), std::numeric_limits<double>::infinity());
    state.deviation.assign(star.size(), 0.0);
    const auto pos = [&](std::uint32_t local) -> const Vec3& { return local == n ? p_n : position(f, local); };
    const auto par = [&](std::uint32_t local) -> const Point2& { return local == n ? uv_n : mesh.uv[local]; };
    std::unordered_map<std::uint32_t, Vec3> normals;  // star triangle -> unit normal
    for (std::size_t s = 0; s < star.size(); ++s) {
      const Triangle& t = mesh.triangles[star[s]];
      const std::array<Point2, 3> uv{par(t[0]), par(t[1]), par(t[2])};
      if (predicates::orient2d(uv[0].data(), uv[1].data(), uv[2].data()) != data.orientation) return std::nullopt;
      if (degenerate(f, t)) continue;
      const std::array<Vec3, 3> p{pos(t[0]), pos(t[1]), pos(t[2])};
      const std::array<double, 3> a = corners(p[0], p[1], p[2]);
      const double smallest = std::min({a[0], a[1], a[2]});
      if (forced(f, data, t, p)) {
        state.forced_min[s] = smallest;
        if (before && smallest < std::min(before->forced_min[s], bound_)) return std::nullopt;
      } else {
        state.objective = std::min(state.objective, smallest);
      }
      state.deviation[s] = normal_deviation(f, data, p, uv);
      if (before && state.deviation[s] > std::max(kMaxNormalDeviation, before->deviation[s])) return std::nullopt;
      normals[star[s]] = unit_normal(p[0], p[1], p[2]);
    }
    // How sharply the face bends across the edges of the star's triangles.
    for (std::uint32_t t : star) {
      const Triangle& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) {
        const auto it = data.edge_triangles.find(edge_key(tri[k], tri[(k + 1) % 3]));
        if (it == data.edge_triangles.end() || it->second[1] < 0) continue;
        const auto other = static_cast<std::uint32_t>(it->second[0] == t ? it->second[1] : it->second[0]);
        if (degenerate(f, mesh.triangles[other]) || degenerate(f, tri)) continue;
        Vec3 m = normals.count(other) > 0 ? normals[other] : Vec3(Vec3::Zero());
        if (normals.count(other) == 0) {
          const Triangle& o = mesh.triangles[other];
          m = unit_normal(pos(o[0]), pos(o[1]), pos(o[2]));
        }
        state.max_bend = std::max(state.max_bend, angle_between(normals[t], m));
      }
    }
    if (before && state.max_bend > std::max(kMaxBend, before->max_bend)) return std::nullopt;
    return state;
  }

  /// Compass search for node n of face f; true if it moved.
  bool move_node(std::size_t f, const FaceData& data, std::uint32_t n) {
    SurfaceMeshes::Face& mesh = face(f);
    const auto& star = data.star[n];
    if (star.empty()) return false;
    const std::optional<StarState> current = evaluate(f, data, n, mesh.uv[n], position(f, n), nullptr);
    if (!current || !(current->objective < bound_)) return false;
    // The star's nodes and the least-squares affine map from their parameters to 3D.
    std::vector<std::uint32_t> nodes;
    for (std::uint32_t t : star) {
      for (std::uint32_t m : mesh.triangles[t]) {
        if (std::find(nodes.begin(), nodes.end(), m) == nodes.end()) nodes.push_back(m);
      }
    }
    Eigen::Vector2d mu = Eigen::Vector2d::Zero();
    Vec3 mp = Vec3::Zero();
    for (std::uint32_t m : nodes) {
      mu += Eigen::Vector2d(mesh.uv[m][0], mesh.uv[m][1]) / static_cast<double>(nodes.size());
      mp += position(f, m) / static_cast<double>(nodes.size());
    }
    Eigen::Matrix2d uu = Eigen::Matrix2d::Zero();
    Eigen::Matrix<double, 3, 2> pu = Eigen::Matrix<double, 3, 2>::Zero();
    double spread = 0.0;
    for (std::uint32_t m : nodes) {
      const Eigen::Vector2d du = Eigen::Vector2d(mesh.uv[m][0], mesh.uv[m][1]) - mu;
      uu += du * du.transpose();
      pu += (position(f, m) - mp) * du.transpose();
      if (m != n) spread += (position(f, m) - position(f, n)).norm() / static_cast<double>(nodes.size() - 1);
    }
    const double det = uu.determinant();
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
    const Eigen::Matrix2d g = (pu * uu.inverse()).transpose() * (pu * uu.inverse());
    if (!(g(0, 0) > 0.0)) return false;
    const double l11 = std::sqrt(g(0, 0));
    const double l12 = g(0, 1) / l11;
    const double rest = g(1, 1) - l12 * l12;
    if (!(rest > 0.0) || !std::isfinite(rest)) return false;
    const double l22 = std::sqrt(rest);
    // A 3D step of length s in tangent direction phi, as a parameter step.
    const auto step_uv = [&](double s, double phi) {
      const double v1 = s * std::sin(phi) / l22;
      const double v0 = (s * std::cos(phi) - l12 * v1) / l11;
      return Point2{v0, v1};
    };
    Point2 best_uv = mesh.uv[n];
    Vec3 best_p = position(f, n);
    StarState best = *current;
    int evaluations = 0;
    const auto try_at = [&](const Point2& uv) {
      ++evaluations;
      // A face with offsets (loose tolerances, SurfaceMeshes::Face::offset): the node keeps its own.
      const Vec3 p = surface_point_(f, uv) + (mesh.offset.empty() ? Vec3(Vec3::Zero()) : mesh.offset[n]);
      if (!p.allFinite()) return false;
      const std::optional<StarState> state = evaluate(f, data, n, uv, p, &*current);
      if (!state || !(state->objective > best.objective + kGain)) return false;
      best = *state;
      best_uv = uv;
      best_p = p;
      return true;
    };
    // The parameter centroid of the link first (Laplacian smoothing), then the compass.
    Point2 centroid{0.0, 0.0};
    for (std::uint32_t m : nodes) {
      if (m == n) continue;
      centroid = {centroid[0] + mesh.uv[m][0] / static_cast<double>(nodes.size() - 1),
                  centroid[1] + mesh.uv[m][1] / static_cast<double>(nodes.size() - 1)};
    }
    try_at(centroid);
    const double first_step = 0.25 * spread;
    double step = first_step;
    while (step > kSmallestStep * first_step && evaluations < kMaxEvaluations) {
      bool improved = false;
      const Point2 from = best_uv;
      for (int d = 0; d < 8 && evaluations < kMaxEvaluations; ++d) {
        const Point2 delta = step_uv(step, d * std::numbers::pi / 4.0);
        improved = try_at({from[0] + delta[0], from[1] + delta[1]}) || improved;
      }
      if (!improved) step *= 0.5;
    }
    if (best_uv == mesh.uv[n]) return false;
    mesh.uv[n] = best_uv;
    points_[mesh.node_vertex[n]] = best_p;
    ++stats_.moves;
    return true;
  }

  /// Max-min angle flips of the edges inside face f, sweeping until none applies.
  std::size_t flip_sweeps(std::size_t f, FaceData& data) {
    std::size_t total = 0;
    for (int sweep = 0; sweep < kFlipSweeps; ++sweep) {
      std::size_t flips = 0;
      std::vector<Key> keys;
      for (const auto& [key, tris] : data.edge_triangles) {
        if (tris[1] >= 0) keys.push_back(key);
      }
      std::sort(keys.begin(), keys.end());
      for (Key key : keys) {
        const auto it = data.edge_triangles.find(key);
        if (it == data.edge_triangles.end() || it->second[1] < 0) continue;
        const auto t1 = static_cast<std::size_t>(it->second[0]), t2 = static_cast<std::size_t>(it->second[1]);
        if (try_flip(f, data, key, t1, t2)) {
          ++flips;
          build(f, data);
        }
      }
      total += flips;
      if (flips == 0) break;
    }
    stats_.flips += total;
    return total;
  }

  bool try_flip(std::size_t f, const FaceData& data, Key key, std::size_t t1, std::size_t t2) {
    SurfaceMeshes::Face& mesh = face(f);
    const auto p = static_cast<std::uint32_t>(key >> 32), q = static_cast<std::uint32_t>(key);
    const auto& v = mesh.node_vertex;
    if (segments_.count(edge_key(v[p], v[q])) > 0) return false;
    Triangle a = mesh.triangles[t1], b = mesh.triangles[t2];
    const auto rotate_to = [](Triangle& t, std::uint32_t x, std::uint32_t y) {
      for (int k = 0; k < 3; ++k) {
        if (t[0] == x && t[1] == y) return true;
        std::rotate(t.begin(), t.begin() + 1, t.end());
      }
      return false;
    };
    if (!rotate_to(a, p, q) && !rotate_to(a, q, p)) return false;
    if (!rotate_to(b, a[1], a[0])) return false;
    const std::uint32_t k = a[2], l = b[2];
    if (k == l || data.edge_triangles.count(edge_key(k, l)) > 0) return false;
    if (global_edges_.count(edge_key(v[k], v[l])) > 0 || segments_.count(edge_key(v[k], v[l])) > 0) return false;
    const Triangle n1{a[0], l, k}, n2{a[1], k, l};
    if (degenerate(f, a) || degenerate(f, b) || degenerate(f, n1) || degenerate(f, n2)) return false;
    for (const Triangle& t : {n1, n2}) {
      if (predicates::orient2d(mesh.uv[t[0]].data(), mesh.uv[t[1]].data(), mesh.uv[t[2]].data()) != data.orientation) {
        return false;
      }
    }
    const auto pts = [&](const Triangle& t) { return std::array<Vec3, 3>{position(f, t[0]), position(f, t[1]), position(f, t[2])}; };
    const auto uvs = [&](const Triangle& t) { return std::array<Point2, 3>{mesh.uv[t[0]], mesh.uv[t[1]], mesh.uv[t[2]]}; };
    const auto smallest = [&](const Triangle& t) {
      const std::array<Vec3, 3> x = pts(t);
      const std::array<double, 3> c = corners(x[0], x[1], x[2]);
      return std::min({c[0], c[1], c[2]});
    };
    const double before = std::min(smallest(a), smallest(b));
    const double after = std::min(smallest(n1), smallest(n2));
    if (!(after > before + kGain) || !(before < bound_)) return false;
    const double deviation_before = std::max(normal_deviation(f, data, pts(a), uvs(a)), normal_deviation(f, data, pts(b), uvs(b)));
    const double deviation_after = std::max(normal_deviation(f, data, pts(n1), uvs(n1)), normal_deviation(f, data, pts(n2), uvs(n2)));
    if (deviation_after > std::max(kMaxNormalDeviation, deviation_before)) return false;
    const auto normal = [&](const Triangle& t) {
      const std::array<Vec3, 3> x = pts(t);
      return unit_normal(x[0], x[1], x[2]);
    };
    const double bend_before = angle_between(normal(a), normal(b));
    const double bend_after = angle_between(normal(n1), normal(n2));
    if (bend_after > std::max(kMaxBend, bend_before)) return false;
    if (--global_edges_[edge_key(v[p], v[q])] == 0) global_edges_.erase(edge_key(v[p], v[q]));
    ++global_edges_[edge_key(v[k], v[l])];
    mesh.triangles[t1] = n1;
    mesh.triangles[t2] = n2;
    return true;
  }

  SurfaceMeshes& meshes_;
  std::vector<Vec3>& points_;
  SurfaceSmoothingOptions options_;
  const SurfacePoint& surface_point_;
  const SurfaceNormal& surface_normal_;
  double bound_;
  std::unordered_set<std::uint32_t> on_cad_edge_;
  std::unordered_set<Key> segments_;
  std::unordered_map<Key, int> global_edges_;
  SurfaceSmoothingStats stats_;
};

}  // namespace

SurfaceSmoothingStats smooth_surface_meshes(SurfaceMeshes& meshes, std::vector<Vec3>& points,
                                            const SurfaceSmoothingOptions& options,
                                            const SurfacePoint& surface_point,
                                            const SurfaceNormal& surface_normal) {
  return Smoother(meshes, points, options, surface_point, surface_normal).run();
}

}  // namespace delmesh::step
