// Quality refinement with rejection rules and termination floors (see
// quality_refinement.h; notes §4.2.1, §4.2.3, §3.8).
#include "refiners/tet3d/quality_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "refiners/tet3d/angle_bearing.h"
#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/domain_marking.h"
#include "refiners/tet3d/interior_strategy.h"
#include "refiners/tet3d/quality_bound.h"
#include "refiners/tet3d/refinement_queue.h"
#include "refiners/tet3d/sliver_improvement.h"
#include "refiners/tet3d/volume_bound.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"
#include "toolkit/tetmesh/tet_insert.h"
#include "toolkit/tetmesh/tet_locate.h"

namespace delmesh::tet3d {

namespace {

/// Candidates drawn for one off-center before falling back to the circumcenter.
constexpr int kOffCenterTries = 8;
/// Points tried between a refused circumcenter and the tet's centroid, each of its
/// vertices, and each of the points of its circumsphere in kSphereDirections (split_inside).
constexpr int kInsideTries = 3;
/// Directions from a refused circumcenter to the further points of the circumsphere that
/// split_inside aims at: the 26 neighbours of a cube's centre (faces, edges, corners).
constexpr int kSphereDirections = 26;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Badness {
  bool skinny = false;
  bool too_big = false;
  /// Bad only by its dihedral angles (notes §4.4).
  bool sliver = false;
  double ratio = 0.0;
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
  /// The circumcenter is not representable (a nearly flat tet): the worst ratio of all.
  bool no_circumcenter = false;
};

/// The tet's badness against radius-edge bound `radius_edge`.
Badness badness(const RefineState& state, std::uint32_t t, double radius_edge) {
  Badness b;
  const auto& v = state.mesh.tet(t).v;
  const Vec3& p0 = state.mesh.point(v[0]);
  const Vec3& p1 = state.mesh.point(v[1]);
  const Vec3& p2 = state.mesh.point(v[2]);
  const Vec3& p3 = state.mesh.point(v[3]);
  const auto c = tet_circumcenter(p0, p1, p2, p3);
  if (!c) {
    b.no_circumcenter = true;
    return b;
  }
  b.center = *c;
  b.radius = (*c - p0).norm();
  const double lmin2 = std::min({(p0 - p1).squaredNorm(), (p0 - p2).squaredNorm(), (p0 - p3).squaredNorm(),
                                 (p1 - p2).squaredNorm(), (p1 - p3).squaredNorm(), (p2 - p3).squaredNorm()});
  b.ratio = b.radius / std::sqrt(lmin2);
  if (state.options.quality && b.ratio > radius_edge) {
    b.skinny = true;
  } else if (dihedral_outside(p0, p1, p2, p3, state.options.min_dihedral_deg, state.options.max_dihedral_deg)) {
    // Split like skinny tets; keyed by their radius-edge ratio, below the bound, they
    // come after the skinny ones (notes §4.4).
    b.skinny = b.sliver = true;
  }
  if (any_volume_bound(state)) {
    const double bound = max_volume_at(state, state.tet_region[t], b.center);
    if (bound > 0.0) {
      const double vol = std::abs((p1 - p0).dot((p2 - p0).cross(p3 - p0))) / 6.0;
      b.too_big = vol > bound;
    }
  }
  return b;
}

class QualityRefiner {
 public:
  QualityRefiner(RefineState& state, std::size_t input_vertices) : state_(state), input_vertices_(input_vertices) {
    box_lo_ = box_hi_ = state.plc.points.front();
    for (const Vec3& p : state.plc.points) {
      box_lo_ = box_lo_.cwiseMin(p);
      box_hi_ = box_hi_.cwiseMax(p);
    }
  }

