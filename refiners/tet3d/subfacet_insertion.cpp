// Vertex insertion on a subfacet for the polish (see subfacet_insertion.h; notes §2.2.4,
// §4.2.1).
#include "refiners/tet3d/subfacet_insertion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/small_angles.h"
#include "toolkit/core/error.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::tet3d {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// The compass search of a new vertex's position (SubfacetInserter::search_point): its
/// directions in the facet's plane, most step halvings and most evaluations.
constexpr int kSearchDirections = 8;
constexpr int kSearchHalvings = 6;
constexpr int kSearchEvaluations = 64;
/// The starting points besides the circumcenter and centroid: the interior points of the
/// subfacet's barycentric grid of step 1/kStartGrid (10 with 6, the centroid aside).
constexpr int kStartGrid = 6;

/// The Lawson flips after the split of subfacet `f` (vertices counterclockwise) at p,
/// strictly inside it: every edge opposite p that is neither a segment nor on the facet's
/// boundary and whose far subfacet's in-plane circle holds p (the facet's own test,
/// incircle_in_plane), in the order a stack of those edges meets them, each with its
/// quadrilateral strictly convex as FacetTriangulation::flip_edge asks (exact
/// orient2d_projected). `removed` gets the subfacets removed (f and those beyond the
/// flipped edges, sorted), `flips` the flipped edges (x, y), each of triangle (x, y, p)
/// when flipped. False when a quadrilateral is not strictly convex. Each flip removes a
/// subfacet, so at most the facet's subfacets are visited.
bool facet_flips(const TetMesh& mesh, const FacetTriangulation& facet, const Subface& f, const Vec3& p,
                 std::vector<FaceKey>& removed, std::vector<std::pair<std::uint32_t, std::uint32_t>>& flips) {
  removed.assign(1, sorted_face_key(f[0], f[1], f[2]));
  flips.clear();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges{{f[0], f[1]}, {f[1], f[2]}, {f[2], f[0]}};
  const Axis axis = facet.axis();
  while (!edges.empty()) {
    const auto [x, y] = edges.back();
    edges.pop_back();
    if (facet.is_segment(x, y)) continue;
    const std::uint32_t z = facet.third_vertex(y, x);
    if (z == ~0u) continue;
    // The facet's coordinates are the tetrahedralization's (sliver_improvement.h).
    if (predicates::incircle_in_plane(mesh.coords(x), mesh.coords(y), p.data(), mesh.coords(z), axis,
                                      facet.normal().data()) != Sign::Positive)
      continue;
    if (predicates::orient2d_projected(mesh.coords(z), p.data(), mesh.coords(x), axis) != Sign::Positive ||
        predicates::orient2d_projected(p.data(), mesh.coords(z), mesh.coords(y), axis) != Sign::Positive)
      return false;
    removed.push_back(sorted_face_key(x, y, z));
    flips.push_back({x, y});
    edges.push_back({x, z});
    edges.push_back({z, y});
  }
  std::sort(removed.begin(), removed.end());
  return true;
}

/// Judges and makes the insertions of insert_on_subfacets.
class SubfacetInserter {
 public:
  explicit SubfacetInserter(RefineState& state)
      : state_(state),
        mesh_(state.mesh),
        low_(state.options.min_dihedral_deg),
        high_(state.options.max_dihedral_deg),
        scale_(window_obtuse_scale(low_, high_)),
        small_(small_angle_vertices(state)) {}

