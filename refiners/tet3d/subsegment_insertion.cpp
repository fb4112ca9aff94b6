// Vertex insertion on a subsegment for the polish (see subsegment_insertion.h; notes
// §2.2.4, §4.2.1).
#include "refiners/tet3d/subsegment_insertion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "refiners/tet3d/boundary_insertion.h"
#include "refiners/tet3d/boundary_split.h"
#include "toolkit/core/error.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/predicates/predicates.h"

namespace delmesh::tet3d {

namespace {

/// The six edges of a tet by their vertex slots.
constexpr std::uint8_t kEdgeVertex[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
/// The line search of a new vertex's position along its subsegment
/// (SubsegmentInserter::search_point): the first step as a fraction of the subsegment,
/// most step halvings and most evaluations.
constexpr double kFirstStep = 0.125;
constexpr int kSearchHalvings = 6;
constexpr int kSearchEvaluations = 32;
/// The starting points besides refinement's split point: i / kStartGrid along the
/// subsegment, 0 < i < kStartGrid.
constexpr int kStartGrid = 6;

/// The subfacets of `facet` that the split of its segment edge (a, b) at p (on the edge)
/// removes, then the Lawson flips after it (replay_facet_flips from the edges opposite p).
/// `removed` gets the subfacets removed (appended), `flips` the flipped edges. False when
/// (a, b) is not an edge of the facet, when a triangle of the split is not strictly
/// counterclockwise in projection (exact orient2d_projected), or when a flip's
/// quadrilateral is not strictly convex.
bool segment_split_flips(const TetMesh& mesh, const FacetTriangulation& facet, std::uint32_t a, std::uint32_t b,
                         const Vec3& p, std::vector<FaceKey>& removed, std::vector<FacetFlip>& flips) {
  flips.clear();
  const Axis axis = facet.axis();
  std::vector<FacetFlip> edges;
  for (const auto& [x, y] : {FacetFlip{a, b}, FacetFlip{b, a}}) {
    // The subfacet (x, y, c), counterclockwise, becomes (x, p, c) and (p, y, c).
    const std::uint32_t c = facet.third_vertex(x, y);
    if (c == ~0u) continue;
    if (predicates::orient2d_projected(mesh.coords(x), p.data(), mesh.coords(c), axis) != Sign::Positive ||
        predicates::orient2d_projected(p.data(), mesh.coords(y), mesh.coords(c), axis) != Sign::Positive)
      return false;
    removed.push_back(sorted_face_key(x, y, c));
    edges.push_back({c, x});
    edges.push_back({y, c});
  }
  if (edges.empty()) return false;
  return replay_facet_flips(mesh, facet, p, std::move(edges), removed, flips);
}

/// Judges and makes the insertions of insert_on_subsegments.
class SubsegmentInserter : public BoundaryInserter {
 public:
  SubsegmentInserter(RefineState& state, SubsegmentJudgement judgement)
      : BoundaryInserter(state), judgement_(judgement) {}

 private:
  Vec3 along(std::uint32_t a, std::uint32_t b, double s) const {
    return mesh_.point(a) + s * (mesh_.point(b) - mesh_.point(a));
  }

  /// The subsegments that are edges of the tets around t's vertices, whose ends touch no
  /// small angle and whose segment crosses t's circumsphere (a point there has t in its
  /// cavity), each with the interval of its parameter inside the sphere (inexact: it
  /// only picks the starting points; the cavity is computed exactly). Sorted by edge key.
  void candidates(std::uint32_t t) {
    const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
    const auto center = tet_circumcenter(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), mesh_.point(v[3]));
    candidates_.clear();
    if (!center) return;
    const double radius2 = (mesh_.point(v[0]) - *center).squaredNorm();
    edges_.clear();
    for (const std::uint32_t x : v) {
      // The tets around x, by a search across their faces at x (each tet met once).
      star_.assign(1, mesh_.any_tet_of(x));
      for (std::size_t i = 0; i < star_.size(); ++i) {
        const std::uint32_t u = star_[i];
        const auto& w = mesh_.tet(u).v;
        for (int e = 0; e < 6; ++e) {
          const std::uint32_t a = w[kEdgeVertex[e][0]], b = w[kEdgeVertex[e][1]];
          if (a != kInfiniteVertex && b != kInfiniteVertex && subsegment_of(state_, a, b))
            edges_.push_back(edge_key(a, b));
        }
        for (int g = 0; g < 4; ++g) {
          if (w[g] == x) continue;  // the face opposite x does not hold x
          const std::uint32_t n = mesh_.neighbor(u, g);
          if (std::find(star_.begin(), star_.end(), n) == star_.end()) star_.push_back(n);
        }
      }
    }
    std::sort(edges_.begin(), edges_.end());
    edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
    for (const std::uint64_t key : edges_) {
      const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
      if (small(a) || small(b)) continue;
      // |a + s d - center|^2 < radius2: s between the roots of a quadratic.
      const Vec3 pa = mesh_.point(a), d = mesh_.point(b) - pa, m = pa - *center;
      const double qa = d.squaredNorm(), qb = m.dot(d), qc = m.squaredNorm() - radius2;
      const double disc = qb * qb - qa * qc;
      if (!(disc > 0.0) || !(qa > 0.0)) continue;
      const double root = std::sqrt(disc);
      const double lo = std::max(0.0, (-qb - root) / qa), hi = std::min(1.0, (-qb + root) / qa);
      if (lo < hi) candidates_.push_back({a, b, lo, hi});
    }
  }

  /// Tries the candidate subsegments of tet t, from refinement's split point (when inside
  /// t's circumsphere) and the points i / kStartGrid of the part inside the sphere in
  /// turn: the point is placed by search_point and inserted at the first that gains.
  bool try_tet(std::uint32_t t) override {
    candidates(t);
    for (const Candidate& c : candidates_) {
      const std::uint32_t a = c.a, b = c.b;
      const std::uint32_t seg = *subsegment_of(state_, a, b);
      const Vec3 pa = mesh_.point(a), d = mesh_.point(b) - pa;
      std::vector<double> starts;
      const double split = (subsegment_split_point(state_, a, b) - pa).dot(d) / d.squaredNorm();
      if (split > c.lo && split < c.hi) starts.push_back(split);
      for (int i = 1; i < kStartGrid; ++i) starts.push_back(c.lo + (c.hi - c.lo) * i / kStartGrid);
      for (double s : starts) {
        if (!(s > 0.0 && s < 1.0)) continue;
        if (!search_point(t, a, b, seg, s)) continue;
        // The cavity of the point found, prepared again for the insertion.
        double margin = 0.0;
        bool acceptable = false;
        const bool admitted = admissible(t, a, b, seg, along(a, b, s), margin, acceptable);
        DELMESH_CHECK(admitted && acceptable && margin > least_margin(),
                      "subsegment insertion: the point found no longer gains");
        commit(a, b, seg, along(a, b, s));
        return true;
      }
    }
    return false;
  }

  /// Moves the point at s along (a, b) to raise the margin of admissible (a line search
  /// from s, both directions, the step halved where neither gains, at most
  /// kSearchEvaluations evaluations). True when a point met is acceptable with a margin
  /// above least_margin(); s is then the one of them with the largest margin.
  bool search_point(std::uint32_t t, std::uint32_t a, std::uint32_t b, std::uint32_t seg, double& s) {
    double current = 0.0;
    bool acceptable = false;
    if (!admissible(t, a, b, seg, along(a, b, s), current, acceptable)) return false;
    double best = acceptable ? current : least_margin();
    double found = s;
    double step = kFirstStep;
    int evaluations = 1, halvings = 0;
    while (evaluations < kSearchEvaluations && halvings < kSearchHalvings) {
      bool moved = false;
      for (const double direction : {1.0, -1.0}) {
        const double q = s + direction * step;
        if (!(q > 0.0 && q < 1.0) || evaluations >= kSearchEvaluations) continue;
        double margin = 0.0;
        ++evaluations;
        if (!admissible(t, a, b, seg, along(a, b, q), margin, acceptable) || !(margin > current)) continue;
        current = margin;
        s = q;
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
    s = found;
    return best > least_margin();
  }

  /// The margin a point must pass: a gain at insertion, any consistent point when the
  /// judgement comes after the polish.
  double least_margin() const {
    return judgement_ == SubsegmentJudgement::AtInsertion ? 0.0 : -std::numeric_limits<double>::infinity();
  }

  /// The checks of subsegment_insertion.h for p, a point of subsegment (a, b) of segment
  /// seg, an edge of bad tet t, leaving the cavity of p prepared: false where the point
  /// cannot be inserted consistently (a facet's split or flips refused, the cavity not
  /// deleting t and the tets around (a, b) or not matching the facets' changes, another
  /// subsegment deleted, encroachment, insertion radius, a new tet not positively
  /// oriented), else judge's margin and acceptable.
  bool admissible(std::uint32_t t, std::uint32_t a, std::uint32_t b, std::uint32_t seg, const Vec3& p,
                  double& margin, bool& acceptable) {
    if (mesh_.num_vertices() >= state_.vertex_cap || !p.allFinite()) return false;
    if (below_split_resolution(state_, a, b, p)) return false;
    const SegmentFacetList& facets = state_.segments[seg].facets;
    removals_.clear();
    facet_removals_.resize(facets.size());
    flips_.resize(facets.size());
    for (std::size_t i = 0; i < facets.size(); ++i) {
      facet_removals_[i].clear();
      if (!segment_split_flips(mesh_, state_.facets[facets[i]], a, b, p, facet_removals_[i], flips_[i])) return false;
      removals_.insert(removals_.end(), facet_removals_[i].begin(), facet_removals_[i].end());
    }
    std::sort(removals_.begin(), removals_.end());
    if (std::adjacent_find(removals_.begin(), removals_.end()) != removals_.end()) return false;
    if (!prepare_insertion(state_, p, mesh_.any_tet_of(a), {kNone, seg})) return false;
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
    const auto on_boundary = [&](std::uint64_t key) {
      return std::binary_search(boundary_edges_.begin(), boundary_edges_.end(), key);
    };
    const std::uint64_t split = edge_key(a, b);
    // The split subsegment is an edge of the cavity's tets and not of its boundary: every
    // tet around it goes.
    if (on_boundary(split)) return false;
    bool holds_split = false;
    deleted_.clear();
    for (const std::uint32_t u : cavity.tets) {
      const auto& w = mesh_.tet(u).v;
      for (int g = 0; g < 4; ++g) {
        const auto& o = kFaceVertex[g];
        if (in_cavity(mesh_.neighbor(u, g)) && subface_of(state_, w[o[0]], w[o[1]], w[o[2]]))
          deleted_.push_back(sorted_face_key(w[o[0]], w[o[1]], w[o[2]]));
        for (int i = 0; i < 3; ++i) {
          const std::uint32_t x = w[o[i]], y = w[o[(i + 1) % 3]];
          if (edge_key(x, y) == split) {
            holds_split = true;
            continue;
          }
          if (subsegment_of(state_, x, y) && !on_boundary(edge_key(x, y))) return false;
        }
      }
    }
    if (!holds_split) return false;
    std::sort(deleted_.begin(), deleted_.end());
    deleted_.erase(std::unique(deleted_.begin(), deleted_.end()), deleted_.end());
    if (deleted_ != removals_) return false;
    // The edges inside a facet's removed region (in two of its removed subfacets, the
    // split subsegment aside) leave the facet triangulation, so they must leave the mesh
    // too: none on the cavity's boundary.
    for (const std::vector<FaceKey>& removed : facet_removals_) {
      removed_edges_.clear();
      for (const FaceKey& k : removed)
        for (int i = 0; i < 3; ++i) removed_edges_.push_back(edge_key(k[i], k[(i + 1) % 3]));
      std::sort(removed_edges_.begin(), removed_edges_.end());
      for (std::size_t i = 0; i + 1 < removed_edges_.size(); ++i)
        if (removed_edges_[i] == removed_edges_[i + 1] && removed_edges_[i] != split && on_boundary(removed_edges_[i]))
          return false;
    }
    cavity_encroached_subsegments(state_, p, split, segments_);
    if (!segments_.empty()) return false;
    cavity_encroached_subfaces(state_, p, kNone, seg, faces_);
    if (!faces_.empty()) return false;
    const double field = std::min(vertex_floor(state_, a), vertex_floor(state_, b));
    if (cavity_insertion_radius(state_, p) < field) return false;
    if (!judge(p, kMinSubsegmentInsertionGain, margin, acceptable)) return false;
    if (judgement_ == SubsegmentJudgement::AfterPolish) acceptable = true;
    return true;
  }

  /// Splits (a, b) at p, admissible with its cavity prepared: refinement's subsegment split
  /// without the facets' flips, then the flips admissible checked (flips_), which leave
  /// the subfacets the cavity's boundary has. The split is the polish's, not one of
  /// refinement's splits: its counters are left as they were.
  void commit(std::uint32_t a, std::uint32_t b, std::uint32_t seg, const Vec3& p) {
    const double floor = std::min(state_.vertices[a].floor, state_.vertices[b].floor);
    const SegmentSplitStats splits = state_.stage_segment_splits;
    const std::uint32_t v = split_subsegment(state_, a, b, p, floor, false);
    state_.stage_segment_splits = splits;
    DELMESH_CHECK(v != kNone, "subsegment insertion: the split of a checked point was refused");
    const SegmentFacetList& facets = state_.segments[seg].facets;
    for (std::size_t i = 0; i < facets.size(); ++i) {
      FacetTriangulation& facet = state_.facets[facets[i]];
      for (const auto& [x, y] : flips_[i]) {
        auto flip = facet.flip_edge(x, y);
        DELMESH_CHECK(flip.has_value(), "subsegment insertion: a checked facet flip was refused");
        apply_subface_change(state_, facets[i], flip.value());
      }
    }
    for (const FaceKey& k : deleted_)
      DELMESH_CHECK(!state_.subfaces.lookup(k), "subsegment insertion: a removed subfacet is still in the table");
  }

  const SubsegmentJudgement judgement_;
  std::vector<std::uint32_t> cavity_tets_;
  std::vector<std::uint64_t> boundary_edges_;
  std::vector<FaceKey> deleted_;
  std::vector<std::uint64_t> segments_;
  std::vector<FaceKey> faces_;
  std::vector<std::uint64_t> removed_edges_;
  std::vector<FaceKey> removals_;
  std::vector<std::vector<FaceKey>> facet_removals_;
  std::vector<std::vector<FacetFlip>> flips_;
  struct Candidate {
    std::uint32_t a, b;
    double lo, hi;
  };
  std::vector<Candidate> candidates_;
  std::vector<std::uint64_t> edges_;
  std::vector<std::uint32_t> star_;
};

}  // namespace

std::size_t insert_on_subsegments(RefineState& state, SubsegmentJudgement judgement,
                                  std::vector<std::array<std::uint32_t, 4>>* bad_tets, std::size_t only) {
  // The split queues the new subsegments and the subfacets its cavity touches; the checks
  // above keep the new vertex from encroaching any, and those encroached before were left
  // so by refinement's floors: nothing is queued for the polish, which splits no boundary.
  const std::size_t segments = state.subsegment_queue.size(), faces = state.subface_queue.size();
  SubsegmentInserter inserter(state, judgement);
  const std::size_t made = inserter.run(only);
  if (bad_tets) *bad_tets = inserter.bad_tets();
  state.subsegment_queue.resize(segments);
  state.subface_queue.resize(faces);
  return made;
}

}  // namespace delmesh::tet3d