  Expected<QualityOutcome> run() {
    QualityOutcome outcome;
    state_.collect_new_tets = true;
    for (std::uint32_t t = 0; t < state_.mesh.tet_slots(); ++t) consider(t);
    const std::size_t bound = quality_steiner_bound(state_);
    while (!queue_.empty()) {
      if (budget_spent()) {
        outcome.budget_exhausted = true;
        break;
      }
      if (state_.stage_steiner >= bound) {
        outcome.budget_exhausted = outcome.bound_reached = true;
        break;
      }
      const QueuedTet e = queue_.pop();
      state_.tet_queue_size = queue_.size();
      if (state_.mesh.is_dead(e.tet) || state_.mesh.tet(e.tet).v != e.v) continue;
      marks_kept_ = false;
      auto step = split_tet(e.tet);
      if (!step) return step.error();
      if (!marks_kept_) remark_new_tets(state_, state_.new_tets);
      state_.new_tets.swap(fresh_);
      state_.new_tets.clear();
      for (const std::uint32_t t : fresh_) consider(t);
      fresh_.clear();
      const TetMesh& mesh = state_.mesh;
      queue_.drop_stale([&](const QueuedTet& q) { return mesh.is_dead(q.tet) || mesh.tet(q.tet).v != q.v; });
    }
    state_.collect_new_tets = false;
    return outcome;
  }

 private:
  bool budget_spent() const {
    const long long budget = state_.options.max_steiner_points;
    if (budget < 0) return false;
    return static_cast<long long>(state_.mesh.num_vertices() - 1 - input_vertices_) >= budget;
  }

  void consider(std::uint32_t t) {
    if (t >= state_.mesh.tet_slots() || state_.mesh.is_dead(t) || state_.mesh.is_infinite(t)) return;
    if (!in_domain(state_.tet_region[t])) return;
    const Badness b = badness(state_, t, radius_edge_bound(state_, t));
    if (!b.skinny && !b.too_big) return;
    queue_.push({t, state_.mesh.tet(t).v}, b.skinny ? b.ratio : 0.0);
  }

  double tet_floor(std::uint32_t t) const {
    const auto& v = state_.mesh.tet(t).v;
    return std::min({vertex_floor(state_, v[0]), vertex_floor(state_, v[1]), vertex_floor(state_, v[2]),
                     vertex_floor(state_, v[3])});
  }

  /// Splits the given encroached subsegments if each midpoint respects the floor; true if
  /// they were split.
  Expected<bool> split_subsegments_for(const std::vector<std::uint64_t>& keys, double floor) {
    for (const std::uint64_t e : keys) {
      const std::uint32_t a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
      if (subsegment_split_radius(state_, a, b, subsegment_split_point(state_, a, b)) < floor) return false;
    }
    for (const std::uint64_t e : keys) {
      const std::uint32_t a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
      if (!state_.subsegments.count(edge_key(a, b))) continue;
      const Vec3 q = subsegment_split_point(state_, a, b);
      if (split_subsegment(state_, a, b, q, floor) == kNone) return false;
    }
    auto ok = restore_conformity(state_, false);
    if (!ok) return ok.error();
    return true;
  }

