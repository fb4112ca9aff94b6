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

#include "refiners/tet3d/boundary_insertion.h"
#include "refiners/tet3d/boundary_split.h"
#include "toolkit/core/error.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/predicates/predicates.h"

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
/// strictly inside it (replay_facet_flips from f's edges): `removed` gets f and the
/// subfacets beyond the flipped edges, sorted, `flips` the flipped edges.
bool facet_flips(const TetMesh& mesh, const FacetTriangulation& facet, const Subface& f, const Vec3& p,
                 std::vector<FaceKey>& removed, std::vector<FacetFlip>& flips) {
  removed.assign(1, sorted_face_key(f[0], f[1], f[2]));
  if (!replay_facet_flips(mesh, facet, p, {{f[0], f[1]}, {f[1], f[2]}, {f[2], f[0]}}, removed, flips)) return false;
  std::sort(removed.begin(), removed.end());
  return true;
}

/// Judges and makes the insertions of insert_on_subfacets.
class SubfacetInserter : public BoundaryInserter {
 public:
  explicit SubfacetInserter(RefineState& state) : BoundaryInserter(state) {}

 private:
  /// Tries the subfacet faces of tet t, from the circumcenter, the centroid and the
  /// points of a grid in turn: the point is placed by search_point and inserted at the
  /// first that gains.
  bool try_tet(std::uint32_t t) override {
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
    const Vec3 n = state_.facets[facet_id].normal().normalized();
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
    const FacetTriangulation& facet = state_.facets[facet_id];
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
    return judge(p, kMinSubfacetInsertionGain, margin, acceptable);
  }

  /// Inserts p, admissible with its cavity prepared, into `facet` and the mesh: the
  /// facet's subfacet split without flips, the vertex with its cavity (commit_insertion),
  /// then the facet's flips that admissible checked (flips_), which leave the subfacets
  /// the cavity's boundary has.
  void commit(std::uint32_t facet_id, const std::array<std::uint32_t, 3>& face, const Vec3& p) {
    double floor = kInf;
    for (const std::uint32_t x : face) floor = std::min(floor, state_.vertices[x].floor);
    FacetTriangulation& facet = state_.facets[facet_id];
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

  std::vector<std::uint32_t> cavity_tets_;
  std::vector<std::uint64_t> boundary_edges_;
  std::vector<FaceKey> deleted_;
  std::vector<std::uint64_t> segments_;
  std::vector<FaceKey> faces_;
  std::vector<std::uint64_t> removed_edges_;
  std::vector<FaceKey> removals_;
  std::vector<FacetFlip> flips_;
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
