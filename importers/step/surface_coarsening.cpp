// Half-edge collapses of crowded inner nodes of CAD face tessellations (see
// surface_coarsening.h).
#include "importers/step/surface_coarsening.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "toolkit/predicates/predicates.h"
#include "importers/step/triangle_corners.h"

namespace delmesh::step {
namespace {

using Key = std::uint64_t;
using Triangle = std::array<std::uint32_t, 3>;

/// A collapse may not turn a triangle farther than this (radians) from the surface normal
/// at its parameter centroid, unless a triangle it replaces already was.
constexpr double kMaxNormalDeviation = std::numbers::pi / 2.0;
/// A collapse must raise the star's smallest angle by more than this (radians).
constexpr double kGain = 1e-9;

double smallest_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
}

class Coarsener {
 public:
  Coarsener(SurfaceMeshes& meshes, const std::vector<Vec3>& points, const SurfaceCoarseningOptions& options,
            const SurfacePoint& surface_point, const SurfaceNormal& surface_normal)
      : meshes_(meshes), points_(points), options_(options), surface_point_(surface_point),
        surface_normal_(surface_normal), bound_(options.min_angle_deg * std::numbers::pi / 180.0) {}

  std::size_t run() {
    for (const SurfaceMeshes::Edge& edge : meshes_.edges) on_cad_edge_.insert(edge.vertices.begin(), edge.vertices.end());
    global_edges_ = count_face_edges(meshes_);
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      if (meshes_.faces[f].refine && meshes_.faces[f].offset.empty()) coarsen_face(f);
    }
    return removed_;
  }

 private:
  struct Candidate {
    std::uint32_t target = 0;
    double angle = -1.0;
  };

  const Vec3& position(std::size_t f, std::uint32_t local) const { return points_[meshes_.faces[f].node_vertex[local]]; }

  double deviation(std::size_t f, const Triangle& t) const {
    if (!surface_normal_) return 0.0;
    const SurfaceMeshes::Face& mesh = meshes_.faces[f];
    const Point2 centre{(mesh.uv[t[0]][0] + mesh.uv[t[1]][0] + mesh.uv[t[2]][0]) / 3.0,
                        (mesh.uv[t[0]][1] + mesh.uv[t[1]][1] + mesh.uv[t[2]][1]) / 3.0};
    const Vec3 surface = surface_normal_(f, centre);
    const Vec3 n = (position(f, t[1]) - position(f, t[0])).cross(position(f, t[2]) - position(f, t[0]));
    if (!surface.allFinite() || surface.isZero() || n.isZero()) return 0.0;
    const double side = orientation_ == Sign::Positive ? 1.0 : -1.0;
    return std::atan2((side * n).cross(surface).norm(), (side * n).dot(surface));
  }

  double deflection(std::size_t f, const Triangle& t) const {
    if (!(options_.max_deflection > 0.0)) return 0.0;
    const SurfaceMeshes::Face& mesh = meshes_.faces[f];
    const Point2 centre{(mesh.uv[t[0]][0] + mesh.uv[t[1]][0] + mesh.uv[t[2]][0]) / 3.0,
                        (mesh.uv[t[0]][1] + mesh.uv[t[1]][1] + mesh.uv[t[2]][1]) / 3.0};
    const Vec3 p = surface_point_(f, centre);
    const Vec3 c = (position(f, t[0]) + position(f, t[1]) + position(f, t[2])) / 3.0;
    const double d = (p - c).norm();
    return std::isfinite(d) ? d : std::numeric_limits<double>::infinity();
  }