  Expected<void> split_tet(std::uint32_t t) {
    if (!in_domain(state_.tet_region[t])) return {};
    const double bound = radius_edge_bound(state_, t);
    const Badness b = badness(state_, t, bound);
    if (!b.skinny && !b.too_big) return {};
    // A skinny tet bearing a small input angle is left (angle_bearing.h, notes §3.8).
    if (!b.too_big && !b.sliver && bears_small_angle(state_, t, bound)) return {};
    const double floor = b.too_big ? 0.0 : tet_floor(t);
    if (b.radius < floor) return {};  // unmet: the floor forbids (counted at the end)
    const QueuedTet self{t, state_.mesh.tet(t).v};
    // A sliver whose circumcenter is rejected splits no subsegment or subfacet: on
    // faceted surfaces, creases near 180 degrees make boundary slivers whose
    // circumcenters lie outside, and splitting the boundary for them never ends. They
    // are left to the improvement pass (sliver_improvement.h).
    const bool sliver = b.sliver && !b.too_big;
    if (sliver && !take_sliver_split(state_)) return {};
    // The point to insert: the circumcenter, or for a sliver with off-centers on, Chew's
    // random point of the inner half of the circumsphere (circumcenter if none is found).
    Vec3 point = b.center;
    if (sliver && state_.options.sliver_off_centers) {
      if (const auto q = off_center(t, b)) point = *q;
    }
    bool outside = !inside_box(point);
    if (!outside) {
      const Location at = locate(state_.mesh, point.data(), t, rng_);
      outside = state_.mesh.is_infinite(at.tet) || state_.tet_region[at.tet] != state_.tet_region[t];
    }
    if (outside) {
      if (sliver) return {};
      return split_for_outside(t, b, point, floor, self);
    }
    if (!prepare_insertion(state_, point, t)) return {};
    if (state_.constrained && !cavity_holds(t)) {
      // Constrained: the point is not visible from the tet (a subfacet between, notes
      // §2.1.7); handled as a point outside the tet's region.
      if (sliver) return {};
      return split_for_outside(t, b, point, floor, self);
    }
    cavity_encroached_subsegments(state_, point, ~std::uint64_t{0}, segs_);
    if (!segs_.empty() && sliver) return {};
    if (!segs_.empty()) {
      auto split = split_subsegments_for(segs_, floor);
      if (!split) return split.error();
      if (*split) requeue(self);
      return {};
    }
    cavity_encroached_subfaces(state_, point, kNone, kNone, faces_);
    if (!faces_.empty() && sliver) return {};
    if (!faces_.empty()) {
      const std::size_t steiner = state_.stage_steiner;
      const FaceKey encroached = faces_.front();
      auto split = split_subface_for(encroached, point, floor, self);
      if (!split || state_.stage_steiner != steiner || state_.mesh.is_dead(t) || state_.mesh.tet(t).v != self.v)
        return split;
      // Nothing was split on the subfacet's behalf (the floor refused it: the subfacet's
      // circumcenter too close to a vertex, or encroaching a subsegment too short to
      // split): the circumcenter itself is inserted when it lies at least the floor off
      // the subfacet's plane (a thinner tet on the subfacet could not be repaired, its
      // splits being below the floor) and its cavity deletes no subfacet. It encroaches no
      // subsegment (checked above), so it deletes none; the encroached subfacet stays, as
      // the floors leave others; and its insertion radius, the circumradius, is at least
      // the floor, so the packing argument covers it. Else another point (split_inside).
      if (height_over(encroached, point) < floor) return split_inside(t, b, floor);
      if (!prepare_insertion(state_, point, t) || cavity_deletes_subface(state_)) return split_inside(t, b, floor);
    }
    // With every subfacet unencroached a circumcenter outside the tet's region always
    // encroaches one (§4.2.1); subfacets left encroached by the floors void that
    // argument, so the location is checked directly and such a tet is split at another
    // point (split_inside) or left unmet.
    const std::uint32_t at = state_.cavity.location.tet;
    if (state_.mesh.is_infinite(at) || state_.tet_region[at] != state_.tet_region[t]) return split_inside(t, b, floor);
    // The circumradius is the insertion radius only while t's circumsphere holds no vertex.
    // One that held one was seen on cgal-couplingdown.off (circumradius 0.0020, a cavity
    // vertex 0.00072 from the circumcenter, floor 0.00153; why that sphere was not empty
    // was not traced): the edge it made left 3 tets above 1.414 away from small angles,
    // their four vertices interior and their circumradii under the floor. The insertion
    // radius is checked against the floor, as for every other point (split_inside when
    // it is under it), so the packing argument needs no empty circumsphere.
    if (cavity_insertion_radius(state_, point) < floor) return split_inside(t, b, floor);
    VertexInfo info;
    info.kind = VertexKind::Interior;
    info.floor = floor;
    // A cavity with no subfacet between two of its tets lies in one region (the marks
    // are exact: nothing separates its tets; subfacets on its boundary stay, and no new
    // face through the interior vertex is one), so commit_insertion's marks, taken from
    // the cavity tets, are the ones remark_new_tets would flood; they stay right unless
    // conformity restoration inserts more or changes the subfacets. Infinite tets in
    // the cavity are left to remark_new_tets (the convex hull's finite neighbours may be
    // region -1).
    const bool plain = !cavity_deletes_subface(state_) && !cavity_has_infinite_tet();
    commit_insertion(state_, point, info);
    const std::size_t steiner = state_.stage_steiner;
    const std::uint64_t subfaces_version = state_.subfaces.version();
    auto ok = restore_conformity(state_, false);
    if (!ok) return ok.error();
    marks_kept_ = plain && state_.stage_steiner == steiner && state_.subfaces.version() == subfaces_version;
    return {};
  }

