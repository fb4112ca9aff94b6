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
// triangulation of its parameter domain. No flip or split may create an edge between
// two PLC vertices that another face already joins (two faces sharing two CAD edges, like
// the halves of a cylinder, would otherwise both hold the same chord). Rounds stop when
// no triangle can be improved, the triangles to split are smaller than the length floor,
// or the point budget is spent. A face marked keep_min_angle takes a boundary split (its
// own or a neighbour's) only where its smallest angle does not drop. An ear (three
// consecutive nodes of one CAD edge, as BRepMesh leaves along circles) gets its
// circumcentre only where that lies inside the face, and a circumcentre falling on an
// edge in 3D (a disc's centre on a diameter) splits that edge. A circumcentre encroaching
// only on segments that are never split goes in where the triangles it makes on them keep
// the bound; where it would not, the point lifted off that segment to where its triangle
// on it meets the bound goes in instead (a heuristic point: it splits no segment); where
// a circumcentre cannot go in, the triangle's longest inner edge is bisected (Rivara) if
// that makes no worse triangle. On a periodic face (a seam held
// twice) with a pole (a triangle joining two copies of one node), where the parameters
// beside the pole are polar coordinates, a circumcentre the parameter plane's affine map
// puts outside the face is found by projecting the 3D circumcentre onto the surface,
// bisection tries the triangle's shorter inner edges when the longest fails, and flips of
// bad pairs in quads that are not affinely parametrised go by the 3D max-min angle (a pole
// without a seam, as on gmsh-wing-fuselage's fuselage halves, keeps the affine rules:
// there the projection made a 1.2e-7 segment that conforming recovery cannot resolve). Segments stay unsplit at a small
// corner of a triangulated face only (two CAD edges of that face meeting at under 10
// degrees; a planar face written as a polygon has no triangle in its corners), not
// wherever two nearly tangent CAD edges meet, and even there a split that widens the
// corner (the flatter of two tangent curves) goes in, and so does a split that balances
// it: a segment reaching farther from the corner than the other edge's first segment by
// more than the wedge is wide is split at that segment's length from the corner (as
// Ruppert's concentric shells, notes §3.8), or, where that split would spoil a triangle of
// a face on the segment and the segment reaches more than twice as far, halfway to the
// corner first (the next shell). The shells go round every corner under the bound at that
// vertex: in a face on the held segment whose corner there is under the bound, the first
// node of its other CAD edge at the vertex balances the segment too. A triangle whose smallest angle lies at a
// corner of its face under 60 degrees (kSmallFaceCornerDeg, the small input angles the
// quality measure leaves out) and under the bound (no triangle there can meet it) is not
// refined either. Where a face's pole is a corner of
// the face, the pole's collapsed triangle gets a node at the distance of the corner's
// first nodes when its apex lies more than twice as far (place_pole_apexes).
#include "importers/step/surface_refinement.h"
#include "importers/step/triangle_corners.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <Eigen/Geometry>

#include "importers/step/surface_mesh_quality.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::step {
namespace {

using Key = std::uint64_t;
/// New triangles with a smaller angle (radians) are refused: the insertion point fell on
/// an existing node or edge in 3D (a distorted parametrisation).
constexpr double kDegenerateAngle = 1e-4;
/// A flip or split may not turn a triangle farther than this (radians, 90 degrees) from
/// the surface normal at its centre, unless a triangle it replaces already was: no flip
/// or split turns a triangle upside down against the surface (a fold).
constexpr double kMaxNormalDeviation = std::numbers::pi / 2.0;
/// New triangles with a smaller angle (radians, 5 degrees) are not checked for folds.
constexpr double kThinAngle = 5.0 * std::numbers::pi / 180.0;
/// Segments meeting at a smaller angle (radians, 10 degrees) at a CAD vertex, at a corner
/// of a triangulated face they both bound, are not split unless that widens the corner:
/// the triangles between two nearly tangent CAD edges cannot be improved (notes §3.8),
/// and splitting their segments mostly narrows the corner's chord angle, feeding a
/// cascade of ever smaller triangles into the corner in every face around it. A planar
/// face written as one polygon has no triangles in its corner: there the splits that
/// the neighbouring curved faces ask for go in (gmsh-part: a fillet meeting a flatter
/// extrusion face tangentially at the edge of a planar wall).
constexpr double kSmallCorner = std::numbers::pi / 18.0;
/// A split may leave a triangle on the split edge with this fraction of the smallest angle
/// of the triangle it comes from (or of the bound, if smaller). Splitting an encroached
/// segment (Ruppert) makes the triangles on it worse until their own circumcentres go in;
/// at 0.5 the splits circumcentres ask for next to curved CAD edges were refused and
/// refinement stopped short (as-anc101 4.7, gmsh-laufrad-impeller 13.4 degrees); at 0.2
/// they reach 20 degrees.
constexpr double kSplitKeeps = 0.2;
/// A segment at a small corner is split only if that widens the corner by at least this
/// factor: on a straight edge the chord keeps its direction (no widening, only rounding),
/// and the widening splits of a curved edge, each a smaller gain than the last, stop.
constexpr double kCornerWidening = 1.1;
/// A face corner over this (radians, 180 degrees) between two CAD edges whose chords meet
/// at less than kSmallCorner is the reflex side of a small angle, not a small angle.
constexpr double kReflexCorner = std::numbers::pi;
/// A quad whose nodes lie farther than this fraction of its extent from the least-squares
/// affine map of its parameter points is not affinely parametrised (beside a pole).
constexpr double kAffineResidual = 0.1;
/// A circumcentre blocked by a segment never split is lifted off it to where its triangle
/// with the segment has its smallest angle at this multiple of the bound (lifted_point),
/// raised by kLiftGrowth at a time, at most kLiftSteps times (a factor 1.2^12 = 8.9: the
/// scaled parameter plane may be that far from the surface's metric across the segment).
constexpr double kLiftAngle = 1.1;
constexpr double kLiftGrowth = 1.2;
constexpr int kLiftSteps = 13;
using Triangle = std::array<std::uint32_t, 3>;

/// Smallest corner angle (radians) of a 3D triangle; 0 for a degenerate one.
double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
}

struct Segment {
  std::size_t edge = 0;
  bool ambiguous = false;  ///< two CAD edges share these end vertices: never split
  /// The small corners this segment bounds (two CAD edges of a face meeting at less than
  /// kSmallCorner): the corner vertex and the other CAD edge there. Such a segment is
  /// split only where that widens or balances the corner (split_place).
  struct SmallCorner {
    std::uint32_t corner = 0;
    std::size_t partner_edge = 0;
  };
  std::vector<SmallCorner> small_corners;
  std::vector<std::size_t> faces;
};

class Refiner {
 public:
  Refiner(SurfaceMeshes& meshes, std::vector<Vec3>& points, const SurfaceRefinementOptions& options,
          const SurfacePoint& surface_point, const EdgePoint& edge_point, const SurfaceNormal& surface_normal,
          const SurfaceParameters& surface_parameters)
      : meshes_(meshes), points_(points), options_(options), surface_point_(surface_point),
        edge_point_(edge_point), surface_normal_(surface_normal), surface_parameters_(surface_parameters),
        state_(meshes.faces.size()),
        bound_(options.min_angle_deg * std::numbers::pi / 180.0) {}