  void coarsen_face(std::size_t f) {
    SurfaceMeshes::Face& mesh = meshes_.faces[f];
    int positive = 0, negative = 0;
    for (const Triangle& t : mesh.triangles) {
      const Sign s = predicates::orient2d(mesh.uv[t[0]].data(), mesh.uv[t[1]].data(), mesh.uv[t[2]].data());
      positive += s == Sign::Positive;
      negative += s == Sign::Negative;
    }
    if ((positive > 0) == (negative > 0)) return;  // not a valid triangulation of its parameter domain
    orientation_ = positive > 0 ? Sign::Positive : Sign::Negative;
    std::unordered_map<std::uint32_t, int> copies;
    for (std::uint32_t v : mesh.node_vertex) ++copies[v];
    std::vector<bool> removable(mesh.uv.size(), false);
    for (std::size_t n = 0; n < mesh.uv.size(); ++n) {
      removable[n] = on_cad_edge_.count(mesh.node_vertex[n]) == 0 && copies[mesh.node_vertex[n]] == 1;
    }
    std::vector<bool> alive(mesh.triangles.size(), true);
    std::vector<std::vector<std::uint32_t>> star(mesh.uv.size());
    std::unordered_set<Key> edges;  // local
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Triangle& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) {
        star[tri[k]].push_back(static_cast<std::uint32_t>(t));
        edges.insert(edge_key(tri[k], tri[(k + 1) % 3]));
      }
    }
    // Every collapse removes a node for good, so the passes end.
    for (bool changed = true; changed;) {
      changed = false;
      for (std::uint32_t n = 0; n < mesh.uv.size(); ++n) {
        if (removable[n] && collapse(f, n, star, edges, alive)) {
          removable[n] = false;
          changed = true;
          ++removed_;
        }
      }
    }
    std::vector<Triangle> kept;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (alive[t]) kept.push_back(mesh.triangles[t]);
    }
    mesh.triangles = std::move(kept);
  }

  bool collapse(std::size_t f, std::uint32_t n, std::vector<std::vector<std::uint32_t>>& star,
                std::unordered_set<Key>& edges, std::vector<bool>& alive) {
    SurfaceMeshes::Face& mesh = meshes_.faces[f];
    const auto& v = mesh.node_vertex;
    const std::vector<std::uint32_t>& around = star[n];
    if (around.size() < 3) return false;
    // The star as triangles (n, a, b) and its link as the cycle a -> b.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> link;
    std::unordered_map<std::uint32_t, std::uint32_t> next;
    double old_angle = std::numeric_limits<double>::infinity();
    double old_deviation = 0.0, old_deflection = 0.0;
    for (std::uint32_t t : around) {
      Triangle tri = mesh.triangles[t];
      while (tri[0] != n) std::rotate(tri.begin(), tri.begin() + 1, tri.end());
      if (v[tri[0]] == v[tri[1]] || v[tri[1]] == v[tri[2]] || v[tri[2]] == v[tri[0]]) return false;
      if (!next.emplace(tri[1], tri[2]).second) return false;
      link.emplace_back(tri[1], tri[2]);
      old_angle = std::min(old_angle, smallest_angle(position(f, tri[0]), position(f, tri[1]), position(f, tri[2])));
      old_deviation = std::max(old_deviation, deviation(f, tri));
      old_deflection = std::max(old_deflection, deflection(f, tri));
    }
    if (!(old_angle < bound_)) return false;
    // A closed disc: the link is one cycle through every star triangle.
    std::uint32_t walk = link.front().first;
    for (std::size_t k = 0; k < link.size(); ++k) {
      const auto it = next.find(walk);
      if (it == next.end()) return false;
      walk = it->second;
    }
    if (walk != link.front().first) return false;
    std::unordered_set<std::uint32_t> visited;
    for (const auto& [a, b] : link) visited.insert(a);
    if (visited.size() != link.size()) return false;
    Candidate best;
    for (const auto& [m, unused] : link) {
      double angle = std::numeric_limits<double>::infinity();
      bool allowed = true;
      for (const auto& [a, b] : link) {
        if (a == m || b == m) continue;
        const Triangle tri{m, a, b};
        if (predicates::orient2d(mesh.uv[m].data(), mesh.uv[a].data(), mesh.uv[b].data()) != orientation_) {
          allowed = false;
          break;
        }
        for (std::uint32_t x : {a, b}) {
          if (next.at(m) == x || next.at(x) == m) continue;  // already an edge of the link
          if (edges.count(edge_key(m, x)) > 0 || global_edges_.count(edge_key(v[m], v[x])) > 0) allowed = false;
        }
        if (!allowed) break;
        angle = std::min(angle, smallest_angle(position(f, m), position(f, a), position(f, b)));
        if (!(angle > old_angle + kGain) || !(angle > best.angle)) {
          allowed = false;
          break;
        }
        if (deviation(f, tri) > std::max(kMaxNormalDeviation, old_deviation) ||
            deflection(f, tri) > std::max(options_.max_deflection, old_deflection)) {
          allowed = false;
          break;
        }
      }
      if (allowed) best = {m, angle};
    }
    if (!(best.angle >= 0.0)) return false;
    const std::uint32_t m = best.target;
    for (const auto& [a, b] : link) {
      edges.erase(edge_key(n, a));
      if (--global_edges_[edge_key(v[n], v[a])] == 0) global_edges_.erase(edge_key(v[n], v[a]));
      if (a == m || b == m || next.at(m) == a || next.at(a) == m) continue;
      edges.insert(edge_key(m, a));
      ++global_edges_[edge_key(v[m], v[a])];
    }
    const std::vector<std::uint32_t> old_star = around;
    for (std::uint32_t t : old_star) {
      Triangle& tri = mesh.triangles[t];
      if (std::find(tri.begin(), tri.end(), m) != tri.end()) {
        alive[t] = false;
        for (std::uint32_t x : tri) {
          auto& s = star[x];
          s.erase(std::remove(s.begin(), s.end(), t), s.end());
        }
        continue;
      }
      std::replace(tri.begin(), tri.end(), n, m);
      star[m].push_back(t);
    }
    star[n].clear();
    return true;
  }

  SurfaceMeshes& meshes_;
  const std::vector<Vec3>& points_;
  SurfaceCoarseningOptions options_;
  const SurfacePoint& surface_point_;
  const SurfaceNormal& surface_normal_;
  double bound_;
  Sign orientation_ = Sign::Zero;
  std::unordered_set<std::uint32_t> on_cad_edge_;
  std::unordered_map<Key, int> global_edges_;
  std::size_t removed_ = 0;
};

}  // namespace

std::size_t coarsen_surface_meshes(SurfaceMeshes& meshes, const std::vector<Vec3>& points,
                                   const SurfaceCoarseningOptions& options, const SurfacePoint& surface_point,
                                   const SurfaceNormal& surface_normal) {
  return Coarsener(meshes, points, options, surface_point, surface_normal).run();
}

}  // namespace delmesh::step