  /// The circumcenter `point` of tet t lies outside t's region (or, constrained, is not
  /// visible from t): split a subfacet of t for it, or leave t.
  Expected<void> split_for_outside(std::uint32_t t, const Badness& b, const Vec3& point, double floor,
                                   const QueuedTet& self) {
    // Outside the tet's region (a boundary sliver; the walk is cheap, the cavity of a
    // far point is not). Split a subfacet among its faces that the point encroaches (if
    // any, subject to the floor). A subfacet the point does not encroach is not split
    // for it (§4.2.1 splits only encroached subfacets) unless the split deletes the tet
    // (below): splitting one that leaves the tet as it is would, requeued, split the
    // facet under its circumcenter again and again down to the floor.
    const auto& v = state_.mesh.tet(t).v;
    for (int f = 0; f < 4; ++f) {
      const auto& o = kFaceVertex[f];
      const FaceKey key = face_key(v[o[0]], v[o[1]], v[o[2]]);
      if (state_.subfaces.count(key) && encroaches(key, point)) return split_subface_or_inside(t, b, key, point, floor, self);
    }
    // None encroached: a nearly flat tet on a facet, its four vertices on the facet's
    // boundary (a cylinder cap's cocircular vertices), its circumcenter far off the
    // facet. A subfacet face whose circumcenter lies in the tet's circumsphere is split
    // (floored): the insertion deletes the tet.
    for (int f = 0; f < 4; ++f) {
      const auto& o = kFaceVertex[f];
      const FaceKey face = face_key(v[o[0]], v[o[1]], v[o[2]]);
      if (!state_.subfaces.count(face)) continue;
      const auto cc = triangle_circumcenter(state_.mesh.point(face[0]), state_.mesh.point(face[1]),
                                            state_.mesh.point(face[2]));
      if (cc && in_circumsphere(t, *cc)) return split_subface_or_inside(t, b, face, *cc, floor, self);
    }
    return split_inside(t, b, floor);
  }

  /// split_subface_for, and split_inside when it split nothing and t is still there.
  Expected<void> split_subface_or_inside(std::uint32_t t, const Badness& b, const FaceKey& face, const Vec3& c,
                                         double floor, const QueuedTet& self) {
    const std::size_t steiner = state_.stage_steiner;
    auto split = split_subface_for(face, c, floor, self);
    if (!split || state_.stage_steiner != steiner || state_.mesh.is_dead(t) || state_.mesh.tet(t).v != self.v)
      return split;
    return split_inside(t, b, floor);
  }