  std::size_t run() {
    // The tets to try, by their vertices: an insertion kills tets whose slots later ones
    // may take.
    std::vector<std::array<std::uint32_t, 4>> bad;
    for (std::uint32_t t = 0; t < mesh_.tet_slots(); ++t)
      if (mesh_.is_finite(t) && !mesh_.is_dead(t) && domain(t) && !touches_small(mesh_.tet(t).v) &&
          outside(mesh_.tet(t).v))
        bad.push_back(mesh_.tet(t).v);
    std::size_t made = 0;
    for (const auto& v : bad) {
      const auto ref = find_face_ref(state_, v[0], v[1], v[2]);
      if (!ref) continue;
      std::uint32_t t = ref->tet;
      if (!has_vertex(t, v[3])) t = mesh_.neighbor(ref->tet, ref->face);
      if (mesh_.is_dead(t) || !mesh_.is_finite(t) || !has_vertex(t, v[3]) || !domain(t) || !outside(mesh_.tet(t).v))
        continue;
      if (try_tet(t)) ++made;
    }
    return made;
  }

 private:
  bool domain(std::uint32_t t) const { return t < state_.tet_region.size() && in_domain(state_.tet_region[t]); }
  bool has_vertex(std::uint32_t t, std::uint32_t x) const {
    const auto& v = mesh_.tet(t).v;
    return std::find(v.begin(), v.end(), x) != v.end();
  }
  /// The new vertex touches no small angle (as in the pass's insertion).
  bool touches_small(const std::array<std::uint32_t, 4>& v) const {
    for (const std::uint32_t x : v)
      if (x < small_.size() && small_[x] != 0) return true;
    return false;
  }
  bool outside(const std::array<std::uint32_t, 4>& v) const {
    return dihedral_outside(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), mesh_.point(v[3]), low_, high_);
  }

  /// Tries the subfacet faces of tet t, from the circumcenter, the centroid and the
  /// points of a grid in turn: the point is placed by search_point and inserted at the
  /// first that gains.
  bool try_tet(std::uint32_t t) {
    const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
    for (int f = 0; f < 4; ++f) {
      const auto& o = kFaceVertex[f];
      const std::array<std::uint32_t, 3> face{v[o[0]], v[o[1]], v[o[2]]};
      const std::uint32_t* facet = subface_of(state_, face[0], face[1], face[2]);
      if (!facet) continue;
      const Vec3 pa = mesh_.point(face[0]), pb = mesh_.point(face[1]), pc = mesh_.point(face[2]);
      // The circumcenter, the centroid, then the other interior points of the subfacet's
      // barycentric grid of step 1/kStartGrid.
      starts_.assign({triangle_circumcenter(pa, pb, pc), (pa + pb + pc) / 3.0});
      for (int i = 1; i < kStartGrid; ++i)
        for (int j = 1; i + j < kStartGrid; ++j)
          if (3 * i != kStartGrid || 3 * j != kStartGrid)
            starts_.push_back((i * pa + j * pb + (kStartGrid - i - j) * pc) / static_cast<double>(kStartGrid));
      const std::vector<std::optional<Vec3>> points = starts_;
      for (const auto& start : points) {
        if (!start) continue;
        Vec3 p = *start;
        if (!search_point(t, *facet, face, p)) continue;
        // The cavity of the point found, prepared again for the insertion.
        double margin = 0.0;
        bool acceptable = false;
        const bool admitted = admissible(t, *facet, face, p, margin, acceptable);
        DELMESH_CHECK(admitted && acceptable && margin > 0.0, "subfacet insertion: the point found no longer gains");
        commit(*facet, face, p);
        return true;
      }
    }
    return false;
  }

  /// Moves p within the facet's plane to raise the margin of admissible (compass search
  /// from p: kSearchDirections directions, the step halved where none gains, at most
  /// kSearchEvaluations evaluations). True when a point met is acceptable with a positive
  /// margin; p is then the one of them with the largest margin.
  bool search_point(std::uint32_t t, std::uint32_t facet_id, const std::array<std::uint32_t, 3>& face, Vec3& p) {
    double current = 0.0;
    bool acceptable = false;
    if (!admissible(t, facet_id, face, p, current, acceptable)) return false;
    double best = acceptable ? current : 0.0;
    Vec3 found = p;
    const Vec3 pa = mesh_.point(face[0]), pb = mesh_.point(face[1]), pc = mesh_.point(face[2]);
    const Vec3 n = state_.facets[facet_id]->normal().normalized();
    const Vec3 u = (pb - pa - (pb - pa).dot(n) * n).normalized();
    const Vec3 w = n.cross(u);
    double step = 0.25 * std::min({(pb - pa).norm(), (pc - pb).norm(), (pa - pc).norm()});
    int evaluations = 1, halvings = 0;
    while (u.allFinite() && w.allFinite() && step > 0.0 && evaluations < kSearchEvaluations &&
           halvings < kSearchHalvings) {
      bool moved = false;
      for (int k = 0; k < kSearchDirections && evaluations < kSearchEvaluations; ++k) {
        const double angle = 2.0 * std::numbers::pi * k / kSearchDirections;
        const Vec3 q = p + step * (std::cos(angle) * u + std::sin(angle) * w);
        double margin = 0.0;
        ++evaluations;
        if (!admissible(t, facet_id, face, q, margin, acceptable) || !(margin > current)) continue;
        current = margin;
        p = q;
        if (acceptable && margin > best) {
          best = margin;
          found = q;
        }
        moved = true;
        break;
      }
      if (!moved) {
        step *= 0.5;
        ++halvings;
      }
    }
    p = found;
    return best > 0.0;
  }

  /// The checks of subfacet_insertion.h for p, a point of `facet` near subfacet `face` of
  /// bad tet t, leaving the cavity of p prepared: false where the point cannot be
  /// inserted consistently (outside the facet's subfacets, the cavity not deleting t or
  /// not matching the facet's change, a subsegment deleted, encroachment, insertion
  /// radius, a new tet not positively oriented), else judge's margin and acceptable.
  bool admissible(std::uint32_t t, std::uint32_t facet_id, const std::array<std::uint32_t, 3>& face, const Vec3& p,
                  double& margin, bool& acceptable) {
    if (mesh_.num_vertices() >= state_.vertex_cap || !p.allFinite()) return false;
    const FacetTriangulation& facet = *state_.facets[facet_id];
    const auto located = facet.locate(p.data(), face[0]);
    if (!located) return false;
    const Subface& f = *located;
    for (int i = 0; i < 3; ++i)
      if (predicates::orient2d_projected(mesh_.coords(f[i]), mesh_.coords(f[(i + 1) % 3]), p.data(), facet.axis()) !=
          Sign::Positive)
        return false;
    if (!facet_flips(mesh_, facet, f, p, removals_, flips_)) return false;
    const std::vector<FaceKey>& removals = removals_;
    if (!prepare_insertion(state_, p, t, {facet_id, kNone})) return false;
    const Cavity& cavity = state_.cavity;
    cavity_tets_ = cavity.tets;
    std::sort(cavity_tets_.begin(), cavity_tets_.end());
    const auto in_cavity = [&](std::uint32_t u) { return std::binary_search(cavity_tets_.begin(), cavity_tets_.end(), u); };
    if (!in_cavity(t)) return false;
    // The boundary's edges, the deleted subfacets and the cavity's subsegments.
    boundary_edges_.clear();
    for (const CavityFace& cf : cavity.boundary)
      for (int i = 0; i < 3; ++i) boundary_edges_.push_back(edge_key(cf.v[i], cf.v[(i + 1) % 3]));
    std::sort(boundary_edges_.begin(), boundary_edges_.end());
    const auto on_boundary = [&](std::uint32_t x, std::uint32_t y) {
      return std::binary_search(boundary_edges_.begin(), boundary_edges_.end(), edge_key(x, y));
    };
    deleted_.clear();
    for (const std::uint32_t u : cavity.tets) {
      const auto& w = mesh_.tet(u).v;
      for (int g = 0; g < 4; ++g) {
        const auto& o = kFaceVertex[g];
        if (in_cavity(mesh_.neighbor(u, g)) && subface_of(state_, w[o[0]], w[o[1]], w[o[2]]))
          deleted_.push_back(sorted_face_key(w[o[0]], w[o[1]], w[o[2]]));
        for (int i = 0; i < 3; ++i) {
          const std::uint32_t x = w[o[i]], y = w[o[(i + 1) % 3]];
          if (subsegment_of(state_, x, y) && !on_boundary(x, y)) return false;
        }
      }
    }
    std::sort(deleted_.begin(), deleted_.end());
    deleted_.erase(std::unique(deleted_.begin(), deleted_.end()), deleted_.end());
    if (deleted_ != removals) return false;
    // The edges inside the removed region (in two of its subfacets) leave the facet
    // triangulation, so they must leave the mesh too: none on the cavity's boundary.
    removed_edges_.clear();
    for (const FaceKey& k : removals)
      for (int i = 0; i < 3; ++i) removed_edges_.push_back(edge_key(k[i], k[(i + 1) % 3]));
    std::sort(removed_edges_.begin(), removed_edges_.end());
    for (std::size_t i = 0; i + 1 < removed_edges_.size(); ++i)
      if (removed_edges_[i] == removed_edges_[i + 1] &&
          std::binary_search(boundary_edges_.begin(), boundary_edges_.end(), removed_edges_[i]))
        return false;
    cavity_encroached_subsegments(state_, p, ~std::uint64_t{0}, segments_);
    if (!segments_.empty()) return false;
    cavity_encroached_subfaces(state_, p, facet_id, kNone, faces_);
    if (!faces_.empty()) return false;
    double field = kInf;
    for (const std::uint32_t x : face) field = std::min(field, vertex_floor(state_, x));
    if (cavity_insertion_radius(state_, p) < field) return false;
    return judge(p, margin, acceptable);
  }

  /// Inserts p, admissible with its cavity prepared, into `facet` and the mesh: the
  /// facet's subfacet split without flips, the vertex with its cavity (commit_insertion),
  /// then the facet's flips that admissible checked (flips_), which leave the subfacets
  /// the cavity's boundary has.
  void commit(std::uint32_t facet_id, const std::array<std::uint32_t, 3>& face, const Vec3& p) {
    double floor = kInf;
    for (const std::uint32_t x : face) floor = std::min(floor, state_.vertices[x].floor);
    FacetTriangulation& facet = *state_.facets[facet_id];
    const std::uint32_t v = insert_facet_point(state_, facet_id, p, floor, face[0], false);
    DELMESH_CHECK(v != kNone, "subfacet insertion: the facet refused a point inside its subfacet");
    for (const auto& [x, y] : flips_) {
      auto flip = facet.flip_edge(x, y);
      DELMESH_CHECK(flip.has_value(), "subfacet insertion: a checked facet flip was refused");
      apply_subface_change(state_, facet_id, flip.value());
    }
    for (const FaceKey& k : deleted_)
      DELMESH_CHECK(!state_.subfaces.lookup(k), "subfacet insertion: a removed subfacet is still in the table");
  }

  /// The polish's judgement of the prepared cavity's new tets (see subfacet_insertion.h):
  /// false when a finite new tet is not positively oriented, else `margin` is the judged
  /// worst new tet less the worst old one and the least gain, and `acceptable` tells
  /// whether the rules other than the gain hold (counts outside the window, holds,
  /// radius-edge bound).
  bool judge(const Vec3& p, double& margin, bool& acceptable) {
    const Cavity& cavity = state_.cavity;
    const double bound = state_.options.max_radius_edge;
    double old_free = kInf, old_held = kInf, new_free = kInf, new_held = kInf;
    std::array<std::size_t, 2> old_bad{}, new_bad{};
    std::size_t old_breakers = 0, new_breakers = 0;
    for (const std::uint32_t u : cavity.tets) {
      if (!mesh_.is_finite(u) || !domain(u)) continue;
      const auto& w = mesh_.tet(u).v;
      const std::array<Vec3, 4> q{mesh_.point(w[0]), mesh_.point(w[1]), mesh_.point(w[2]), mesh_.point(w[3])};
      const bool held = touches_small(w);
      double& worst = held ? old_held : old_free;
      worst = std::min(worst, min_window_dihedral_sine(q[0], q[1], q[2], q[3], scale_));
      old_bad[held ? 1 : 0] += dihedral_outside(q[0], q[1], q[2], q[3], low_, high_) ? 1 : 0;
      old_breakers += radius_edge_ratio(q[0], q[1], q[2], q[3]) > bound ? 1 : 0;
    }
    for (const CavityFace& cf : cavity.boundary) {
      // The new tet: the cavity tet on this face with its opposite vertex replaced by p.
      const std::uint32_t inner_ref = mesh_.tet(cf.outside >> 2).adj[cf.outside & 3u];
      const std::uint32_t inner = inner_ref >> 2;
      std::array<std::uint32_t, 4> w = mesh_.tet(inner).v;
      const std::uint32_t replaced = inner_ref & 3u;
      bool infinite = false;
      for (std::uint32_t i = 0; i < 4; ++i) infinite = infinite || (i != replaced && w[i] == kInfiniteVertex);
      if (infinite) continue;  // a new hull face: by the cavity's exact visibility test
      std::array<Vec3, 4> q{mesh_.point(w[0]), mesh_.point(w[1]), mesh_.point(w[2]), mesh_.point(w[3])};
      q[replaced] = p;
      w[replaced] = kInfiniteVertex;  // the new vertex touches no small angle
      if (predicates::orient3d(q[0].data(), q[1].data(), q[2].data(), q[3].data()) != Sign::Positive) return false;
      if (!domain(inner)) continue;
      const bool held = touches_small(w);
      double& worst = held ? new_held : new_free;
      worst = std::min(worst, min_window_dihedral_sine(q[0], q[1], q[2], q[3], scale_));
      new_bad[held ? 1 : 0] += dihedral_outside(q[0], q[1], q[2], q[3], low_, high_) ? 1 : 0;
      new_breakers += radius_edge_ratio(q[0], q[1], q[2], q[3]) > bound ? 1 : 0;
    }
    // With holds (the worst cavity tet touches a small angle) the tets touching one are
    // constraints and the others the objective; else the worst of all is.
    const bool holds = old_held < old_free;
    margin = (holds ? new_free : std::min(new_free, new_held)) - old_free - kMinSubfacetInsertionGain;
    acceptable = new_bad[0] <= old_bad[0] && new_bad[1] <= old_bad[1] && new_breakers <= old_breakers &&
                 (!holds || new_held >= old_held);
    return true;
  }

  RefineState& state_;
  TetMesh& mesh_;
  const double low_, high_, scale_;
  const std::vector<std::uint8_t> small_;
  std::vector<std::uint32_t> cavity_tets_;
  std::vector<std::uint64_t> boundary_edges_;
  std::vector<FaceKey> deleted_;
  std::vector<std::uint64_t> segments_;
  std::vector<FaceKey> faces_;
  std::vector<std::uint64_t> removed_edges_;
  std::vector<FaceKey> removals_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> flips_;
  std::vector<std::optional<Vec3>> starts_;
};

}  // namespace

std::size_t insert_on_subfacets(RefineState& state) {
  // The insertion path queues the cavity's subsegments and subfacets that an apex
  // encroaches; the checks above keep the new vertex from encroaching any, and those
  // encroached before were left so by refinement's floors: nothing is queued for the
  // polish, which splits no boundary.
  const std::size_t segments = state.subsegment_queue.size(), faces = state.subface_queue.size();
  const std::size_t made = SubfacetInserter(state).run();
  state.subsegment_queue.resize(segments);
  state.subface_queue.resize(faces);
  return made;
}

}  // namespace delmesh::tet3d