  SurfaceRefinementStats run() {
    build_segments();
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) prepare_face(f);
    mark_small_corners();
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      state_[f].small_face_corners = small_face_corners(meshes_, f, points_);
    }
    stats_.min_angle_before_deg = smallest_angle_deg();
    const std::size_t budget_end = points_.size() + options_.max_new_points;
    const double bound = bound_;
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) flip_face(f);
    for (int round = 0; round < 64; ++round) {
      for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
        if (state_[f].refinable && state_[f].has_pole) place_pole_apexes(f, budget_end);
      }
      // The worst triangles of the whole model first, so the budget goes where it matters.
      std::vector<std::tuple<double, std::size_t, std::size_t>> bad;
      for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
        if (!state_[f].refinable) continue;
        for (std::size_t t = 0; t < face(f).triangles.size(); ++t) {
          const double q = quality(f, face(f).triangles[t]);
          if (q < bound || too_far_from_surface(f, face(f).triangles[t])) bad.emplace_back(q, f, t);
        }
      }
      std::sort(bad.begin(), bad.end());
      bool split_any = false;
      for (const auto& [q, f, t] : bad) {
        if (points_.size() >= budget_end) break;
        if (quality(f, face(f).triangles[t]) >= bound && !too_far_from_surface(f, face(f).triangles[t])) continue;
        split_any = insert_circumcenter(f, t) || split_longest_edge(f, t) || split_any;
        split_encroached_subsegments(budget_end);
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
      for (Point2& p : face(f).uv) p = {p[0] / state_[f].scale[0], p[1] / state_[f].scale[1]};
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
    std::array<double, 2> scale{1.0, 1.0};  ///< parameter-plane scaling to 3D lengths
    double min_angle_before = 0.0;  ///< radians, smallest angle of the unrefined face
    std::unordered_map<Key, std::array<std::int64_t, 2>> edge_triangles;  ///< local edge -> triangles
    std::unordered_map<Key, std::vector<Key>> segment_edges;  ///< CAD segment -> local edges on it
    /// A triangle joins two copies of one node (collapsed at a pole of the surface).
    bool has_pole = false;
    /// The face holds a CAD segment twice: a seam of a periodic surface.
    bool has_seam = false;
    /// PLC vertices at corners of the face under kSmallFaceCornerDeg (surface_mesh_quality.h)
    /// and the corners (degrees), as BRepMesh's triangles give them.
    std::map<std::uint32_t, double> small_face_corners;
    /// Bounding box of the face's nodes in the scaled parameter plane.
    std::array<double, 2> low{0.0, 0.0}, high{0.0, 0.0};
  };

  SurfaceMeshes::Face& face(std::size_t f) { return meshes_.faces[f]; }

  Sign uv_orient(std::size_t f, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const auto& uv = face(f).uv;
    return predicates::orient2d(uv[a].data(), uv[b].data(), uv[c].data());
  }

  Vec3 position(std::size_t f, std::uint32_t local) { return points_[face(f).node_vertex[local]]; }

  /// The PLC vertex pair of local edge (i, j) of face f.
  Key global_key(std::size_t f, std::uint32_t i, std::uint32_t j) {
    return edge_key(face(f).node_vertex[i], face(f).node_vertex[j]);
  }

  /// Is the PLC vertex pair of local edge (i, j) already an edge of some face? Two faces
  /// sharing two CAD edges (the halves of a cylinder) can each join the same pair of
  /// boundary vertices; both would be the same straight segment of the PLC, cutting
  /// through the model, so no flip or split may create such an edge.
  bool edge_exists(std::size_t f, std::uint32_t i, std::uint32_t j) {
    return global_edges_.count(global_key(f, i, j)) > 0;
  }

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

  /// The surface point at the triangle's parameter-plane centroid lies farther than the
  /// allowed deflection from its 3D centroid: the triangle spans too much of a curved
  /// face (its neighbours could fold against it), so it is split like a bad one.
  bool too_far_from_surface(std::size_t f, const Triangle& t) {
    if (degenerate(f, t)) return false;
    const Vec3 middle = (position(f, t[0]) + position(f, t[1]) + position(f, t[2])) / 3.0;
    double bound = options_.max_deflection > 0.0 ? options_.max_deflection : std::numeric_limits<double>::infinity();
    for (const SurfaceMeshes::Face::DeflectionZone& zone : face(f).zones) {
      if ((middle - zone.center).norm() <= zone.radius) bound = std::min(bound, zone.max_deflection);
    }
    if (!(bound < std::numeric_limits<double>::infinity())) return false;
    const auto& uv = face(f).uv;
    const Point2 centroid{(uv[t[0]][0] + uv[t[1]][0] + uv[t[2]][0]) / 3.0,
                          (uv[t[0]][1] + uv[t[1]][1] + uv[t[2]][1]) / 3.0};
    return (surface_at(f, centroid) + offset_in(f, t, centroid) - middle).norm() > bound;
  }

  double smallest_angle_deg() {
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < meshes_.faces.size(); ++f) {
      if (!face(f).refine && !face(f).keep_min_angle) continue;
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
        auto [it, inserted] = segments_.try_emplace(edge_key(v[k], v[k + 1]));
        if (inserted) {
          it->second.edge = e;
        } else if (it->second.edge != e) {
          it->second.ambiguous = true;
        }
      }
    }
  }

  /// Is face f written as its triangles (refined, or kept as BRepMesh left it)? Other
  /// faces (planar ones) become polygonal facets: no triangle of theirs sits in a corner.
  bool triangulated(std::size_t f) { return face(f).refine || face(f).keep_min_angle; }

  /// The corner of face f at PLC vertex `vertex`: the sum of its triangles' 3D angles
  /// there (radians).
  double face_corner(std::size_t f, std::uint32_t vertex) {
    double sum = 0.0;
    for (const Triangle& t : face(f).triangles) {
      for (int k = 0; k < 3; ++k) {
        if (face(f).node_vertex[t[k]] != vertex) continue;
        const Vec3 p = position(f, t[k]);
        const Vec3 u = position(f, t[(k + 1) % 3]) - p, w = position(f, t[(k + 2) % 3]) - p;
        const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
        if (std::isfinite(angle)) sum += angle;
      }
    }
    return sum;
  }

  /// Marks the end segments of two CAD edges that meet at a CAD vertex at less than
  /// kSmallCorner and bound a common face whose corner there is small (not the reflex
  /// side, over kReflexCorner). Nearly tangent CAD edges that bound no such corner (the
  /// far sides of a vertex where several faces meet, or a face going round them) make no
  /// small triangle: their segments may be split. Needs the faces and triangles of every
  /// segment (prepare_face).
  void mark_small_corners() {
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> corner_neighbours;
    for (std::size_t e = 0; e < meshes_.edges.size(); ++e) {
      const auto& v = meshes_.edges[e].vertices;
      if (v.size() < 2) continue;
      corner_neighbours[v.front()].push_back(v[1]);
      corner_neighbours[v.back()].push_back(v[v.size() - 2]);
    }
    for (const auto& [corner, neighbours] : corner_neighbours) {
      for (std::size_t i = 0; i < neighbours.size(); ++i) {
        for (std::size_t j = i + 1; j < neighbours.size(); ++j) {
          if (neighbours[i] == neighbours[j] || neighbours[i] == corner || neighbours[j] == corner) continue;
          const Vec3 u = points_[neighbours[i]] - points_[corner];
          const Vec3 w = points_[neighbours[j]] - points_[corner];
          if (!(std::atan2(u.cross(w).norm(), u.dot(w)) < kSmallCorner)) continue;
          const auto first = segments_.find(edge_key(corner, neighbours[i]));
          const auto second = segments_.find(edge_key(corner, neighbours[j]));
          if (first == segments_.end() || second == segments_.end()) continue;
          const auto& faces = first->second.faces;
          const bool small = std::any_of(second->second.faces.begin(), second->second.faces.end(), [&](std::size_t f) {
            return std::find(faces.begin(), faces.end(), f) != faces.end() && triangulated(f) &&
                   face_corner(f, corner) < kReflexCorner;
          });
          if (!small) continue;
          first->second.small_corners.push_back({corner, second->second.edge});
          second->second.small_corners.push_back({corner, first->second.edge});
        }
      }
    }
  }

  void add_triangle_edges(std::size_t f, std::size_t t) {
    const Triangle& tri = face(f).triangles[t];
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = state_[f].edge_triangles.try_emplace(edge_key(tri[k], tri[(k + 1) % 3]),
                                                                 std::array<std::int64_t, 2>{-1, -1});
      if (inserted) ++global_edges_[global_key(f, tri[k], tri[(k + 1) % 3])];
      (it->second[0] < 0 ? it->second[0] : it->second[1]) = static_cast<std::int64_t>(t);
    }
  }

  void remove_triangle_edges(std::size_t f, std::size_t t) {
    const Triangle& tri = face(f).triangles[t];
    for (int k = 0; k < 3; ++k) {
      const Key key = edge_key(tri[k], tri[(k + 1) % 3]);
      auto it = state_[f].edge_triangles.find(key);
      if (it == state_[f].edge_triangles.end()) continue;
      if (it->second[0] == static_cast<std::int64_t>(t)) it->second[0] = it->second[1];
      it->second[1] = -1;
      if (it->second[0] < 0) {
        state_[f].edge_triangles.erase(it);
        const auto global = global_edges_.find(global_key(f, tri[k], tri[(k + 1) % 3]));
        if (global != global_edges_.end() && --global->second == 0) global_edges_.erase(global);
      }
    }
  }

  void register_segment_edge(std::size_t f, std::uint32_t i, std::uint32_t j) {
    const auto& v = face(f).node_vertex;
    auto it = segments_.find(edge_key(v[i], v[j]));
    if (it == segments_.end()) return;
    state_[f].segment_edges[it->first].push_back(edge_key(i, j));
    if (std::find(it->second.faces.begin(), it->second.faces.end(), f) == it->second.faces.end()) {
      it->second.faces.push_back(f);
    }
  }

  /// Mean lengths of the surface derivatives over the face's triangles (from the
  /// triangles' 3D and parameter-plane edges), so that circumcentres computed in the
  /// scaled plane sit where 3D circumcentres would on cylinders, cones and tori.
  std::array<double, 2> parameter_scale(std::size_t f) {
    double su = 0.0, sv = 0.0;
    int count = 0;
    const auto& uv = face(f).uv;
    for (const Triangle& t : face(f).triangles) {
      const double u1 = uv[t[1]][0] - uv[t[0]][0], v1 = uv[t[1]][1] - uv[t[0]][1];
      const double u2 = uv[t[2]][0] - uv[t[0]][0], v2 = uv[t[2]][1] - uv[t[0]][1];
      const double det = u1 * v2 - u2 * v1;
      if (!(std::abs(det) > 0.0)) continue;
      const Vec3 e1 = position(f, t[1]) - position(f, t[0]);
      const Vec3 e2 = position(f, t[2]) - position(f, t[0]);
      const Vec3 du = (e1 * v2 - e2 * v1) / det;
      const Vec3 dv = (e2 * u1 - e1 * u2) / det;
      if (!du.allFinite() || !dv.allFinite()) continue;
      su += du.norm();
      sv += dv.norm();
      ++count;
    }
    if (count == 0 || !(su > 0.0) || !(sv > 0.0)) return {1.0, 1.0};
    return {su / count, sv / count};
  }

  void prepare_face(std::size_t f) {
    FaceState& state = state_[f];
    state.min_angle_before = std::numeric_limits<double>::infinity();
    for (const Triangle& t : face(f).triangles) state.min_angle_before = std::min(state.min_angle_before, quality(f, t));
    state.scale = parameter_scale(f);
    for (Point2& p : face(f).uv) p = {p[0] * state.scale[0], p[1] * state.scale[1]};
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
    for (const Triangle& t : face(f).triangles) state.has_pole = state.has_pole || degenerate(f, t);
    state.low = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    state.high = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const Point2& p : face(f).uv) {
      for (int k = 0; k < 2; ++k) {
        state.low[k] = std::min(state.low[k], p[k]);
        state.high[k] = std::max(state.high[k], p[k]);
      }
    }
    for (std::size_t t = 0; t < face(f).triangles.size(); ++t) add_triangle_edges(f, t);
    for (const auto& [key, tris] : state.edge_triangles) {
      register_segment_edge(f, static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key));
    }
    for (const auto& [segment, locals] : state.segment_edges) state.has_seam = state.has_seam || locals.size() > 1;
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
    return segments_.count(edge_key(v[i], v[j])) > 0;
  }

  bool try_flip(std::size_t f, Key key, std::array<Key, 4>* outer = nullptr) {
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
    if (k == l || state.edge_triangles.count(edge_key(k, l)) > 0 || is_segment(f, k, l) || edge_exists(f, k, l)) {
      return false;
    }
    const Triangle n1{a[0], l, k}, n2{a[1], k, l};
    if (degenerate(f, a) || degenerate(f, b) || degenerate(f, n1) || degenerate(f, n2)) return false;
    if (uv_orient(f, n1[0], n1[1], n1[2]) != Sign::Positive ||
        uv_orient(f, n2[0], n2[1], n2[2]) != Sign::Positive) {
      return false;
    }
    const double deviation_after = std::max(normal_deviation(f, n1), normal_deviation(f, n2));
    const double deviation_before = std::max(normal_deviation(f, a), normal_deviation(f, b));
    if (deviation_after > std::max(kMaxNormalDeviation, deviation_before)) return false;
    // A pair holding a triangle turned against the surface is flipped whenever the flip
    // turns both the right way, whatever the Delaunay criterion says.
    const bool unfolds = deviation_before > kMaxNormalDeviation && deviation_after <= kMaxNormalDeviation;
    // Delaunay criterion in the quad's own first fundamental form (exact incircle on the
    // parameter points mapped by quad_metric): l inside the circumcircle of a. The metric
    // depends on the four nodes only, not on the diagonal, so a quad never flips back.
    // Flat triangles (zero area in the parameter plane) are always flipped away.
    // Beside a pole the parameters are polar coordinates, which no affine metric of a quad
    // follows: on a periodic face with a pole, in a quad that is not affinely parametrised
    // (affine), a pair below the bound is flipped where that raises the smallest 3D angle
    // of the two triangles (max-min angle) without bending the face more sharply across
    // the new diagonal than across the old (gmsh-periodic-u: 1.06 -> 18.3 degrees).
    const bool polar = !unfolds && state.has_pole && state.has_seam &&
                       !affine(f, std::array<std::uint32_t, 4>{a[0], a[1], a[2], l});
    const double min_before = polar ? std::min(quality(f, a), quality(f, b)) : 0.0;
    const double min_after = polar ? std::min(quality(f, n1), quality(f, n2)) : 0.0;
    // There, no flip lowers the pair's smallest 3D angle either (the two criteria would
    // undo each other's flips).
    if (polar && min_after < min_before) return false;
    if (polar && min_before < bound_) {
      if (!(min_after > min_before) || bend(f, n1, n2) > bend(f, a, b)) return false;
    } else if (!unfolds && uv_orient(f, a[0], a[1], a[2]) == Sign::Positive) {
      const std::array<std::uint32_t, 4> quad{a[0], a[1], a[2], l};
      const std::array<double, 3> m = quad_metric(f, quad);
      std::array<Point2, 4> x{};
      for (int i = 0; i < 4; ++i) {
        const Point2& w = face(f).uv[quad[i]];
        x[i] = {m[0] * w[0] + m[1] * w[1], m[2] * w[1]};
      }
      if (!(m[0] > 0.0 && m[2] > 0.0) ||
          predicates::orient2d(x[0].data(), x[1].data(), x[2].data()) != Sign::Positive) {
        const auto& uv = face(f).uv;
        if (predicates::incircle(uv[a[0]].data(), uv[a[1]].data(), uv[a[2]].data(), uv[l].data()) != Sign::Positive) {
          return false;
        }
      } else if (predicates::incircle(x[0].data(), x[1].data(), x[2].data(), x[3].data()) != Sign::Positive) {
        return false;
      }
    }
    remove_triangle_edges(f, t1);
    remove_triangle_edges(f, t2);
    face(f).triangles[t1] = n1;
    face(f).triangles[t2] = n2;
    add_triangle_edges(f, t1);
    add_triangle_edges(f, t2);
    if (outer) *outer = {edge_key(a[0], l), edge_key(l, a[1]), edge_key(a[1], k), edge_key(k, a[0])};
    return true;
  }

  /// Angle (radians) between the 3D normals of two triangles of face f sharing an edge:
  /// how sharply the face bends there.
  double bend(std::size_t f, const Triangle& s, const Triangle& t) {
    const auto normal = [&](const Triangle& r) {
      return Vec3((position(f, r[1]) - position(f, r[0])).cross(position(f, r[2]) - position(f, r[0])));
    };
    const Vec3 m = normal(s), n = normal(t);
    return std::atan2(m.cross(n).norm(), m.dot(n));
  }

  /// Inserts the circumcentre of triangle t of face f (computed in the face's scaled
  /// parameter plane), Chew/Ruppert style: walk towards it from t; if a CAD segment lies
  /// in the way, split that segment instead; if it lands on an edge, split the edge.
  bool insert_circumcenter(std::size_t f, std::size_t t) {
    const Triangle& tri = face(f).triangles[t];
    const auto& v = face(f).node_vertex;
    // An ear (three consecutive nodes of one CAD edge, as BRepMesh leaves along circles)
    // gets its circumcentre only where that lies inside the face: splitting the curved
    // edge would only make flatter ears.
    const bool ear = on_one_cad_edge(v[tri[0]], v[tri[1]], v[tri[2]]);
    // A sliver with one tiny edge (BRepMesh leaves such) still has a large circumcircle
    // and is refined; only triangles that are small as a whole stop refinement.
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, (position(f, tri[(k + 1) % 3]) - position(f, tri[k])).norm());
    }
    if (!(longest > 2.0 * options_.min_edge_length)) return false;
    if (small_input_angle(f, tri)) return false;
    Point2 center = local_circumcenter(f, tri);
    if (state_[f].has_pole && state_[f].has_seam && surface_parameters_ && !in_parameter_box(f, center)) {
      const std::optional<Point2> projected = projected_circumcenter(f, tri);
      if (!projected) return false;
      center = *projected;
    }
    return insert_point(f, t, center, ear, true);
  }

  /// Inserts the point `center` (scaled parameter plane) for triangle t of face f: walks
  /// to it from t; a CAD segment in the way, or encroached, is split instead. Where the
  /// point is blocked (it would make a triangle under the bound on a segment that is never
  /// split) and `may_lift`, the point lifted off that segment (lifted_point) is tried.
  bool insert_point(std::size_t f, std::size_t t, const Point2& center, bool ear, bool may_lift) {
    const auto& uv = face(f).uv;
    if (!std::isfinite(center[0]) || !std::isfinite(center[1])) return false;
    // Visibility walk.
    std::size_t current = t;
    for (int step = 0;; ++step) {
      if (step > 4096) return false;
      const Triangle here = face(f).triangles[current];
      bool moved = false;
      for (int k = 0; k < 3 && !moved; ++k) {
        const std::uint32_t i = here[k], j = here[(k + 1) % 3];
        if (predicates::orient2d(uv[i].data(), uv[j].data(), center.data()) != Sign::Negative) continue;
        if (const std::optional<Key> segment = segment_of(f, i, j)) return ear || !may_lift ? false : split_segment(*segment);
        const auto adjacent = state_[f].edge_triangles.find(edge_key(i, j));
        if (adjacent == state_[f].edge_triangles.end() || adjacent->second[1] < 0) return false;
        current = static_cast<std::size_t>(adjacent->second[0] == static_cast<std::int64_t>(current)
                                               ? adjacent->second[1]
                                               : adjacent->second[0]);
        moved = true;
      }
      if (!moved) break;
    }
    std::optional<Key> blocked;
    if (const std::optional<Key> segment = encroached_segment(f, center, surface_at(f, center), blocked)) {
      // A lifted point is no circumcentre: it splits nothing (its splits cascaded along
      // gmsh-fusee-rocket's face 107, 7.8 -> 2.2 degrees).
      return ear || !may_lift ? false : split_segment(*segment);
    }
    if (blocked) {
      if (ear || !may_lift) return false;
      const std::optional<Point2> lifted = lifted_point(f, *blocked, center);
      return lifted && insert_point(f, t, *lifted, ear, false);
    }
    const Triangle host = face(f).triangles[current];
    std::array<Sign, 3> sides{};
    int zeros = 0;
    for (int k = 0; k < 3; ++k) {
      sides[k] = predicates::orient2d(uv[host[k]].data(), uv[host[(k + 1) % 3]].data(), center.data());
      zeros += sides[k] == Sign::Zero;
    }
    if (zeros > 1) return false;
    if (zeros == 1) {
      const int k = static_cast<int>(std::find(sides.begin(), sides.end(), Sign::Zero) - sides.begin());
      const std::uint32_t i = host[k], j = host[(k + 1) % 3];
      if (const std::optional<Key> segment = segment_of(f, i, j)) return ear || !may_lift ? false : split_segment(*segment);
      return split_interior_edge(f, i, j, center);
    }
    return insert_in_triangle(f, current, center, !ear);
  }

  /// Rivara's longest-edge bisection, where the circumcentre of triangle t of face f
  /// cannot go in (it would fold the face, lies beyond a segment that is never split, or
  /// would spoil a triangle on one): the longest 3D edge, if it lies inside the face, is
  /// split at its parameter-plane midpoint, provided that midpoint encroaches on no CAD
  /// segment (no new node crowds the boundary) and no new triangle is worse than the one
  /// it comes from. Not for ears and triangles whose smallest angle is an input angle (as
  /// insert_circumcenter), nor for faces where bisection folded or spoiled the result
  /// (SurfaceMeshes::Face::bisect).
  bool split_longest_edge(std::size_t f, std::size_t t) {
    if (!face(f).bisect) return false;
    const Triangle tri = face(f).triangles[t];
    const auto& v = face(f).node_vertex;
    if (degenerate(f, tri) || small_input_angle(f, tri) || on_one_cad_edge(v[tri[0]], v[tri[1]], v[tri[2]])) {
      return false;
    }
    // Edges by decreasing 3D length: the longest only, or on a face with a pole each in
    // turn (beside a pole a chord reaching round it can be shorter than the triangle's
    // longest edge, whose split only makes a flatter triangle against that chord).
    std::array<std::pair<double, int>, 3> edges{};
    for (int k = 0; k < 3; ++k) edges[k] = {(position(f, tri[(k + 1) % 3]) - position(f, tri[k])).norm(), k};
    std::sort(edges.begin(), edges.end(), std::greater<>());
    const int tries = state_[f].has_pole && state_[f].has_seam ? 3 : 1;
    for (int n = 0; n < tries; ++n) {
      const auto [length, k] = edges[n];
      if (!(length > 2.0 * options_.min_edge_length)) return false;
      const std::uint32_t i = tri[k], j = tri[(k + 1) % 3];
      if (segment_of(f, i, j)) continue;
      const auto& uv = face(f).uv;
      const Point2 middle{0.5 * (uv[i][0] + uv[j][0]), 0.5 * (uv[i][1] + uv[j][1])};
      if (encroaches_any_segment(f, middle) || !split_interior_edge(f, i, j, middle, 1.0)) continue;
      face(f).bisected = true;
      return true;
    }
    return false;
  }

  /// Angle (radians) between the normal of the 3D triangle (a, b, c), positively
  /// oriented at parameters (ua, ub, uc), and the surface normal at its parameter
  /// centroid; 0 where either is undefined or the face is not validly parametrised.
  double normal_deviation(std::size_t f, const Vec3& a, const Vec3& b, const Vec3& c, const Point2& ua,
                          const Point2& ub, const Point2& uc) {
    if (!surface_normal_ || !state_[f].uv_valid) return 0.0;
    const Vec3 n = (b - a).cross(c - a);
    const Point2 centre{(ua[0] + ub[0] + uc[0]) / (3.0 * state_[f].scale[0]),
                        (ua[1] + ub[1] + uc[1]) / (3.0 * state_[f].scale[1])};
    const Vec3 surface = surface_normal_(f, centre);
    if (!(n.norm() > 0.0) || !(surface.norm() > 0.0) || !surface.allFinite()) return 0.0;
    return std::atan2(n.cross(surface).norm(), n.dot(surface));
  }

  double normal_deviation(std::size_t f, const Triangle& t) {
    if (degenerate(f, t)) return 0.0;
    const auto& uv = face(f).uv;
    return normal_deviation(f, position(f, t[0]), position(f, t[1]), position(f, t[2]), uv[t[0]], uv[t[1]], uv[t[2]]);
  }

  /// Would the new triangle (a, b, c) at parameters (ua, ub, uc), cut from `parent`, be
  /// turned against the surface where its parent was not? Thin new triangles (smallest
  /// angle below kThinAngle) are let through: their normal says little and the flips
  /// that follow a split replace them.
  bool folds(std::size_t f, const Triangle& parent, const Vec3& a, const Vec3& b, const Vec3& c, const Point2& ua,
             const Point2& ub, const Point2& uc) {
    if (!surface_normal_ || min_angle(a, b, c) < kThinAngle) return false;
    return normal_deviation(f, a, b, c, ua, ub, uc) > std::max(kMaxNormalDeviation, normal_deviation(f, parent));
  }

  /// Upper-triangular L = {l11, l12, l22} with L^T L the first fundamental form of the
  /// least-squares affine map from the parameter points of `nodes` to their 3D points (in
  /// the face's scaled parameter plane); zeros when the fit degenerates.
  template <std::size_t N>
  std::array<double, 3> quad_metric(std::size_t f, const std::array<std::uint32_t, N>& nodes) {
    const auto& uv = face(f).uv;
    Point2 mu{0.0, 0.0};
    Vec3 mp = Vec3::Zero();
    for (std::uint32_t n : nodes) {
      mu = {mu[0] + uv[n][0] / N, mu[1] + uv[n][1] / N};
      mp += position(f, n) / static_cast<double>(N);
    }
    Eigen::Matrix2d uu = Eigen::Matrix2d::Zero();
    Eigen::Matrix<double, 3, 2> pu = Eigen::Matrix<double, 3, 2>::Zero();
    for (std::uint32_t n : nodes) {
      const Eigen::Vector2d du(uv[n][0] - mu[0], uv[n][1] - mu[1]);
      uu += du * du.transpose();
      pu += (position(f, n) - mp) * du.transpose();
    }
    const double det = uu.determinant();
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return {0.0, 0.0, 0.0};
    const Eigen::Matrix<double, 3, 2> jacobian = pu * uu.inverse();
    const Eigen::Matrix2d g = jacobian.transpose() * jacobian;
    if (!(g(0, 0) > 0.0)) return {0.0, 0.0, 0.0};
    const double l11 = std::sqrt(g(0, 0));
    const double l12 = g(0, 1) / l11;
    const double rest = g(1, 1) - l12 * l12;
    if (!(rest > 0.0)) return {0.0, 0.0, 0.0};
    return {l11, l12, std::sqrt(rest)};
  }

  /// Does the least-squares affine map from the parameter points of `nodes` to their 3D
  /// points (the map quad_metric takes the metric from) put every node within
  /// kAffineResidual of the nodes' extent of its 3D point? Beside a pole, where the
  /// parameters are polar coordinates, it does not.
  template <std::size_t N>
  bool affine(std::size_t f, const std::array<std::uint32_t, N>& nodes) {
    const auto& uv = face(f).uv;
    Eigen::Vector2d mu = Eigen::Vector2d::Zero();
    Vec3 mp = Vec3::Zero();
    for (std::uint32_t n : nodes) {
      mu += Eigen::Vector2d(uv[n][0], uv[n][1]) / static_cast<double>(N);
      mp += position(f, n) / static_cast<double>(N);
    }
    Eigen::Matrix2d uu = Eigen::Matrix2d::Zero();
    Eigen::Matrix<double, 3, 2> pu = Eigen::Matrix<double, 3, 2>::Zero();
    double extent = 0.0;
    for (std::uint32_t n : nodes) {
      const Eigen::Vector2d du = Eigen::Vector2d(uv[n][0], uv[n][1]) - mu;
      uu += du * du.transpose();
      pu += (position(f, n) - mp) * du.transpose();
      extent = std::max(extent, (position(f, n) - mp).norm());
    }
    const double det = uu.determinant();
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
    const Eigen::Matrix<double, 3, 2> jacobian = pu * uu.inverse();
    for (std::uint32_t n : nodes) {
      const Eigen::Vector2d du = Eigen::Vector2d(uv[n][0], uv[n][1]) - mu;
      if (!((position(f, n) - mp - jacobian * du).norm() <= kAffineResidual * extent)) return false;
    }
    return true;
  }

  /// The circumcentre of the 3D triangle mapped to the parameter plane by the affine map
  /// that takes the 3D triangle to its parameter-plane triangle (same barycentric
  /// coordinates): the circumcentre in the triangle's own first fundamental form, which
  /// follows the surface's metric where a per-face scale cannot (free-form surfaces,
  /// cones, spheres).
  Point2 local_circumcenter(std::size_t f, const Triangle& tri) {
    const Vec3 a = position(f, tri[0]), b = position(f, tri[1]), c = position(f, tri[2]);
    const double la = (b - c).squaredNorm(), lb = (c - a).squaredNorm(), lc = (a - b).squaredNorm();
    const double wa = la * (lb + lc - la), wb = lb * (lc + la - lb), wc = lc * (la + lb - lc);
    const double sum = wa + wb + wc;
    const auto& uv = face(f).uv;
    return {(wa * uv[tri[0]][0] + wb * uv[tri[1]][0] + wc * uv[tri[2]][0]) / sum,
            (wa * uv[tri[0]][1] + wb * uv[tri[1]][1] + wc * uv[tri[2]][1]) / sum};
  }

  /// Does `p` lie in the bounding box of face f's nodes in the scaled parameter plane?
  bool in_parameter_box(std::size_t f, const Point2& p) const {
    const FaceState& state = state_[f];
    return p[0] >= state.low[0] && p[0] <= state.high[0] && p[1] >= state.low[1] && p[1] <= state.high[1];
  }

  /// The 3D circumcentre of triangle `tri` of face f projected onto the surface, in the
  /// scaled parameter plane (nothing if the projection fails).
  std::optional<Point2> projected_circumcenter(std::size_t f, const Triangle& tri) {
    const Vec3 a = position(f, tri[0]);
    const Vec3 ab = position(f, tri[1]) - a, ac = position(f, tri[2]) - a;
    const Vec3 n = ab.cross(ac);
    const double denominator = 2.0 * n.squaredNorm();
    if (!(denominator > 0.0)) return std::nullopt;
    const Vec3 center = a + (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / denominator;
    if (!center.allFinite()) return std::nullopt;
    const auto& w = face(f).uv;
    const Point2 start{(w[tri[0]][0] + w[tri[1]][0] + w[tri[2]][0]) / (3.0 * state_[f].scale[0]),
                       (w[tri[0]][1] + w[tri[1]][1] + w[tri[2]][1]) / (3.0 * state_[f].scale[1])};
    const std::optional<Point2> uv = surface_parameters_(f, center, start);
    if (!uv) return std::nullopt;
    return Point2{(*uv)[0] * state_[f].scale[0], (*uv)[1] * state_[f].scale[1]};
  }

  /// Where CAD segment `key` is split: the index k of its first node in its edge's
  /// discretisation and the fraction s of the way from node k to node k + 1 (curve
  /// parameter t_k + s (t_k+1 - t_k)); nothing where it may not be split.
  struct SplitPlace {
    std::size_t k = 0;
    double fraction = 0.5;
    double parameter = 0.0;
    /// The small corner (its vertex) this split widens or balances, if any.
    std::optional<std::uint32_t> widens, balances;
    /// For a balancing split at less than half the segment's reach from the corner: the
    /// split halfway there (fraction and curve parameter), tried where the balancing split
    /// itself would spoil a triangle of a face on the segment.
    std::optional<std::pair<double, double>> halfway;
  };

  /// Where CAD segment `key` may be split, given the small corners it bounds: at its
  /// midpoint, or at a small corner, where the midpoint would narrow it, so as to balance it.
  /// Splitting a segment at a corner moves its chord towards the curve's tangent there:
  /// where that widens the corner by kCornerWidening (the other edge curves away more
  /// sharply, as where a fillet meets a flatter face tangentially), the midpoint split goes
  /// in like any other. Where it narrows the corner (the angle between its chord and the
  /// other CAD edge's first chord) or leaves it as it is (a straight edge), midpoint splits
  /// would cascade into it: the segment is split only where the corner triangle it makes
  /// with the other edge's first segment there (corner, its far end, the other's far end)
  /// is obtuse at the other's far end (the segment reaches farther from the corner by more
  /// than the wedge is wide, so the edge opposite the corner runs along the wedge and the
  /// triangle beyond it is a sliver), and then at that segment's length from the corner
  /// (as Ruppert's concentric shells do, notes §3.8): the corner triangle becomes
  /// isosceles, its free edge crosses the wedge, and the triangles beyond can reach the
  /// bound. A balanced corner is never widened again: balancing moves the other edge's
  /// first node towards the corner, which a curve tangent there (a cusp) turns into room
  /// for more widening splits of this edge, then more balancing, a cascade into the corner.
  /// A widened corner is balanced only where the balancing split narrows it by less than
  /// kCornerWidening (not at a cusp, where it would close the corner; gmsh-wing-fuselage's
  /// face 13, whose 11-degree corner was widened on one edge, stopped at 10.4 degrees
  /// beside the other edge's first segment, twice as long, held). Widening splits are
  /// finitely many (each widens the corner by a tenth) and come before any balancing
  /// split, and an isosceles corner triangle is not obtuse, so the splits at a corner are
  /// finitely many.
  std::optional<SplitPlace> split_place(Key key, const Segment& segment) const {
    const SurfaceMeshes::Edge& edge = meshes_.edges[segment.edge];
    std::size_t k = 0;
    while (k + 1 < edge.vertices.size() && edge_key(edge.vertices[k], edge.vertices[k + 1]) != key) ++k;
    if (k + 1 >= edge.vertices.size()) return std::nullopt;
    const double t0 = edge.parameters[k], t1 = edge.parameters[k + 1];
    SplitPlace middle{k, 0.5, 0.5 * (t0 + t1), std::nullopt, std::nullopt, std::nullopt};
    if (segment.small_corners.empty()) return middle;
    const Vec3 p = edge_point_(segment.edge, middle.parameter);
    if (!p.allFinite()) return std::nullopt;
    const auto angle = [](const Vec3& u, const Vec3& w) { return std::atan2(u.cross(w).norm(), u.dot(w)); };
    bool widens = true;
    // The corner the segment starts from and the shortest first segment of another CAD
    // edge there (for a balancing split).
    std::optional<std::uint32_t> apex;
    double partner_length = std::numeric_limits<double>::infinity();
    std::uint32_t partner_next = 0;  // the other edge's first node at partner_length
    for (const Segment::SmallCorner& corner : segment.small_corners) {
      const std::uint32_t far = corner.corner == edge.vertices[k] ? edge.vertices[k + 1] : edge.vertices[k];
      const auto& partner = meshes_.edges[corner.partner_edge].vertices;
      if (partner.size() < 2) return std::nullopt;
      const Vec3& at = points_[corner.corner];
      std::vector<std::uint32_t> next_nodes;
      if (partner.front() == corner.corner) next_nodes.push_back(partner[1]);
      if (partner.back() == corner.corner) next_nodes.push_back(partner[partner.size() - 2]);
      for (const std::uint32_t next : next_nodes) {
        if (!(angle(p - at, points_[next] - at) >= kCornerWidening * angle(points_[far] - at, points_[next] - at))) {
          widens = false;
        }
        if (apex && *apex != corner.corner) return std::nullopt;  // small corners at both ends
        if (balanced_corners_.count(corner.corner) > 0) widens = false;
        apex = corner.corner;
        // The corner triangle (corner, far, next) is obtuse at next: the segment reaches
        // farther from the corner than the other edge's first segment by more than the
        // width of the wedge there.
        if ((at - points_[next]).dot(points_[far] - points_[next]) < 0.0 && (points_[next] - at).norm() < partner_length) {
          partner_length = (points_[next] - at).norm();
          partner_next = next;
        }
      }
    }
    if (widens) {
      middle.widens = apex;
      return middle;
    }
    if (!apex) return std::nullopt;
    const Vec3& at = points_[*apex];
    const bool from_first = *apex == edge.vertices[k];
    // The shells go round every corner under the bound at the apex, not only the small
    // corner's own wedge: in a face on the segment whose corner there is under the bound
    // (no triangle at it can meet the bound), the first node of its other CAD edge at the
    // apex balances the segment as a small corner's partner does.
    const std::uint32_t reach_end = from_first ? edge.vertices[k + 1] : edge.vertices[k];
    const auto apex_edges = vertex_edges_.find(*apex);
    for (std::size_t f : segment.faces) {
      const auto corner = state_[f].small_face_corners.find(*apex);
      if (corner == state_[f].small_face_corners.end() || !(corner->second < options_.min_angle_deg)) continue;
      if (apex_edges == vertex_edges_.end()) break;
      for (std::size_t e : apex_edges->second) {
        const auto& other = meshes_.edges[e].vertices;
        if (e == segment.edge || other.size() < 2) continue;
        for (const std::uint32_t next : {other.front() == *apex ? other[1] : *apex,
                                         other.back() == *apex ? other[other.size() - 2] : *apex}) {
          if (next == *apex) continue;
          const auto first = segments_.find(edge_key(*apex, next));
          if (first == segments_.end() ||
              std::find(first->second.faces.begin(), first->second.faces.end(), f) == first->second.faces.end()) {
            continue;
          }
          if ((at - points_[next]).dot(points_[reach_end] - points_[next]) < 0.0 && (points_[next] - at).norm() < partner_length) {
            partner_length = (points_[next] - at).norm();
            partner_next = next;
          }
        }
      }
    }
    if (!std::isfinite(partner_length)) return std::nullopt;
    // The curve parameter at a distance from the corner: bisection on the segment's
    // parameter interval (the distance grows from 0 at the corner to the segment's length).
    const auto at_distance = [&](double distance) -> std::optional<double> {
      double near = from_first ? t0 : t1, away = from_first ? t1 : t0;
      for (int step = 0; step < 60; ++step) {
        const double t = 0.5 * (near + away);
        const Vec3 q = edge_point_(segment.edge, t);
        if (!q.allFinite()) return std::nullopt;
        ((q - at).norm() < distance ? near : away) = t;
      }
      const double t = 0.5 * (near + away);
      if (!(t > std::min(t0, t1) && t < std::max(t0, t1))) return std::nullopt;
      return t;
    };
    const std::optional<double> balancing = at_distance(partner_length);
    if (!balancing) return std::nullopt;
    const double t = *balancing;
    if (widened_corners_.count(*apex) > 0) {
      // A widened corner is balanced only where that narrows it by less than
      // kCornerWidening: on two curves tangent at the corner (a cusp) the balancing split
      // moves the chord to the tangent and the corner closes.
      const Vec3 q = edge_point_(segment.edge, t);
      const Vec3& far = points_[from_first ? edge.vertices[k + 1] : edge.vertices[k]];
      const Vec3& next = points_[partner_next];
      if (!(kCornerWidening * angle(q - at, next - at) >= angle(far - at, next - at))) return std::nullopt;
    }
    SplitPlace place{k, (t - t0) / (t1 - t0), t, std::nullopt, apex, std::nullopt};
    // The segment reaches more than twice as far from the corner as the other edge's first
    // node: its split halfway is the next of Ruppert's concentric shells towards the
    // balance (notes §3.8).
    const double reach = (points_[from_first ? edge.vertices[k + 1] : edge.vertices[k]] - at).norm();
    if (partner_length < 0.5 * reach) {
      if (const std::optional<double> half = at_distance(0.5 * reach)) place.halfway = {{(*half - t0) / (t1 - t0), *half}};
    }
    return place;
  }

  /// Can CAD segment `key` be split (not shared by two CAD edges, not narrowing a small
  /// corner other than to balance it)?
  bool splittable(Key key) const {
    const auto it = segments_.find(key);
    return it != segments_.end() && !it->second.ambiguous && split_place(key, it->second).has_value();
  }

  /// A CAD segment of face f whose diametral circle (in the scaled parameter plane)
  /// contains p and that may be split: Ruppert's encroachment rule, splitting the segment
  /// instead keeps new nodes away from the boundary. A segment that is never split does
  /// not stop p from going in, unless p would make a triangle on it (3D point `at`) with
  /// an angle under the bound: then `blocked` is set to its local edge.
  std::optional<Key> encroached_segment(std::size_t f, const Point2& p, const Vec3& at, std::optional<Key>& blocked) {
    const auto& uv = face(f).uv;
    for (const auto& [global, locals] : state_[f].segment_edges) {
      for (Key local : locals) {
        const auto i = static_cast<std::uint32_t>(local >> 32);
        const auto j = static_cast<std::uint32_t>(local);
        const double dot = (uv[i][0] - p[0]) * (uv[j][0] - p[0]) + (uv[i][1] - p[1]) * (uv[j][1] - p[1]);
        if (dot > 0.0) {
          // Inside the segment's diametral ball only in 3D, on a face with a pole: split it
          // if it may be split.
          if (state_[f].has_pole && in_diametral_ball(f, i, j, at) && splittable(global)) return global;
          continue;
        }
        if (splittable(global)) return global;
        if (!(min_angle(position(f, i), position(f, j), at) >= bound_)) blocked = local;
      }
    }
    return std::nullopt;
  }

  /// A point for a circumcentre `center` of face f that a segment never split blocks
  /// (local edge `local`: the circumcentre lies in its diametral circle and would make a
  /// triangle on it with an angle under the bound): the point over the segment, on the
  /// circumcentre's side, whose triangle with the segment has angles just over
  /// the bound, above the circumcentre's foot on the segment (kept to the segment's middle
  /// half, so that lifted points stay at least a tenth of the segment's length off it in
  /// the scaled plane); nothing if no height up to kLiftSteps growths makes a triangle
  /// with the segment whose smallest 3D angle is kLiftAngle times the bound.
  std::optional<Point2> lifted_point(std::size_t f, Key local, const Point2& center) {
    const auto i = static_cast<std::uint32_t>(local >> 32);
    const auto j = static_cast<std::uint32_t>(local);
    const Point2& a = face(f).uv[i];
    const Point2& b = face(f).uv[j];
    const double du = b[0] - a[0], dv = b[1] - a[1];
    const double length = std::hypot(du, dv);
    if (!(length > 0.0)) return std::nullopt;
    const double side = du * (center[1] - a[1]) - dv * (center[0] - a[0]);
    if (side == 0.0) return std::nullopt;
    const double s = std::clamp(((center[0] - a[0]) * du + (center[1] - a[1]) * dv) / (length * length), 0.25, 0.75);
    const Point2 foot{a[0] + s * du, a[1] + s * dv};
    const Point2 normal{(side > 0.0 ? -dv : dv) / length, (side > 0.0 ? du : -du) / length};
    const double reach = std::min(s, 1.0 - s) * length;
    // Raised step by step from the height that gives the bound in the scaled plane (which
    // is not the surface's metric) until the 3D triangle with the segment meets it.
    double height = reach * std::tan(kLiftAngle * bound_);
    for (int step = 0; step < kLiftSteps; ++step, height *= kLiftGrowth) {
      const Point2 p{foot[0] + height * normal[0], foot[1] + height * normal[1]};
      const Vec3 at = surface_at(f, p);
      if (at.allFinite() && min_angle(position(f, i), position(f, j), at) >= kLiftAngle * bound_) return p;
    }
    return std::nullopt;
  }

  /// Does 3D point p lie in the open diametral ball of the chord of local edge (i, j) of
  /// face f (not on its sphere: the ends themselves, a pole's copies, do not count)? Beside
  /// a pole, where one parameter moves a point by almost nothing, a point far from a
  /// segment in the parameter plane can lie next to it in 3D; used on faces with a pole
  /// only (elsewhere it stopped refinement short: occt-screw 20.2 -> 7.6 degrees).
  bool in_diametral_ball(std::size_t f, std::uint32_t i, std::uint32_t j, const Vec3& p) {
    if (!p.allFinite()) return false;
    return (position(f, i) - p).dot(position(f, j) - p) < 0.0;
  }

  /// Does p lie in the diametral circle (scaled parameter plane) of a CAD segment of f?
  bool encroaches_any_segment(std::size_t f, const Point2& p) {
    const auto& uv = face(f).uv;
    for (const auto& [global, locals] : state_[f].segment_edges) {
      for (Key local : locals) {
        const auto i = static_cast<std::uint32_t>(local >> 32);
        const auto j = static_cast<std::uint32_t>(local);
        if ((uv[i][0] - p[0]) * (uv[j][0] - p[0]) + (uv[i][1] - p[1]) * (uv[j][1] - p[1]) <= 0.0) return true;
      }
    }
    return false;
  }

  /// After a segment split: subsegments whose opposite vertex (in a triangle on them)
  /// lies in their diametral circle are split too, as in Ruppert's algorithm.
  void split_encroached_subsegments(std::size_t budget_end) {
    while (!encroached_.empty() && points_.size() < budget_end) {
      const Key global = encroached_.back();
      encroached_.pop_back();
      const auto segment = segments_.find(global);
      if (segment == segments_.end()) continue;
      bool encroached = false;
      for (std::size_t f : segment->second.faces) {
        const auto locals = state_[f].segment_edges.find(global);
        if (locals == state_[f].segment_edges.end() || !state_[f].refinable) continue;
        const auto& uv = face(f).uv;
        for (Key local : locals->second) {
          const auto adjacent = state_[f].edge_triangles.find(local);
          if (adjacent == state_[f].edge_triangles.end()) continue;
          const auto i = static_cast<std::uint32_t>(local >> 32);
          const auto j = static_cast<std::uint32_t>(local);
          for (std::int64_t t : adjacent->second) {
            if (t < 0) continue;
            for (std::uint32_t apex : face(f).triangles[static_cast<std::size_t>(t)]) {
              if (apex == i || apex == j) continue;
              const Point2& p = uv[apex];
              if ((uv[i][0] - p[0]) * (uv[j][0] - p[0]) + (uv[i][1] - p[1]) * (uv[j][1] - p[1]) <= 0.0) {
                encroached = true;
              }
            }
          }
        }
      }
      if (encroached) split_segment(global);
    }
    encroached_.clear();
  }

  /// The triangle's smallest angle lies between two CAD segments: an angle of the input
  /// (two CAD edges meeting at a small angle) that no refinement can enlarge; refining
  /// there would only cascade towards the corner.
  bool small_input_angle(std::size_t f, const Triangle& tri) {
    int smallest = 0;
    double angle = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = position(f, tri[k]);
      const Vec3 u = position(f, tri[(k + 1) % 3]) - p, w = position(f, tri[(k + 2) % 3]) - p;
      const double corner = std::atan2(u.cross(w).norm(), u.dot(w));
      if (corner < angle) {
        angle = corner;
        smallest = k;
      }
    }
    // At a face corner narrower than the bound: no triangle there can meet the bound, and
    // refining the corner's fan cascades into the corner.
    const auto corner = state_[f].small_face_corners.find(face(f).node_vertex[tri[smallest]]);
    if (corner != state_[f].small_face_corners.end() && corner->second < options_.min_angle_deg) return true;
    return segment_of(f, tri[smallest], tri[(smallest + 1) % 3]).has_value() &&
           segment_of(f, tri[smallest], tri[(smallest + 2) % 3]).has_value();
  }

  /// The CAD segment local edge (i, j) of face f lies on, if any.
  std::optional<Key> segment_of(std::size_t f, std::uint32_t i, std::uint32_t j) {
    const auto& v = face(f).node_vertex;
    const Key global = edge_key(v[i], v[j]);
    if (segments_.count(global) == 0) return std::nullopt;
    return global;
  }

  /// Beside a pole (a triangle of face f joining two copies of one node, collapsed in 3D)
  /// the parameters are polar coordinates: every node near the pole that the collapsed
  /// triangle's apex sees is joined to that apex, however far from the pole it lies, and
  /// the triangles between them are needles that no flip in the parameter plane removes
  /// (the collapsed triangle is never flipped); at a pole that is a small corner of the
  /// face (gmsh-wing-fuselage's wing-tip patches) their circumcentres split the corner's
  /// segments again and again (a cascade into the corner down to the edge-length floor,
  /// 0.03 degrees). Where the apex lies more than twice as far from the pole as the
  /// farthest of the pole's neighbours along CAD segments (the first nodes of the CAD edges
  /// at the corner), a node goes into the collapsed triangle at that neighbour's distance
  /// from the pole (on the parameter-plane line from the middle of the collapsed edge to the
  /// apex): the pole's fan then has its apex where the first nodes around the corner are,
  /// as Ruppert's concentric shells put them around a small input angle (notes §3.8), and
  /// the 3D max-min flips of faces with a pole join the nodes across the wedge. Each
  /// insertion at least halves the apex's distance from the pole and none comes within
  /// twice the edge-length floor of it, so the insertions are finitely many.
  void place_pole_apexes(std::size_t f, std::size_t budget_end) {
    for (std::size_t t = 0; t < face(f).triangles.size() && points_.size() < budget_end; ++t) {
      const Triangle tri = face(f).triangles[t];
      const auto& v = face(f).node_vertex;
      int apex = -1;
      for (int k = 0; k < 3; ++k) {
        if (v[tri[(k + 1) % 3]] == v[tri[(k + 2) % 3]] && v[tri[k]] != v[tri[(k + 1) % 3]]) apex = k;
      }
      if (apex < 0) continue;
      const std::uint32_t x = tri[apex], c1 = tri[(apex + 1) % 3], c2 = tri[(apex + 2) % 3];
      const Vec3 pole = position(f, c1);
      const double apex_distance = (position(f, x) - pole).norm();
      double nearest = 0.0;
      for (const auto& [key, tris] : state_[f].edge_triangles) {
        const auto i = static_cast<std::uint32_t>(key >> 32), j = static_cast<std::uint32_t>(key);
        for (const auto& [end, other] : {std::pair{i, j}, std::pair{j, i}}) {
          if ((end == c1 || end == c2) && v[other] != v[c1] && other != x && is_segment(f, end, other)) {
            nearest = std::max(nearest, (position(f, other) - pole).norm());
          }
        }
      }
      if (!(apex_distance > 2.0 * nearest) || !(nearest > 2.0 * options_.min_edge_length)) continue;
      const auto& uv = face(f).uv;
      const Point2 base{0.5 * (uv[c1][0] + uv[c2][0]), 0.5 * (uv[c1][1] + uv[c2][1])};
      const auto along = [&](double s) {
        return Point2{base[0] + s * (uv[x][0] - base[0]), base[1] + s * (uv[x][1] - base[1])};
      };
      double low = 0.0, high = 1.0;
      for (int step = 0; step < 60; ++step) {
        const double middle = 0.5 * (low + high);
        const Vec3 q = surface_at(f, along(middle));
        if (!q.allFinite()) break;
        ((q - pole).norm() < nearest ? low : high) = middle;
      }
      const Point2 at = along(0.5 * (low + high));
      const Vec3 offset = offset_in(f, tri, at);
      const Vec3 p = surface_at(f, at) + offset;
      if (!p.allFinite() || !((p - pole).norm() > options_.min_edge_length)) continue;
      const double* m = at.data();
      if (predicates::orient2d(uv[x].data(), uv[c1].data(), m) != Sign::Positive ||
          predicates::orient2d(uv[c1].data(), uv[c2].data(), m) != Sign::Positive ||
          predicates::orient2d(uv[c2].data(), uv[x].data(), m) != Sign::Positive) {
        continue;
      }
      const std::uint32_t node = split_triangle(f, t, apex, at, p, offset);
      pending_flips_.push_back({f, edge_key(x, node)});
      legalize();
      ++stats_.interior_splits;
    }
  }

  /// Splits triangle t of face f into three at a new node placed on the surface at `xy`
  /// (or, where that lies on one of its edges in 3D, the edge: split_edge_near).
  bool insert_in_triangle(std::size_t f, std::size_t t, const Point2& xy, bool may_split_segment) {
    const Triangle tri = face(f).triangles[t];
    const Vec3 offset = offset_in(f, tri, xy);
    const Vec3 p = surface_at(f, xy) + offset;
    if (!p.allFinite()) return false;
    for (int k = 0; k < 3; ++k) {
      if (min_angle(position(f, tri[k]), position(f, tri[(k + 1) % 3]), p) < kDegenerateAngle) {
        // On an edge in 3D (a centre of a disk on one of its diameters): split the edge
        // there instead, at the parameter point's projection onto it.
        return split_edge_near(f, tri[k], tri[(k + 1) % 3], xy, may_split_segment);
      }
      // Not next to an existing node: an edge that short could never be refined away.
      if (!((position(f, tri[k]) - p).norm() > options_.min_edge_length)) return false;
      if (folds(f, tri, position(f, tri[k]), position(f, tri[(k + 1) % 3]), p, face(f).uv[tri[k]],
                face(f).uv[tri[(k + 1) % 3]], xy)) {
        return false;
      }
    }
    split_triangle(f, t, 0, xy, p, offset);
    legalize();
    ++stats_.interior_splits;
    return true;
  }

  /// Splits triangle t of face f into three at a new node (parameter point xy, 3D point p,
  /// its offset), the first new triangle starting at corner `first`; queues the old
  /// triangle's edges for flips and returns the node.
  std::uint32_t split_triangle(std::size_t f, std::size_t t, int first, const Point2& xy, const Vec3& p,
                               const Vec3& offset) {
    const Triangle tri = face(f).triangles[t];
    const std::uint32_t a = tri[first], b = tri[(first + 1) % 3], c = tri[(first + 2) % 3];
    points_.push_back(p);
    SurfaceMeshes::Face& mesh = face(f);
    state_[f].touched = true;
    const auto m = static_cast<std::uint32_t>(mesh.uv.size());
    mesh.uv.push_back(xy);
    mesh.node_vertex.push_back(static_cast<std::uint32_t>(points_.size() - 1));
    if (!mesh.offset.empty()) mesh.offset.push_back(offset);
    remove_triangle_edges(f, t);
    mesh.triangles[t] = {a, b, m};
    mesh.triangles.push_back({b, c, m});
    mesh.triangles.push_back({c, a, m});
    add_triangle_edges(f, t);
    add_triangle_edges(f, mesh.triangles.size() - 2);
    add_triangle_edges(f, mesh.triangles.size() - 1);
    for (int k = 0; k < 3; ++k) pending_flips_.push_back({f, edge_key(tri[k], tri[(k + 1) % 3])});
    return m;
  }

  /// Splits local edge (i, j) of face f at the projection of `xy` onto it in the
  /// parameter plane (kept off its ends): the CAD segment in every face if it is one
  /// and `may_split_segment`.
  bool split_edge_near(std::size_t f, std::uint32_t i, std::uint32_t j, const Point2& xy, bool may_split_segment) {
    if (const std::optional<Key> segment = segment_of(f, i, j)) return may_split_segment && split_segment(*segment);
    const auto& uv = face(f).uv;
    const double du = uv[j][0] - uv[i][0], dv = uv[j][1] - uv[i][1];
    const double length2 = du * du + dv * dv;
    if (!(length2 > 0.0)) return false;
    const double s = std::clamp(((xy[0] - uv[i][0]) * du + (xy[1] - uv[i][1]) * dv) / length2, 0.25, 0.75);
    return split_interior_edge(f, i, j, {uv[i][0] + s * du, uv[i][1] + s * dv});
  }

  /// Is PLC vertex `vertex` a node of CAD edge `edge`?
  bool apex_on_edge(std::uint32_t vertex, std::size_t edge) const {
    const auto edges = vertex_edges_.find(vertex);
    return edges != vertex_edges_.end() &&
           std::find(edges->second.begin(), edges->second.end(), edge) != edges->second.end();
  }

  /// a, b and c are consecutive nodes of one CAD edge: a flat triangle BRepMesh leaves
  /// along a boundary; refining it would only add flat triangles.
  bool on_one_cad_edge(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const auto ea = vertex_edges_.find(a);
    if (ea == vertex_edges_.end()) return false;
    std::array<std::uint32_t, 3> sorted{a, b, c};
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t e : ea->second) {
      const auto& v = meshes_.edges[e].vertices;
      for (std::size_t k = 0; k + 2 < v.size(); ++k) {
        std::array<std::uint32_t, 3> run{v[k], v[k + 1], v[k + 2]};
        std::sort(run.begin(), run.end());
        if (run == sorted) return true;
      }
    }
    return false;
  }

  /// The offset (SurfaceMeshes::Face::offset) of face f at parameter point xy of triangle
  /// `tri`: its nodes' offsets interpolated by xy's barycentric coordinates in the
  /// parameter plane; zero on faces without offsets.
  Vec3 offset_in(std::size_t f, const Triangle& tri, const Point2& xy) {
    const auto& offset = face(f).offset;
    if (offset.empty()) return Vec3::Zero();
    const auto& uv = face(f).uv;
    const Point2& a = uv[tri[0]];
    const Point2& b = uv[tri[1]];
    const Point2& c = uv[tri[2]];
    const double det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (!(std::abs(det) > 0.0)) return (offset[tri[0]] + offset[tri[1]] + offset[tri[2]]) / 3.0;
    const double wb = ((xy[0] - a[0]) * (c[1] - a[1]) - (xy[1] - a[1]) * (c[0] - a[0])) / det;
    const double wc = ((b[0] - a[0]) * (xy[1] - a[1]) - (b[1] - a[1]) * (xy[0] - a[0])) / det;
    return (1.0 - wb - wc) * offset[tri[0]] + wb * offset[tri[1]] + wc * offset[tri[2]];
  }

  /// The offset of face f at parameter point xy on local edge (i, j) (its projection onto
  /// the edge in the parameter plane), interpolated linearly; zero without offsets.
  Vec3 offset_on(std::size_t f, std::uint32_t i, std::uint32_t j, const Point2& xy) {
    const auto& offset = face(f).offset;
    if (offset.empty()) return Vec3::Zero();
    const auto& uv = face(f).uv;
    const double du = uv[j][0] - uv[i][0], dv = uv[j][1] - uv[i][1];
    const double length2 = du * du + dv * dv;
    const double s = length2 > 0.0 ? std::clamp(((xy[0] - uv[i][0]) * du + (xy[1] - uv[i][1]) * dv) / length2, 0.0, 1.0) : 0.5;
    return (1.0 - s) * offset[i] + s * offset[j];
  }

  Vec3 surface_at(std::size_t f, const Point2& xy) {
    return surface_point_(f, {xy[0] / state_[f].scale[0], xy[1] / state_[f].scale[1]});
  }

  /// The triangles on local edge (i, j) of face f, each split by local node m: checks
  /// that all new triangles are positively oriented in the parameter plane.
  bool split_is_valid(std::size_t f, std::uint32_t i, std::uint32_t j, const Point2& uv_m) {
    if (!state_[f].uv_valid) return true;
    auto it = state_[f].edge_triangles.find(edge_key(i, j));
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
  /// new triangle at least `keeps` (kSplitKeeps) times as good as the triangle it comes
  /// from, or as `keeps` times the bound (a point off the chord on a curved surface, or on a
  /// strongly distorted parametrisation, may make far worse ones).
  bool keeps_angles(std::size_t f, std::uint32_t i, std::uint32_t j, const Vec3& p, const Point2& uv_p,
                    std::optional<std::size_t> cad_edge = std::nullopt, double keeps = kSplitKeeps) {
    if (!face(f).refine && !face(f).keep_min_angle) return true;  // written as a polygon
    auto it = state_[f].edge_triangles.find(edge_key(i, j));
    if (it == state_[f].edge_triangles.end()) return false;
    for (std::int64_t t : it->second) {
      if (t < 0) continue;
      Triangle tri = face(f).triangles[static_cast<std::size_t>(t)];
      if (degenerate(f, tri)) continue;
      if (!rotate_to(tri, i, j)) rotate_to(tri, j, i);
      const double before = quality(f, tri);
      const Vec3 a = position(f, tri[0]), b = position(f, tri[1]), c = position(f, tri[2]);
      const double after = std::min(min_angle(a, p, c), min_angle(p, b, c));
      if (after < keeps * std::min(before, bound_)) return false;
      // An apex on the CAD edge being split makes a flat triangle along that edge, which
      // refinement leaves alone (on_one_cad_edge): it must not get flatter, or repeated
      // splits halve its angle again and again.
      if (cad_edge && after < before && apex_on_edge(face(f).node_vertex[tri[2]], *cad_edge)) return false;
      if (face(f).keep_min_angle && after < std::min(state_[f].min_angle_before, bound_)) return false;
      const auto& uv = face(f).uv;
      if (folds(f, tri, a, p, c, uv[tri[0]], uv_p, uv[tri[2]]) || folds(f, tri, p, b, c, uv_p, uv[tri[1]], uv[tri[2]])) {
        return false;
      }
    }
    return true;
  }

  /// Splits the triangles on local edge (i, j) of face f at a new local node (with
  /// `offset`, SurfaceMeshes::Face::offset).
  void apply_split(std::size_t f, std::uint32_t i, std::uint32_t j, const Point2& uv_m,
                   std::uint32_t vertex, const Vec3& offset) {
    SurfaceMeshes::Face& mesh = face(f);
    state_[f].touched = true;
    const auto m = static_cast<std::uint32_t>(mesh.uv.size());
    mesh.uv.push_back(uv_m);
    mesh.node_vertex.push_back(vertex);
    if (!mesh.offset.empty()) mesh.offset.push_back(offset);
    const std::array<std::int64_t, 2> tris = state_[f].edge_triangles.at(edge_key(i, j));
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
      pending_flips_.push_back({f, edge_key(tri[2], tri[0])});
      pending_flips_.push_back({f, edge_key(tri[1], tri[2])});
    }
  }

  /// Lawson's flip propagation around new nodes: flip the queued edges where the
  /// max-min angle criterion asks for it, queueing the outer edges of flipped quads.
  void legalize() {
    std::size_t budget = 64 * pending_flips_.size() + 64;
    while (!pending_flips_.empty() && budget-- > 0) {
      const auto [f, key] = pending_flips_.back();
      pending_flips_.pop_back();
      if (!state_[f].refinable) continue;
      std::array<Key, 4> outer{};
      if (try_flip(f, key, &outer)) {
        ++stats_.flips;
        for (Key k : outer) pending_flips_.push_back({f, k});
      }
    }
    pending_flips_.clear();
  }

  bool split_interior_edge(std::size_t f, std::uint32_t i, std::uint32_t j, const Point2& uv_m,
                           double keeps = kSplitKeeps) {
    auto it = state_[f].edge_triangles.find(edge_key(i, j));
    if (it == state_[f].edge_triangles.end() || it->second[1] < 0) return false;
    if (!split_is_valid(f, i, j, uv_m)) return false;
    const Vec3 offset = offset_on(f, i, j, uv_m);
    const Vec3 p = surface_at(f, uv_m) + offset;
    if (!p.allFinite() || !keeps_angles(f, i, j, p, uv_m, std::nullopt, keeps)) return false;
    points_.push_back(p);
    apply_split(f, i, j, uv_m, static_cast<std::uint32_t>(points_.size() - 1), offset);
    legalize();
    ++stats_.interior_splits;
    return true;
  }

  bool split_segment(Key key) {
    auto found = segments_.find(key);
    if (found == segments_.end() || found->second.ambiguous) return false;
    std::optional<SplitPlace> place = split_place(key, found->second);
    if (!place) return false;
    const Segment segment = found->second;
    const auto a = static_cast<std::uint32_t>(key >> 32);
    const auto b = static_cast<std::uint32_t>(key);
    SurfaceMeshes::Edge& edge = meshes_.edges[segment.edge];
    const std::size_t k = place->k;
    if (!((points_[a] - points_[b]).norm() > 2.0 * options_.min_edge_length)) return false;
    // Local edges on the segment in every face, with the parameter-plane points at the
    // split's fraction of the way from the edge's node k.
    struct LocalSplit {
      std::size_t face;
      std::uint32_t i, j;
      Point2 uv;
    };
    std::vector<LocalSplit> splits;
    const auto place_splits = [&](double fraction) {
      splits.clear();
      for (std::size_t f : segment.faces) {
        auto local = state_[f].segment_edges.find(key);
        if (local == state_[f].segment_edges.end()) continue;
        for (Key local_key : local->second) {
          const auto i = static_cast<std::uint32_t>(local_key >> 32);
          const auto j = static_cast<std::uint32_t>(local_key);
          const auto& uv = face(f).uv;
          const double s = face(f).node_vertex[i] == edge.vertices[k] ? fraction : 1.0 - fraction;
          splits.push_back({f, i, j, {uv[i][0] + s * (uv[j][0] - uv[i][0]), uv[i][1] + s * (uv[j][1] - uv[i][1])}});
          if (!split_is_valid(f, i, j, splits.back().uv)) return false;
        }
      }
      return true;
    };
    if (!place_splits(place->fraction)) return false;
    // The new vertex is joined to the apex of every triangle on the segment: two faces
    // with the same apex would give the PLC one segment twice (through the model).
    std::vector<std::uint32_t> apexes;
    for (const LocalSplit& split : splits) {
      const auto tris = state_[split.face].edge_triangles.find(edge_key(split.i, split.j));
      if (tris == state_[split.face].edge_triangles.end()) continue;
      for (std::int64_t t : tris->second) {
        if (t < 0) continue;
        for (std::uint32_t node : face(split.face).triangles[static_cast<std::size_t>(t)]) {
          if (node != split.i && node != split.j) apexes.push_back(face(split.face).node_vertex[node]);
        }
      }
    }
    std::sort(apexes.begin(), apexes.end());
    if (std::adjacent_find(apexes.begin(), apexes.end()) != apexes.end()) return false;
    const auto keeps_everywhere = [&](const Vec3& at) {
      return std::all_of(splits.begin(), splits.end(), [&](const LocalSplit& split) {
        return keeps_angles(split.face, split.i, split.j, at, split.uv, segment.edge);
      });
    };
    Vec3 p = edge_point_(segment.edge, place->parameter);
    if (!p.allFinite()) return false;
    if (!keeps_everywhere(p)) {
      // A balancing split too close to the corner for a face on the segment: the split
      // halfway to the corner instead (the next shell), where that keeps the angles.
      if (!place->halfway) return false;
      place->fraction = place->halfway->first;
      place->parameter = place->halfway->second;
      p = edge_point_(segment.edge, place->parameter);
      if (!p.allFinite() || !place_splits(place->fraction) || !keeps_everywhere(p)) return false;
    }
    const double t = place->parameter;
    if (place->widens) widened_corners_.insert(*place->widens);
    if (place->balances) balanced_corners_.insert(*place->balances);
    points_.push_back(p);
    const auto m = static_cast<std::uint32_t>(points_.size() - 1);
    edge.vertices.insert(edge.vertices.begin() + static_cast<std::ptrdiff_t>(k) + 1, m);
    vertex_edges_[m].push_back(segment.edge);
    edge.parameters.insert(edge.parameters.begin() + static_cast<std::ptrdiff_t>(k) + 1, t);
    segments_.erase(found);
    Segment first = segment, second = segment;
    // Each half keeps the small corners at its own ends.
    std::erase_if(first.small_corners, [&](const Segment::SmallCorner& c) { return c.corner != a; });
    std::erase_if(second.small_corners, [&](const Segment::SmallCorner& c) { return c.corner != b; });
    segments_[edge_key(a, m)] = first;
    segments_[edge_key(m, b)] = second;
    for (std::size_t f : segment.faces) state_[f].segment_edges.erase(key);
    for (const LocalSplit& s : splits) {
      apply_split(s.face, s.i, s.j, s.uv, m,
                  face(s.face).offset.empty() ? Vec3(Vec3::Zero()) : Vec3(p - surface_at(s.face, s.uv)));
      const auto local_m = static_cast<std::uint32_t>(face(s.face).uv.size() - 1);
      const auto& v = face(s.face).node_vertex;
      state_[s.face].segment_edges[edge_key(v[s.i], m)].push_back(edge_key(s.i, local_m));
      state_[s.face].segment_edges[edge_key(m, v[s.j])].push_back(edge_key(local_m, s.j));
    }
    legalize();
    encroached_.push_back(edge_key(a, m));
    encroached_.push_back(edge_key(m, b));
    ++stats_.boundary_splits;
    return true;
  }

  SurfaceMeshes& meshes_;
  std::vector<Vec3>& points_;
  SurfaceRefinementOptions options_;
  const SurfacePoint& surface_point_;
  const EdgePoint& edge_point_;
  const SurfaceNormal& surface_normal_;
  const SurfaceParameters& surface_parameters_;
  std::vector<FaceState> state_;
  std::vector<std::pair<std::size_t, Key>> pending_flips_;  ///< (face, local edge) to check
  std::vector<Key> encroached_;  ///< new subsegments to check for encroachment
  double bound_;  ///< radians
  std::unordered_map<Key, Segment> segments_;
  std::unordered_map<Key, int> global_edges_;  ///< PLC vertex pair -> local edges of all faces on it
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> vertex_edges_;  ///< CAD edges through a vertex
  /// Small corners (their vertices) where a split widened or balanced the corner.
  std::unordered_set<std::uint32_t> widened_corners_, balanced_corners_;
  SurfaceRefinementStats stats_;
};

}  // namespace

SurfaceRefinementStats refine_surface_meshes(SurfaceMeshes& meshes, std::vector<Vec3>& points,
                                             const SurfaceRefinementOptions& options,
                                             const SurfacePoint& surface_point,
                                             const EdgePoint& edge_point,
                                             const SurfaceNormal& surface_normal,
                                             const SurfaceParameters& surface_parameters) {
  return Refiner(meshes, points, options, surface_point, edge_point, surface_normal, surface_parameters).run();
}

}  // namespace delmesh::step