  /// Tet t's circumcenter was refused and nothing was split for it (it lies outside t's
  /// region, or within a floor of the plane of a subfacet it encroaches whose own split the
  /// floors refused): another point of t's circumsphere is inserted instead, the first of
  /// kInsideTries points on each segment from the circumcenter to t's centroid, then to each
  /// of t's vertices, then to the points of the sphere in the kSphereDirections directions
  /// (inside the circumsphere, so the insertion deletes t; toward a vertex reaches the tets
  /// whose centroid lies as near the boundary as their circumcenter, e.g. three vertices on
  /// segments and an interior apex; the fixed directions reach those whose only points at
  /// least a floor from their vertices and off the subfacet's plane lie aside of all five,
  /// tets with a circumradius of 1.4-1.6 floors at subsegments too short to split: occt-sh2
  /// left 9 such above 1.414 away from small angles, 1 with them) that lies in t's region, encroaches no
  /// subsegment, lies at least the floor off the plane of every subfacet it encroaches,
  /// deletes no subfacet, and has an insertion radius of at least the floor. It is the
  /// circumcenter's rule of split_tet with the circumcenter moved inside: nothing on the
  /// boundary is deleted or split, and its insertion radius is at least the floor, so the
  /// packing argument of the termination floors covers it (notes §3.8; Üngör's off-centers
  /// likewise move the point from the circumcenter toward the tet). When no point qualifies,
  /// the subsegments encroached by the first one that met every condition before that are
  /// split, floor permitting (split_subsegments_for), and t is looked at afresh: tets with
  /// three vertices on segments and an interior apex whose circumcenter lies outside their
  /// region with none of their subfacet faces encroached (cgal-homer 2, cgal-anchor 1 left
  /// above 1.414 away from small angles without it, none with it).
  Expected<void> split_inside(std::uint32_t t, const Badness& b, double floor) {
    // Floorless volume refinement keeps to the circumcenter's rules; a sliver whose
    // circumcenter is rejected is left to the improvement pass (split_tet).
    if (b.too_big || b.sliver) return {};
    const auto v = state_.mesh.tet(t).v;
    std::array<Vec3, 5 + kSphereDirections> toward;
    toward[0] = (state_.mesh.point(v[0]) + state_.mesh.point(v[1]) + state_.mesh.point(v[2]) +
                 state_.mesh.point(v[3])) /
                4.0;
    for (int i = 0; i < 4; ++i) toward[i + 1] = state_.mesh.point(v[i]);
    std::size_t k = 5;
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z)
          if (x != 0 || y != 0 || z != 0) toward[k++] = b.center + b.radius * Vec3(x, y, z).normalized();
    // The subsegments encroached by the first point that met every condition before them.
    std::vector<std::uint64_t> encroached;
    for (std::size_t n = 0; n < toward.size() * kInsideTries; ++n) {
      const double fraction = static_cast<double>(n % kInsideTries + 1) / (kInsideTries + 1);
      const Vec3 q = b.center + fraction * (toward[n / kInsideTries] - b.center);
      // Necessary conditions first, without the cavity: t's vertices and subfacet faces
      // belong to the cavity (it holds t), q lies in t's region, and on a CCDT the faces
      // of t that do not see q can be crossed (star_may_keep; a point it refuses still
      // advances the location walk as its preparation would, pass_over_insertion).
      if (!inside_box(q) || !clear_of_tet(t, q, floor)) continue;
      const Location where = locate(state_.mesh, q.data(), t, rng_);
      if (state_.mesh.is_infinite(where.tet) || state_.tet_region[where.tet] != state_.tet_region[t]) continue;
      if (state_.constrained && !star_may_keep(t, q)) {
        pass_over_insertion(state_, q, t);
        continue;
      }
      if (!prepare_insertion(state_, q, t) || !cavity_holds(t)) continue;
      const std::uint32_t at = state_.cavity.location.tet;
      if (state_.mesh.is_infinite(at) || state_.tet_region[at] != state_.tet_region[t]) continue;
      if (cavity_deletes_subface(state_) || cavity_insertion_radius(state_, q) < floor) continue;
      cavity_encroached_subsegments(state_, q, ~std::uint64_t{0}, segs_);
      if (!segs_.empty()) {
        if (encroached.empty()) encroached = segs_;
        continue;
      }
      cavity_encroached_subfaces(state_, q, kNone, kNone, faces_);
      if (std::any_of(faces_.begin(), faces_.end(), [&](const FaceKey& f) { return height_over(f, q) < floor; }))
        continue;
      VertexInfo info;
      info.kind = VertexKind::Interior;
      info.floor = floor;
      commit_insertion(state_, q, info);
      auto ok = restore_conformity(state_, false);
      if (!ok) return ok.error();
      return {};
    }
    // No point qualified, but one in t's region, clear of its vertices and deleting no
    // subfacet encroached subsegments: they are split, floor permitting (§4.2.1 rejects such
    // a point and splits them; the circumcenter's rule), and t is looked at afresh.
    if (!encroached.empty()) return split_subsegments_then_requeue(encroached, floor, QueuedTet{t, v});
    return {};
  }

  /// Is q at least `floor` from each vertex of t and, for each subfacet face of t that q
  /// encroaches, at least `floor` off its plane?
  bool clear_of_tet(std::uint32_t t, const Vec3& q, double floor) const {
    const auto& v = state_.mesh.tet(t).v;
    for (int i = 0; i < 4; ++i)
      if ((state_.mesh.point(v[i]) - q).norm() < floor) return false;
    for (int f = 0; f < 4; ++f) {
      const auto& o = kFaceVertex[f];
      const FaceKey face = face_key(v[o[0]], v[o[1]], v[o[2]]);
      if (state_.subfaces.count(face) && encroaches(face, q) && height_over(face, q) < floor) return false;
    }
    return true;
  }

  /// Can the cavity of q that prepare_insertion computes on a CCDT (state.constrained)
  /// hold tet t and delete no subfacet, as split_inside requires? A necessary condition,
  /// exact and local. That cavity is shrunk to a star of q, whose boundary faces all see
  /// q (q strictly on the cavity's side). So a face of t that does not see q is inside
  /// such a cavity: it is no subfacet (the cavity would delete it), and the tet beyond
  /// it is in the cavity too, hence in conflict with q (tet_in_conflict, the search's own
  /// rule with q's perturbation id; a tet holding q is in conflict). On pocc-io1 it
  /// refused 3668 of the 4270 candidates of split_inside whose cavity did not hold t, and
  /// none whose cavity did.
  bool star_may_keep(std::uint32_t t, const Vec3& q) const {
    const TetMesh& mesh = state_.mesh;
    const auto& v = mesh.tet(t).v;
    const auto q_id = static_cast<std::uint32_t>(mesh.num_vertices());
    for (int f = 0; f < 4; ++f) {
      const auto& o = kFaceVertex[f];
      if (predicates::orient3d(mesh.coords(v[o[0]]), mesh.coords(v[o[1]]), mesh.coords(v[o[2]]), q.data()) ==
          Sign::Positive)
        continue;
      if (state_.subfaces.count(face_key(v[o[0]], v[o[1]], v[o[2]]))) return false;
      if (!tet_in_conflict(mesh, mesh.neighbor(t, f), q.data(), q_id)) return false;
    }
    return true;
  }

  bool cavity_holds(std::uint32_t t) const {
    return std::find(state_.cavity.tets.begin(), state_.cavity.tets.end(), t) != state_.cavity.tets.end();
  }

  bool cavity_has_infinite_tet() const {
    for (const std::uint32_t c : state_.cavity.tets)
      if (state_.mesh.is_infinite(c)) return true;
    return false;
  }

  /// A number in [-1, 1) from the off-center generator (splitmix64, seeded by the options'
  /// seed: the same seed gives the same points).
  double uniform() {
    std::uint64_t z = (offcenter_rng_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;
  }

  /// Chew's off-center for sliver t (notes §4.4): random points of the ball of half the
  /// circumradius around the circumcenter, at most kOffCenterTries of them; the first
  /// that lies in no face's disallowed region (off_center_disallowed) is returned.
  std::optional<Vec3> off_center(std::uint32_t t, const Badness& b) {
    for (int k = 0; k < kOffCenterTries; ++k) {
      Vec3 u = Vec3::Zero();
      for (int draw = 0; draw < 64; ++draw) {  // uniform in the unit ball, by rejection
        u = Vec3(uniform(), uniform(), uniform());
        if (u.squaredNorm() <= 1.0) break;
      }
      const Vec3 q = b.center + 0.5 * b.radius * u;
      if (!inside_box(q) || !prepare_insertion(state_, q, t)) continue;
      if (!off_center_disallowed(q)) return q;
    }
    return std::nullopt;
  }

  /// Does q (its cavity prepared) lie in the disallowed region of a cavity boundary face:
  /// would q and the face make an in-domain tet outside the dihedral window whose
  /// radius-edge ratio meets the bound (a sliver radius-edge refinement keeps)?
  bool off_center_disallowed(const Vec3& q) const {
    const TetMesh& mesh = state_.mesh;
    const double bound = state_.options.quality ? state_.options.max_radius_edge : kInfinity;
    for (const CavityFace& f : state_.cavity.boundary) {
      if (f.v[0] == kInfiniteVertex || f.v[1] == kInfiniteVertex || f.v[2] == kInfiniteVertex) continue;
      const std::uint32_t out_tet = f.outside >> 2;
      const std::uint32_t inner = mesh.tet(out_tet).adj[f.outside & 3u] >> 2;
      if (inner >= state_.tet_region.size() || !in_domain(state_.tet_region[inner])) continue;
      const Vec3 &a = mesh.point(f.v[0]), &c = mesh.point(f.v[1]), &d = mesh.point(f.v[2]);
      if (dihedral_outside(a, c, d, q, state_.options.min_dihedral_deg, state_.options.max_dihedral_deg) &&
          radius_edge_ratio(a, c, d, q) <= bound)
        return true;
    }
    return false;
  }

  /// Does p lie strictly inside the circumsphere of tet t (exact insphere; the mesh's
  /// tets are positively oriented, so inside is Positive)?
  bool in_circumsphere(std::uint32_t t, const Vec3& p) const {
    const TetMesh& mesh = state_.mesh;
    const auto& v = mesh.tet(t).v;
    return predicates::insphere(mesh.coords(v[0]), mesh.coords(v[1]), mesh.coords(v[2]), mesh.coords(v[3]),
                                p.data()) == Sign::Positive;
  }

  /// Distance from p to the plane of subfacet f.
  double height_over(const FaceKey& f, const Vec3& p) const {
    const Vec3& a = state_.mesh.point(f[0]);
    const Vec3 n = (state_.mesh.point(f[1]) - a).cross(state_.mesh.point(f[2]) - a);
    return std::abs(n.dot(p - a)) / n.norm();
  }

  Expected<void> split_subface_for(const FaceKey& encroached, const Vec3& c, double floor, const QueuedTet& self) {
    const auto it = state_.subfaces.find(encroached);
    if (it == state_.subfaces.end()) return {};
    const std::uint32_t facet = it->second;
    FaceKey target = encroached;
    const auto below = subface_below(state_, facet, encroached[0], c);
    if (!below) {
      // c projects outside the facet (notes §4.2.3, Projection Lemma): the subsegment
      // between is split instead if c encroaches it, floor permitting. The lemma promises
      // that it does only while the facet's subsegments are all unencroached, which the
      // floors do not keep; when it does not, the encroached subfacet itself is split
      // below (floored), as for a point whose prism subfacet it does not encroach.
      const auto seg = subsegment_toward(state_, facet, encroached, c);
      if (seg) {
        const std::uint32_t a = static_cast<std::uint32_t>(*seg >> 32), b = static_cast<std::uint32_t>(*seg);
        if (predicates::dot3d(state_.mesh.coords(a), state_.mesh.coords(b), c.data()) != Sign::Positive)
          return split_subsegments_then_requeue({*seg}, floor, self);
      }
    }
    // The Projection Lemma's subfacet (the one whose prism holds c) when c encroaches it;
    // else c encroaches a subsegment of the facet (Lemma 26) outside the cavity, and the
    // encroached subfacet itself is split.
    if (below && state_.subfaces.count(*below) && encroaches(*below, c)) target = *below;
    const auto center =
        triangle_circumcenter(state_.mesh.point(target[0]), state_.mesh.point(target[1]), state_.mesh.point(target[2]));
    if (!center) return {};
    if (!prepare_insertion(state_, *center, state_.mesh.any_tet_of(target[0]), {facet, kNone})) return {};
    cavity_encroached_subsegments(state_, *center, ~std::uint64_t{0}, segs_);
    if (!segs_.empty()) {
      auto split = split_subsegments_for(segs_, floor);
      if (!split) return split.error();
      if (*split) requeue(self);
      return {};
    }
    if (cavity_insertion_radius(state_, *center) < floor) return {};
    if (insert_facet_point(state_, facet, *center, floor, target[0]) == kNone) {
      // The circumcenter lies outside the facet: a vertex of the subfacet encroaches the
      // subsegment between (Lemma 17), which is split instead, above the floor.
      if (const auto seg = subsegment_toward(state_, facet, target, *center))
        return split_subsegments_then_requeue({*seg}, floor, self);
      // Otherwise the subfacet's centroid, under the same floor as every other vertex
      // (the termination argument of "Termination of quality refinement" counts on it).
      const Vec3 g = (state_.mesh.point(target[0]) + state_.mesh.point(target[1]) + state_.mesh.point(target[2])) / 3.0;
      if (!prepare_insertion(state_, g, state_.mesh.any_tet_of(target[0]), {facet, kNone})) return {};
      if (cavity_insertion_radius(state_, g) < floor) return {};
      if (insert_facet_point(state_, facet, g, floor, target[0]) == kNone) return {};
    }
    auto ok = restore_conformity(state_, false);
    if (!ok) return ok.error();
    requeue(self);
    return {};
  }

  Expected<void> split_subsegments_then_requeue(const std::vector<std::uint64_t>& keys, double floor,
                                                const QueuedTet& self) {
    auto split = split_subsegments_for(keys, floor);
    if (!split) return split.error();
    if (*split) requeue(self);
    return {};
  }

  void requeue(const QueuedTet& self) {
    if (!state_.mesh.is_dead(self.tet) && state_.mesh.tet(self.tet).v == self.v) consider(self.tet);
  }

  /// p inside or on the equatorial sphere of subfacet f.
  bool encroaches(const FaceKey& f, const Vec3& p) const {
    const TetMesh& mesh = state_.mesh;
    return predicates::in_equatorial_sphere(mesh.coords(f[0]), mesh.coords(f[1]), mesh.coords(f[2]), p.data()) !=
           Sign::Negative;
  }

  bool inside_box(const Vec3& p) const {
    return (p.array() >= box_lo_.array()).all() && (p.array() <= box_hi_.array()).all();
  }

  RefineState& state_;
  std::size_t input_vertices_;
  Vec3 box_lo_, box_hi_;
  std::uint64_t rng_ = 0x9E3779B97F4A7C15ULL;
  std::uint64_t offcenter_rng_ = state_.options.seed ^ 0xD1B54A32D192ED03ULL;
  RefinementQueue queue_;
  /// Set by split_tet when the step's new tets already carry the marks remark_new_tets
  /// would give them (a single insertion whose cavity held no subfacet).
  bool marks_kept_ = false;
  std::vector<std::uint32_t> fresh_;
  std::vector<std::uint64_t> segs_;
  std::vector<FaceKey> faces_;
};

}  // namespace

double radius_edge_bound(const RefineState& state, std::uint32_t t) { return interior_strategy_bound(state, t); }

Expected<QualityOutcome> refine_quality(RefineState& state, std::size_t input_vertices) {
  QualityRefiner refiner(state, input_vertices);
  return refiner.run();
}

}  // namespace delmesh::tet3d
