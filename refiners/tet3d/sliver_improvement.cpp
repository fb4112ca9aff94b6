// Flips and smoothing for the worst dihedral angles (see sliver_improvement.h; notes
// §2.2.4).
#include "refiners/tet3d/sliver_improvement.h"

#include "refiners/tet3d/change_clock.h"
#include "refiners/tet3d/facet_edge_flip.h"
#include "refiners/tet3d/flip_trade.h"
#include "refiners/tet3d/improvement_schedule.h"
#include "refiners/tet3d/interior_strategy.h"
#include "refiners/tet3d/joint_move.h"
#include "refiners/tet3d/small_angles.h"
#include "refiners/tet3d/vertex_deletion.h"
#include "refiners/tet3d/volume_bound.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "toolkit/core/error.h"
#include "toolkit/geometry/circumcenter.h"
#include "toolkit/predicates/predicates.h"
#include "toolkit/quality/tet_quality.h"
#include "toolkit/tetmesh/tet_flips.h"

namespace delmesh::tet3d {

namespace {

constexpr int kSmoothIterations = 6;
constexpr int kLineSearchHalvings = 8;
/// Smallest gain in the worst sine for a flip, a vertex move, an insertion or a deletion
/// to be worth making (improvement_schedule.h: tiny moves only make work for the next
/// pass).
constexpr double kMinFlipGain = 1e-4;
/// Quality given to a tet with minimum dihedral sine s that breaks a radius-edge or
/// volume bound: kBoundPenalty + kBoundSlope s, in (-0.75, -0.5], below every tet that
/// keeps the bounds and above inverted ones (s - 1 <= -1). Bound breakers still rank by
/// their angles, so a tet the refinement's floors left skinny can be replaced by skinny
/// tets with better angles, never by one with worse.
constexpr double kBoundPenalty = -0.75;
constexpr double kBoundSlope = 0.25;

double penalized(double sine) { return kBoundPenalty + kBoundSlope * sine; }
/// Quality given to every flat, inverted or bound-breaking tet under
/// ImprovementTarget::strict_bounds: the least there is, so a step must remove them all
/// and make none to beat it.
constexpr double kStrictRefused = -2.0;
constexpr std::size_t kMaxRing = 12;
/// The polish (Improver::polish) smooths the vertices of the tets whose quality is within
/// this much of a bad tet's in the stars of its vertices (measured: 0.05, 0.1, 0.2, 0.4
/// and every tet of the stars left 170, 156, 141, 147 and 148 tets outside [20, 150] away
/// from small angles on seven corpus inputs).
constexpr double kPolishMargin = 0.2;
/// A trade (Improver::hold_for_trade) keeps every tet touching a small input angle in the
/// star at or above this share of the least window dihedral sine of those tets before it
/// (measured with [20, 150] on gmsh-netgen-hinge, cgal-boeing and cgal-anchor while the
/// trade rounds had a budget of their own, kPolishTriesPerBadTet per tet away from small
/// angles: 0.5 left 53, 60 and 105 tets outside the window away from small angles, 0.25
/// left 52, 58 and 109, none but the trades' extreme angles 52, 60 and 104: the share
/// costs little and keeps each holder at half its angle or better).
constexpr double kTradeFraction = 0.5;
/// Most ascents of a trade's move, each from the best point of the one before
/// (Improver::trade_move).
constexpr int kTradeAscents = 3;
/// Most tets a vertex insertion of the improvement pass may replace.
constexpr std::size_t kMaxCavity = 48;
/// Offsets of the starting points of a vertex insertion off a bad tet's flat direction,
/// in units of its longest edge (insertion_candidates).
constexpr double kInsertOffsets[] = {0.2, 0.4};
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The six edges of a tet as local vertex pairs, in the order of dihedral_angles_deg.
constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

enum class Freedom { Free, Plane, Line };

/// A hull face of a moving vertex and the apex of a neighbouring hull face, which must not
/// lie beyond it (orient3d of the face, vertices in the infinite tet's kFaceVertex order,
/// and the apex not positive).
struct HullCheck {
  std::array<std::uint32_t, 3> face;
  std::uint32_t apex;
};

/// How a star tet enters a smoothing move's objective (Improver::smooth_vertex).
enum class Hold : std::uint8_t {
  None,       ///< its quality counts towards the star's worst
  NotWorse,   ///< touches a small input angle, outside the window: may not fall below `least`
  InsideWindow,  ///< touches a small input angle, inside the window: must stay inside
  /// touches a small input angle, in a trade (Improver::hold_for_trade): may not fall below
  /// `least_sine` nor beyond the trade's extreme angles
  Traded
};

struct StarTet {
  std::uint32_t tet;
  int local;  ///< index of the moving vertex in the tet
  int region;
  std::array<Vec3, 4> p;
  Hold hold = Hold::None;
  double least = 0.0;  ///< for Hold::NotWorse: the worst quality of the held tets before the move
  /// For Hold::NotWorse: the least window dihedral sine of the held tets before the move
  /// (the quality ranks a tet breaking a bound below every other, whatever its angles).
  double least_sine = 0.0;
  /// Broke a radius-edge or volume bound before the move (a Hold::InsideWindow tet that
  /// did may go on breaking it; one that did not may not start).
  bool breaker = false;
};

class Improver {
 public:
  Improver(RefineState& state, const ImprovementTarget& target)
      : state_(state),
        mesh_(state.mesh),
        target_(target),
        low_(target.min_dihedral_deg),
        high_(target.max_dihedral_deg),
        obtuse_scale_(window_obtuse_scale(target.min_dihedral_deg, target.max_dihedral_deg)),
        radius_edge_bound_(strict_radius_edge_bound(state.options, target)),
        any_volume_bound_(any_volume_bound(state)),
        first_new_vertex_(state.mesh.num_vertices()),
        clock_(state.mesh.num_vertices()) {
    if (target.small_angle_holds) at_small_angle_ = small_angle_vertices(state);
  }

  ImprovementStats run() {
    ImprovementStats stats;
    collect_bad(bad_);  // the only scan of the whole mesh, or of target_.start_tets
    stats.bad_before = bad_.size();
    ImprovementSchedule schedule(bad_.size(), target_.max_passes, target_.tries_per_bad_tet);
    bool another = !bad_.empty();
    while (another) {
      ++stats.passes;
      const std::size_t bad_at_start = bad_.size();
      bool changed = false;
      // Every tet that may be bad after this pass is a tet bad before it, a tet made by a
      // flip, or a tet around a moved vertex: those are gathered in touched_.
      touched_ = bad_;
      // Flips, worklist seeded with the bad tets; the new tets that are still bad join it.
      work_ = bad_;
      std::reverse(work_.begin(), work_.end());
      while (!work_.empty()) {
        const std::uint32_t t = work_.back();
        work_.pop_back();
        if (!is_bad(t)) continue;
        if (flips_failed_.still_fails(t, mesh_.tet(t).v, clock_)) {
          // Its flips would fail as they did: only their pointer side effect is kept.
          replay_failed_flips(t);
          continue;
        }
        if (!schedule.take(ImprovementStep::Flips)) break;
        if (try_flips(t, stats)) {
          changed = true;
        } else {
          flips_failed_.record(t, clock_);
        }
      }
      // Smoothing of the vertices of the tets still bad.
      keep_bad(touched_, bad_);
      vertices_.clear();
      for (const std::uint32_t t : bad_)
        for (const std::uint32_t v : mesh_.tet(t).v) vertices_.push_back(v);
      std::sort(vertices_.begin(), vertices_.end());
      vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
      touched_ = bad_;
      for (const std::uint32_t v : vertices_) {
        if (smoothing_failed_.still_fails(v, std::span<const std::uint32_t>(&v, 1), clock_)) continue;
        if (!schedule.take(ImprovementStep::Smoothing)) break;
        if (smooth_vertex(v)) {
          ++stats.vertex_moves;
          changed = true;
          for (const StarTet& st : star_tets_) touched_.push_back(st.tet);
          clock_.moved(mesh_, star_);
        } else {
          smoothing_failed_.record(v, clock_);
        }
      }
      keep_bad(touched_, bad_);
      // Vertex insertion for the tets flips and smoothing left bad, once per tet.
      const std::vector<std::uint32_t> left = bad_;
      for (const std::uint32_t t : left) {
        if (!is_bad(t) || schedule.insertion_tried(mesh_.tet(t).v)) continue;
        if (!schedule.take(ImprovementStep::Insertion)) break;
        const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
        if (try_insert(t)) {
          ++stats.insertions;
          changed = true;
        } else {
          schedule.record_insertion(v);
        }
      }
      keep_bad(touched_, bad_);
      // Vertex deletion for the tets still bad.
      const std::vector<std::uint32_t> still = bad_;
      for (const std::uint32_t t : still) {
        if (!is_bad(t) || deletion_failed_.still_fails(t, mesh_.tet(t).v, clock_)) continue;
        if (!schedule.take(ImprovementStep::Deletion)) break;
        if (try_delete(t)) {
          ++stats.deletions;
          changed = true;
        } else {
          deletion_failed_.record(t, clock_);
        }
      }
      keep_bad(touched_, bad_);
      another = schedule.another_pass(stats.passes, bad_at_start, bad_.size(), changed);
    }
    stats.bad_after_passes = bad_.size();
    polish(stats);
    stats.bad_after = bad_.size();
    stats.held_moves = held_moves_;
    stats.relaxed_held_moves = relaxed_held_moves_;
    stats.traded_moves = traded_moves_;
    stats.pulled_back_trades = pulled_back_trades_;
    if (trades_started_) {
      stats.trade_min_deg = trade_min_deg_;
      stats.trade_max_deg = trade_max_deg_;
    }
    stats.breaker_held_moves = breaker_held_moves_;
    stats.polish_insertions = polish_insertions_;
    stats.polish_deletions = polish_deletions_;
    stats.joint_moves = joint_moves_;
    stats.neighbour_joint_moves = neighbour_joint_moves_;
    stats.flip_trades = flip_trades_;
    stats.polish_flips = polish_flips_;
    stats.holder_removals = holder_removals_;
    for (const ImprovementStep step :
         {ImprovementStep::Flips, ImprovementStep::Smoothing, ImprovementStep::Insertion, ImprovementStep::Deletion})
      stats.tries += schedule.taken(step);
    return stats;
  }

 private:
  /// One smoothing try of each vertex in `vertices` (sorted, unique) that may not add a
  /// tet outside the window to its star.
  void smooth_without_new_bad(const std::vector<std::uint32_t>& vertices, std::size_t& budget,
                              ImprovementStats& stats) {
    for (const std::uint32_t v : vertices) {
      if (budget == 0) return;
      FailureRecords& failed = trading_ ? trade_failed_ : polish_failed_;
      if (failed.still_fails(v, std::span<const std::uint32_t>(&v, 1), clock_)) continue;
      --budget;
      ++stats.polish_tries;
      if (smooth_vertex(v, true)) {
        ++stats.vertex_moves;
        for (const StarTet& st : star_tets_) touched_.push_back(st.tet);
        clock_.moved(mesh_, star_);
      } else {
        failed.record(v, clock_);
      }
    }
  }

  /// After the passes: rounds of smoothing for the tets still bad, first of the other
  /// vertices of the tets nearly as bad in the stars of their vertices (at a local
  /// optimum of the max-min objective a bad tet's vertex is held by such a tet, whose
  /// other vertices no step before moved), then of their own vertices; no move adds a tet
  /// outside the window to its star, so the count of bad tets never grows. At most
  /// kPolishRounds rounds and kPolishTriesPerBadTet tries per tet left bad
  /// (improvement_schedule.h); a round that removes no bad tet ends it. Then, with
  /// small-angle holds, the trade rounds from the same budget (trade_rounds).
  void polish(ImprovementStats& stats) {
    std::size_t budget = kPolishTriesPerBadTet * bad_.size();
    for (int round = 0; round < kPolishRounds && !bad_.empty() && budget > 0; ++round) {
      const std::size_t before = bad_.size();
      touched_ = bad_;
      // With small-angle holds, the tets touching no small input angle first: the budget
      // goes to them before the tets the termination floors hold outside the window.
      if (!at_small_angle_.empty()) {
        polish_tets_.clear();
        for (const std::uint32_t t : bad_)
          if (!at_small_angle(t)) polish_tets_.push_back(t);
        polish_round(polish_tets_, budget, stats);
        polish_insertion(polish_tets_, budget, stats);
        polish_flips(polish_tets_, budget, stats);
        polish_holder_removals(polish_tets_, budget, stats);
        polish_deletion(polish_tets_, budget, stats);
      }
      polish_tets_ = bad_;
      polish_round(polish_tets_, budget, stats);
      keep_bad(touched_, bad_);
      if (!at_small_angle_.empty()) {
        trade_extremes();
        collect_away_from_small_angles();
        polish_joint_moves(polish_tets_, stats);
        keep_bad(touched_, bad_);
      }
      if (bad_.size() >= before) break;
    }
    if (!at_small_angle_.empty()) trade_rounds(budget, stats);
  }

  /// Are two faces of tet t subfacets of one facet (a flat tet lying on the facet, which
  /// flat_facet_tets.h releases after the pass)?
  bool two_faces_on_one_facet(std::uint32_t t) const {
    const TetRecord& r = mesh_.tet(t);
    std::array<std::uint32_t, 4> facets{};
    int n = 0;
    for (int f = 0; f < 4; ++f) {
      const auto& o = kFaceVertex[f];
      const auto it = state_.subfaces.find(face_key(r.v[o[0]], r.v[o[1]], r.v[o[2]]));
      if (it == state_.subfaces.end()) continue;
      if (std::find(facets.begin(), facets.begin() + n, it->second) != facets.begin() + n) return true;
      facets[n++] = it->second;
    }
    return false;
  }

  /// The bad tets touching no small input angle, into polish_tets_.
  void collect_away_from_small_angles() {
    polish_tets_.clear();
    for (const std::uint32_t t : bad_)
      if (!at_small_angle(t)) polish_tets_.push_back(t);
  }

  /// After the polish's rounds, rounds of trades (hold_for_trade) for the bad tets
  /// touching no small input angle: smoothing of the vertices polish_round picks, where a
  /// move that would bring such a tet closer to the window may make tets touching a small
  /// angle worse, each kept at or above kTradeFraction of the least window dihedral sine of
  /// the tets touching one in the star and within the extreme dihedral angles the tets
  /// touching one had when the trades started (so the mesh's extreme angles are the ones
  /// the polish left); then the polish's steps without trades for the same tets (smoothing,
  /// insertion, flips, edge removal at holders, deletion). At most kTradeRounds rounds,
  /// from what is left of the polish's `budget` or kTradeTriesPerTet per such tet where
  /// that is more, ending after a round that leaves as many of them and made none it was
  /// not offered; where the tries are spent the rounds still make the joint moves and flip
  /// trades, which take none (on occt-sh2 and td-slit-1 with [20, 150] the polish's rounds
  /// once spent them all, so neither was ever tried there).
  void trade_rounds(std::size_t& budget, ImprovementStats& stats) {
    trade_extremes();
    if (trade_min_deg_ > trade_max_deg_) return;  // no tet touching a small angle is bad: nothing holds
    trades_started_ = true;
    collect_away_from_small_angles();
    // The trades' own tries where the polish's rounds left fewer: on inputs with many tets
    // touching a small angle outside the window those rounds spend the budget on them.
    budget = std::max(budget, kTradeTriesPerTet * polish_tets_.size());
    for (int round = 0; round < kTradeRounds && !polish_tets_.empty(); ++round) {
      const std::size_t before = polish_tets_.size();
      const std::set<std::array<std::uint32_t, 4>> offered = vertex_sets(polish_tets_);
      touched_ = bad_;
      trading_ = true;
      polish_round(polish_tets_, budget, stats);
      trading_ = false;
      polish_joint_moves(polish_tets_, stats);
      polish_neighbour_joint_moves(polish_tets_, stats);
      polish_flip_trades(polish_tets_, stats);
      polish_round(polish_tets_, budget, stats);
      polish_insertion(polish_tets_, budget, stats);
      polish_flips(polish_tets_, budget, stats);
      polish_holder_removals(polish_tets_, budget, stats);
      polish_deletion(polish_tets_, budget, stats);
      keep_bad(touched_, bad_);
      collect_away_from_small_angles();
      // A round that made a bad tet not offered to it yet is followed by another, which
      // offers it (the others' steps are not retried on unchanged stars).
      bool fresh = false;
      for (const auto& key : vertex_sets(polish_tets_)) fresh = fresh || offered.count(key) == 0;
      if (polish_tets_.size() >= before && !fresh) break;
    }
  }
  /// The sorted vertices of each tet of `tets`.
  std::set<std::array<std::uint32_t, 4>> vertex_sets(const std::vector<std::uint32_t>& tets) const {
    std::set<std::array<std::uint32_t, 4>> keys;
    for (const std::uint32_t t : tets) {
      std::array<std::uint32_t, 4> key = mesh_.tet(t).v;
      std::sort(key.begin(), key.end());
      keys.insert(key);
    }
    return keys;
  }

  /// The extreme dihedral angles of the tets touching a small angle (those outside the
  /// window are bad tets; flat tets lying on a facet, which mesh_plc releases after the
  /// pass, aside), into trade_min_deg_ and trade_max_deg_.
  void trade_extremes() {
    trade_min_deg_ = 180.0;
    trade_max_deg_ = 0.0;
    for (const std::uint32_t t : bad_) {
      if (!at_small_angle(t)) continue;
      const auto& tv = mesh_.tet(t).v;
      if (two_faces_on_one_facet(t)) continue;
      const auto [smallest, largest] =
          dihedral_extremes_deg(mesh_.point(tv[0]), mesh_.point(tv[1]), mesh_.point(tv[2]), mesh_.point(tv[3]));
      trade_min_deg_ = std::min(trade_min_deg_, smallest);
      trade_max_deg_ = std::max(trade_max_deg_, largest);
    }
  }

  /// One round of the polish for the bad tets `tets`: smoothing of the other vertices of
  /// the tets nearly as bad in the stars of their vertices, then of their own vertices.
  void polish_round(const std::vector<std::uint32_t>& tets, std::size_t& budget, ImprovementStats& stats) {
    // The other vertices of the tets nearly as bad as a bad tet in the stars of its
    // vertices: they hold its vertices at a local optimum of their stars.
    vertices_.clear();
    for (const std::uint32_t t : tets) {
      if (!is_bad(t)) continue;
      const double q = tet_quality(t);
      const std::array<std::uint32_t, 4> tv = mesh_.tet(t).v;
      for (const std::uint32_t v : tv) {
        mesh_.star(v, star_);
        for (const std::uint32_t u : star_) {
          if (u == t || !in_domain_tet(u) || tet_quality(u) > q + kPolishMargin) continue;
          for (const std::uint32_t w : mesh_.tet(u).v)
            if (std::find(tv.begin(), tv.end(), w) == tv.end()) vertices_.push_back(w);
        }
      }
    }
    std::sort(vertices_.begin(), vertices_.end());
    vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
    smooth_without_new_bad(vertices_, budget, stats);
    // Then the bad tets' own vertices.
    vertices_.clear();
    for (const std::uint32_t t : tets)
      if (is_bad(t))
        for (const std::uint32_t v : mesh_.tet(t).v) vertices_.push_back(v);
    std::sort(vertices_.begin(), vertices_.end());
    vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
    smooth_without_new_bad(vertices_, budget, stats);
  }


  // ---- measures ---------------------------------------------------------------------

  bool in_domain_tet(std::uint32_t t) const {
    return t < mesh_.tet_slots() && !mesh_.is_dead(t) && !mesh_.is_infinite(t) && t < state_.tet_region.size() &&
           in_domain(state_.tet_region[t]);
  }

  bool is_bad(std::uint32_t t) const {
    if (!in_domain_tet(t)) return false;
    const auto& v = mesh_.tet(t).v;
    return dihedral_outside(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), mesh_.point(v[3]), low_,
                            high_);
  }

  void collect_bad(std::vector<std::uint32_t>& out) const {
    out.clear();
    if (target_.start_tets) {
      std::vector<std::uint32_t> start = *target_.start_tets;
      keep_bad(start, out);
      return;
    }
    for (std::uint32_t t = 0; t < mesh_.tet_slots(); ++t)
      if (is_bad(t)) out.push_back(t);
  }

  /// The bad tets among `candidates` (which may repeat or be dead), in increasing order:
  /// the same list collect_bad gives when every bad tet is a candidate.
  void keep_bad(std::vector<std::uint32_t>& candidates, std::vector<std::uint32_t>& out) const {
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    out.clear();
    for (const std::uint32_t t : candidates)
      if (is_bad(t)) out.push_back(t);
  }

  /// The radius-edge bound the steps hold new tets to: max_radius_edge, or under strict
  /// bounds with the graded interior strategy (interior_strategy.h) the least of its
  /// per-tet bounds, which every tet wherever it lies then meets.
  static double strict_radius_edge_bound(const MeshOptions& options, const ImprovementTarget& target) {
    if (target.strict_bounds && options.interior_strategy == InteriorStrategy::Graded)
      return std::min(options.max_radius_edge, kInteriorBound);
    return options.max_radius_edge;
  }

  /// Does the tet break the radius-edge bound or a volume bound of the options?
  bool breaks_bounds(int region, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) const {
    if (state_.options.quality && !(radius_edge_ratio(a, b, c, d) <= radius_edge_bound_)) return true;
    if (any_volume_bound_) {
      const auto center = tet_circumcenter(a, b, c, d);
      if (!center) return true;
      const double bound = max_volume_at(state_, region, *center);
      if (bound > 0.0 && signed_volume(a, b, c, d) > bound) return true;
    }
    return false;
  }

  /// The objective of a flat or inverted tet of minimum dihedral sine s <= 0.
  double flat_quality(double sine) const { return target_.strict_bounds ? kStrictRefused : sine - 1.0; }
  /// The objective of a tet of minimum dihedral sine s > 0 that breaks a bound.
  double breaker_quality(double sine) const { return target_.strict_bounds ? kStrictRefused : penalized(sine); }

  /// The improvement objective of a tet of `region`: its minimum dihedral sine s, or
  /// breaker_quality(s) if it breaks a bound, or flat_quality(s) if it is flat or inverted.
  double quality(int region, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) const {
    return quality_of_sine(region, min_window_dihedral_sine(a, b, c, d, obtuse_scale_), a, b, c, d);
  }

  /// quality() of the tet (a, b, c, d) whose min_window_dihedral_sine is `sine`.
  double quality_of_sine(int region, double sine, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) const {
    if (sine <= 0.0) return flat_quality(sine);
    return breaks_bounds(region, a, b, c, d) ? breaker_quality(sine) : sine;
  }

  double tet_quality(std::uint32_t t) const {
    const auto& v = mesh_.tet(t).v;
    return quality(state_.tet_region[t], mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]), mesh_.point(v[3]));
  }

  // ---- retries (change_clock.h) -------------------------------------------------------
  //
  // Flips, smoothing and deletion that failed are not retried until a vertex whose star
  // they read has changed: on the same tets they would fail again, so skipping them
  // changes no result. The stars read:
  //   - flips of tet t: the tets around t's edges and across its faces, all in the stars
  //     of t's vertices;
  //   - smoothing v: v's star;
  //   - deletion for t: the stars of t's vertices.
  // Vertex insertion, the costliest step (a cavity and an ascent per starting point),
  // reads a cavity of up to kMaxCavity tets that smoothing and flips nearby change pass
  // after pass, mostly without making room for a vertex; it is tried once per tet, not
  // again for the same four vertices (improvement_schedule.h).

  /// What a failed try_flips(t) leaves behind: t as the vertex tet of v[0], v[1], v[2]
  /// (the edge searches start there).
  void replay_failed_flips(std::uint32_t t) {
    const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
    for (const auto& e : kEdges) mesh_.set_vertex_tet(v[e[0]], t);
  }

  // ---- flips ------------------------------------------------------------------------

  void adopt(int region) {
    clock_.made(mesh_, created_);
    if (state_.tet_region.size() < mesh_.tet_slots()) state_.tet_region.resize(mesh_.tet_slots(), kRegionExterior);
    for (const std::uint32_t t : created_) {
      state_.tet_region[t] = region;
      touched_.push_back(t);
      if (is_bad(t)) work_.push_back(t);
    }
  }

  bool try_flips(std::uint32_t t, ImprovementStats& stats) {
    const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
    for (const int e : edges_worst_first(v)) {
      if (mesh_.is_dead(t) || mesh_.tet(t).v != v) return false;
      mesh_.set_vertex_tet(v[kEdges[e][0]], t);  // the edge search starts in t
      if (try_remove_edge(v[kEdges[e][0]], v[kEdges[e][1]])) {
        ++stats.edge_removals;
        return true;
      }
      if (try_flip_facet_edge(v[kEdges[e][0]], v[kEdges[e][1]])) {
        ++stats.facet_edge_flips;
        return true;
      }
    }
    for (int f = 0; f < 4; ++f) {
      if (try_flip23(t, f)) {
        ++stats.flips23;
        return true;
      }
    }
    return false;
  }

  /// Edge removal of (a, b) if the worst new tet beats the worst tet of the ring. With
  /// `free_inside` (polish_holder_removals) no new tet touching no small input angle may lie
  /// outside the window, and no new tet may have a window dihedral sine below the least of
  /// the ring's tets (the objective ranks a tet breaking a bound below every other, so
  /// judged by it alone a ring whose worst tet breaks one may give way to a flatter tet that
  /// does not: on cgal-anchor the least dihedral angle of the tets touching small angles
  /// fell from 0.27 to 0.09 degrees).
  bool try_remove_edge(std::uint32_t a, std::uint32_t b, bool free_inside = false) {
    if (state_.subsegments.count(edge_key(a, b))) return false;
    if (!mesh_.tets_around_edge(a, b, ring_tets_, &ring_)) return false;
    if (ring_.size() > kMaxRing) return false;
    const int region = state_.tet_region[ring_tets_.front()];
    double old_worst = kInf, least_sine = kInf;
    for (std::size_t k = 0; k < ring_tets_.size(); ++k) {
      const std::uint32_t t = ring_tets_[k];
      if (!in_domain_tet(t) || state_.tet_region[t] != region) return false;
      if (state_.subfaces.count(face_key(a, b, ring_[k]))) return false;
      // The sine once, for the tet's quality and the ring's least sine.
      const auto& v = mesh_.tet(t).v;
      const Vec3 &p0 = mesh_.point(v[0]), &p1 = mesh_.point(v[1]), &p2 = mesh_.point(v[2]), &p3 = mesh_.point(v[3]);
      const double sine = min_window_dihedral_sine(p0, p1, p2, p3, obtuse_scale_);
      old_worst = std::min(old_worst, quality_of_sine(region, sine, p0, p1, p2, p3));
      least_sine = std::min(least_sine, sine);
    }
    // A tet at or below the threshold already rules its triangulation out: its bounds
    // need not be checked.
    const double threshold = old_worst + kMinFlipGain;
    // The points of the ring's vertices touching a small angle (free_inside; the
    // objective sees points, and no two vertices of a valid mesh share one).
    small_points_.clear();
    if (free_inside) {
      for (const std::uint32_t x : ring_)
        if (x < at_small_angle_.size() && at_small_angle_[x] != 0) small_points_.push_back(mesh_.point(x));
      for (const std::uint32_t x : {a, b})
        if (x < at_small_angle_.size() && at_small_angle_[x] != 0) small_points_.push_back(mesh_.point(x));
    }
    const TetQualityFn objective = [this, region, threshold, free_inside, least_sine](
                                       const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
      const double sine = min_window_dihedral_sine(p, q, r, s, obtuse_scale_);
      if (sine <= 0.0) return flat_quality(sine);
      if (free_inside && sine < least_sine) return -kInf;
      if (free_inside && dihedral_outside(p, q, r, s, low_, high_)) {
        bool touches = false;
        for (const Vec3& x : small_points_) touches = touches || x == p || x == q || x == r || x == s;
        if (!touches) return -kInf;
      }
      if (!(sine > threshold)) return sine;
      return breaks_bounds(region, p, q, r, s) ? breaker_quality(sine) : sine;
    };
    if (!remove_edge(mesh_, a, b, threshold, &created_, objective)) return false;
    adopt(region);
    return true;
  }

  /// Removes edge (a, b) of a facet by flipping it to the other diagonal of its two
  /// subfacets (facet_edge_flip.h) if that raises the worst quality around it.
  bool try_flip_facet_edge(std::uint32_t a, std::uint32_t b) {
    if (state_.vertices[a].kind == VertexKind::Interior || state_.vertices[b].kind == VertexKind::Interior)
      return false;
    const RegionTetQuality objective = [this](int region, const Vec3& p, const Vec3& q, const Vec3& r,
                                              const Vec3& s) { return quality(region, p, q, r, s); };
    if (!plan_facet_edge_flip(state_, a, b, kMinFlipGain, objective, facet_flip_)) return false;
    if (!commit_facet_edge_flip(state_, facet_flip_, created_)) return false;
    clock_.made(mesh_, created_);
    for (const std::uint32_t t : created_) {
      touched_.push_back(t);
      if (is_bad(t)) work_.push_back(t);
    }
    return true;
  }

  bool try_flip23(std::uint32_t t, int f) {
    const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
    const auto& o = kFaceVertex[f];
    if (state_.subfaces.count(face_key(v[o[0]], v[o[1]], v[o[2]]))) return false;
    const std::uint32_t u = mesh_.neighbor(t, f);
    const int region = state_.tet_region[t];
    if (!in_domain_tet(u) || state_.tet_region[u] != region) return false;
    const std::uint32_t apex = mesh_.opposite_vertex({t, static_cast<std::uint8_t>(f)});
    double new_worst = kInf;
    for (const std::uint8_t p : o) {
      std::array<std::uint32_t, 4> q = v;
      q[p] = apex;
      new_worst = std::min(new_worst, quality(region, mesh_.point(q[0]), mesh_.point(q[1]), mesh_.point(q[2]),
                                              mesh_.point(q[3])));
    }
    const double old_worst = std::min(tet_quality(t), tet_quality(u));
    if (!(new_worst > old_worst + kMinFlipGain)) return false;
    if (!flip23(mesh_, {t, static_cast<std::uint8_t>(f)}, &created_)) return false;
    adopt(region);
    return true;
  }

  // ---- smoothing --------------------------------------------------------------------

  /// Gathers the star of v and the facets through v; false when v may not move.
  bool gather_star(std::uint32_t v) {
    const VertexInfo& info = state_.vertices[v];
    if (info.kind == VertexKind::Interior) {
      freedom_ = Freedom::Free;
    } else if (info.kind == VertexKind::OnFacet) {
      freedom_ = Freedom::Plane;
    } else if (info.kind == VertexKind::OnSegment) {
      freedom_ = Freedom::Line;
    } else {
      return false;
    }
    mesh_.star(v, star_);
    star_tets_.clear();
    facets_.clear();
    hull_checks_.clear();
    bool any_in_domain = false;
    for (const std::uint32_t t : star_) {
      const TetRecord& r = mesh_.tet(t);
      const int k = mesh_.infinite_index(t);
      if (k >= 0) {
        // A hull face: if it is not a subfacet, a move must keep the hull convex at its
        // edges (the subfacets around a facet or segment vertex stay in their planes).
        const auto& o = kFaceVertex[k];
        if (state_.subfaces.count(face_key(r.v[o[0]], r.v[o[1]], r.v[o[2]]))) continue;
        for (int f = 0; f < 4; ++f) {
          if (f == k) continue;
          const std::uint32_t apex = mesh_.tet(r.adj[f] >> 2).v[r.adj[f] & 3u];
          hull_checks_.push_back({{r.v[o[0]], r.v[o[1]], r.v[o[2]]}, apex});
        }
        continue;
      }
      StarTet s;
      s.tet = t;
      s.local = mesh_.local_index(t, v);
      s.region = t < state_.tet_region.size() ? state_.tet_region[t] : kRegionUnknown;
      for (int i = 0; i < 4; ++i) s.p[i] = mesh_.point(r.v[i]);
      if (in_domain(s.region)) any_in_domain = true;
      star_tets_.push_back(s);
      for (int f = 0; f < 4; ++f) {
        if (f == s.local) continue;
        const auto& o = kFaceVertex[f];
        const auto it = state_.subfaces.find(face_key(r.v[o[0]], r.v[o[1]], r.v[o[2]]));
        if (it != state_.subfaces.end() && std::find(facets_.begin(), facets_.end(), it->second) == facets_.end())
          facets_.push_back(it->second);
      }
    }
    if (!any_in_domain) return false;
    if (freedom_ == Freedom::Free) return facets_.empty();
    if (freedom_ == Freedom::Plane) {
      if (facets_.size() != 1 || facets_.front() != info.owner) return false;
      const FacetTriangulation& facet = state_.facets[info.owner];
      direction_ = facet.normal().normalized();
      const Plc::Facet& input = state_.plc.facets[info.owner];
      origin_ = state_.plc.points[input.polygons.front().front()];
      axis_aligned_ = -1;
      const Vec3& n = facet.normal();
      for (int c = 0; c < 3; ++c)
        if (n[c] != 0.0 && n[(c + 1) % 3] == 0.0 && n[(c + 2) % 3] == 0.0) axis_aligned_ = c;
      return true;
    }
    const SegmentData& seg = state_.segments[info.owner];
    origin_ = mesh_.point(seg.a);
    span_ = mesh_.point(seg.b) - origin_;
    direction_ = span_.normalized();
    return true;
  }

  /// The point of v's constraint set nearest to x.
  Vec3 constrain(const Vec3& x) const {
    switch (freedom_) {
      case Freedom::Free:
        return x;
      case Freedom::Plane: {
        if (axis_aligned_ >= 0) {
          Vec3 p = x;
          p[axis_aligned_] = origin_[axis_aligned_];
          return p;
        }
        return x - (x - origin_).dot(direction_) * direction_;
      }
      case Freedom::Line: {
        const double t = (x - origin_).dot(span_) / span_.squaredNorm();
        return origin_ + t * span_;
      }
    }
    return x;
  }

  /// A direction projected onto the constraint's tangent space.
  Vec3 tangent(const Vec3& g) const {
    switch (freedom_) {
      case Freedom::Free:
        return g;
      case Freedom::Plane:
        return g - g.dot(direction_) * direction_;
      case Freedom::Line:
        return g.dot(direction_) * direction_;
    }
    return g;
  }

  /// The quality of a star tet with v at p: +inf for a positively oriented tet outside
  /// the domain, -inf for an inverted or flat tet, breaker_quality(sine) for a bound-breaking
  /// one; -inf as well when it is at most `floor` (a move must raise the star's worst
  /// quality above the current one).
  double star_tet_quality(const StarTet& s, const Vec3& p, double floor) const {
    std::array<Vec3, 4> q = s.p;
    q[s.local] = p;
    if (!in_domain(s.region)) return signed_volume(q[0], q[1], q[2], q[3]) > 0.0 ? kInf : -kInf;
    if (s.hold != Hold::None) {
      if (held_tet_keeps(s, q)) return kInf;
      // A Hold::NotWorse tet below its least counts towards the worst, so that an ascent
      // starting where it does not keep (a vertex insertion's starting point) raises it;
      // where the start keeps every hold (a smoothing move) such a point scores below the
      // start and is refused.
      if (s.hold == Hold::InsideWindow) return -kInf;
    }
    const double sine = min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_);
    if (!(sine > 0.0) || !(sine > floor)) return -kInf;
    if (!breaks_bounds(s.region, q[0], q[1], q[2], q[3])) return sine;
    const double value = breaker_quality(sine);
    return value > floor ? value : -kInf;
  }

  /// The worst quality over the star with v at p, into values_ per star tet; -inf as soon
  /// as one tet is at most `floor`. The star is kept worst first, so a failing trial point
  /// usually stops at its first tet.
  double star_quality(const Vec3& p, double floor) {
    double worst = kInf;
    values_.resize(star_tets_.size());
    for (std::size_t k = 0; k < star_tets_.size(); ++k) {
      values_[k] = star_tet_quality(star_tets_[k], p, floor);
      if (values_[k] == -kInf) return -kInf;
      worst = std::min(worst, values_[k]);
    }
    return worst;
  }

  bool exactly_valid(std::uint32_t v, const Vec3& p) const {
    for (const StarTet& s : star_tets_) {
      std::array<Vec3, 4> q = s.p;
      q[s.local] = p;
      if (predicates::orient3d(q[0].data(), q[1].data(), q[2].data(), q[3].data()) != Sign::Positive) return false;
    }
    for (const std::uint32_t f : facets_)
      if (!state_.facets[f].can_move_vertex(v, p)) return false;
    // Hull convexity (as check_delaunay tests it): no neighbouring hull face's apex beyond
    // a hull face of v, with v at p.
    for (const HullCheck& h : hull_checks_) {
      const double* c[3];
      for (int i = 0; i < 3; ++i) c[i] = h.face[i] == v ? p.data() : mesh_.coords(h.face[i]);
      if (predicates::orient3d(c[0], c[1], c[2], mesh_.coords(h.apex)) == Sign::Positive) return false;
    }
    return true;
  }

  /// Minimum-norm point of the convex hull of the gradients (Gilbert's algorithm).
  static Vec3 min_norm_point(const std::vector<Vec3>& g) {
    Vec3 x = g.front();
    for (const Vec3& y : g)
      if (y.squaredNorm() < x.squaredNorm()) x = y;
    for (int iter = 0; iter < 64; ++iter) {
      const Vec3* best = &g.front();
      for (const Vec3& y : g)
        if (y.dot(x) < best->dot(x)) best = &y;
      const Vec3 step = *best - x;
      const double gap = -x.dot(step);
      if (gap <= 1e-12 * x.squaredNorm() || step.squaredNorm() == 0.0) break;
      x += std::clamp(gap / step.squaredNorm(), 0.0, 1.0) * step;
    }
    return x;
  }

  /// Does held star tet s (Hold::NotWorse or InsideWindow) with its vertices at q keep
  /// what its hold asks?
  bool held_tet_keeps(const StarTet& s, const std::array<Vec3, 4>& q) const {
    if (s.hold == Hold::InsideWindow) {
      const double sine = min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_);
      return sine > 0.0 && !dihedral_outside(q[0], q[1], q[2], q[3], low_, high_) &&
             (s.breaker || !breaks_bounds(s.region, q[0], q[1], q[2], q[3]));
    }
    if (s.hold == Hold::Traded) {
      if (!(min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_) >= s.least_sine)) return false;
      const auto [smallest, largest] = dihedral_extremes_deg(q[0], q[1], q[2], q[3]);
      return smallest >= trade_min_deg_ && largest <= trade_max_deg_ &&
             (s.breaker || !breaks_bounds(s.region, q[0], q[1], q[2], q[3]));
    }
    return quality(s.region, q[0], q[1], q[2], q[3]) >= s.least &&
           min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_) >= s.least_sine;
  }

  /// Once the trade rounds have started, does every in-domain tet of star_tets_ touching a
  /// small angle keep, with the moving vertex at p, its dihedral angles within the trade's
  /// extremes (or its own, where it lies beyond them already; flat tets lying on a facet
  /// aside, as trade_extremes leaves them)? The traded moves keep them by their holds; the
  /// plain, held and relaxed moves of the trade rounds, judged by window sines, could take
  /// such a tet beyond them (on the needle of Tet3dSmallAngleTrades a move took one
  /// from inside them to 178.554 degrees, the extreme being 178.536, in the first trade
  /// round's smoothing, not by a traded move).
  bool keeps_trade_extremes(const Vec3& p) const {
    if (!trades_started_) return true;
    for (const StarTet& st : star_tets_) {
      if (!in_domain(st.region) || !at_small_angle(st.tet) || two_faces_on_one_facet(st.tet)) continue;
      std::array<Vec3, 4> q = st.p;
      const auto [smallest, largest] = dihedral_extremes_deg(q[0], q[1], q[2], q[3]);
      q[st.local] = p;
      const auto [new_smallest, new_largest] = dihedral_extremes_deg(q[0], q[1], q[2], q[3]);
      if (new_smallest < std::min(trade_min_deg_, smallest) || new_largest > std::max(trade_max_deg_, largest))
        return false;
    }
    return true;
  }

  /// Does every in-domain tet of star_tets_ keep, with the moving vertex at p, a window
  /// dihedral sine at or above the least of them before the move?
  bool keeps_least_sine(const Vec3& p) const {
    double least = kInf;
    for (const StarTet& st : star_tets_)
      if (in_domain(st.region))
        least = std::min(least, min_window_dihedral_sine(st.p[0], st.p[1], st.p[2], st.p[3], obtuse_scale_));
    for (const StarTet& st : star_tets_) {
      if (!in_domain(st.region)) continue;
      std::array<Vec3, 4> q = st.p;
      q[st.local] = p;
      if (min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_) < least) return false;
    }
    return true;
  }

  /// Does every in-domain tet of star_tets_ without a hold keep, with the moving vertex at
  /// p, a window dihedral sine at or above the least of them before the move? (The
  /// objective alone lets them fall to any positive sine where the worst of them breaks a
  /// bound.)
  bool free_tets_keep_least_sine(const Vec3& p) const {
    double least = kInf;
    for (const StarTet& st : star_tets_)
      if (in_domain(st.region) && st.hold == Hold::None)
        least = std::min(least, min_window_dihedral_sine(st.p[0], st.p[1], st.p[2], st.p[3], obtuse_scale_));
    for (const StarTet& st : star_tets_) {
      if (!in_domain(st.region) || st.hold != Hold::None) continue;
      std::array<Vec3, 4> q = st.p;
      q[st.local] = p;
      if (min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_) < least) return false;
    }
    return true;
  }

  /// Do all held tets of star_tets_ keep their holds with the moving vertex at p?
  bool holds_kept(const Vec3& p) const {
    for (const StarTet& st : star_tets_) {
      if (st.hold == Hold::None) continue;
      std::array<Vec3, 4> q = st.p;
      q[st.local] = p;
      if (!held_tet_keeps(st, q)) return false;
    }
    return true;
  }

  /// Does tet t have a vertex that touches a small input angle (small_angles.h, taken at
  /// the start of the pass; the interior vertices the pass inserts touch none)?
  bool at_small_angle(std::uint32_t t) const {
    for (const std::uint32_t x : mesh_.tet(t).v)
      if (x < at_small_angle_.size() && at_small_angle_[x] != 0) return true;
    return false;
  }

  /// Small-angle holds for the star of v (gathered): where a tet touching a small input
  /// angle is the worst of the star, worse than every tet that touches none, the star's
  /// worst cannot rise while that tet cannot be mended (the termination floors left it),
  /// and the tets beside it stay as they are. The holds make the tets touching a small
  /// angle constraints instead: one outside the window may not fall below the worst of
  /// them (so the star's worst does not fall), one inside must stay inside the window and
  /// within the bounds if it kept them (so none leaves it; one inside the window that
  /// breaks a bound is held by its angles alone, not to the worst held tet's objective, at
  /// which the objective's penalty put it and where it held the move); the tets touching no small angle make the
  /// objective. `relaxed`: every tet touching a small angle is held only to the worst of
  /// them, one inside the window as well (smooth_vertex then counts the tets outside the
  /// window). False (no holds set) when v touches a small angle itself, when no star tet
  /// touches none, or when no tet touching one is worse than all that do not.
  bool hold_small_angle_tets(std::uint32_t v, bool relaxed) {
    // Vertices the pass inserted (beyond at_small_angle_) are interior: they touch none.
    if (at_small_angle_.empty() || (v < at_small_angle_.size() && at_small_angle_[v] != 0)) return false;
    double free_worst = kInf, held_worst = kInf, held_sine = kInf;
    for (StarTet& s : star_tets_) {
      if (!in_domain(s.region)) continue;
      const double q = quality(s.region, s.p[0], s.p[1], s.p[2], s.p[3]);
      if (at_small_angle(s.tet)) {
        const double sine = min_window_dihedral_sine(s.p[0], s.p[1], s.p[2], s.p[3], obtuse_scale_);
        held_worst = std::min(held_worst, q);
        held_sine = std::min(held_sine, sine);
        s.least = q;
        s.breaker = q < 0.0 && sine > 0.0;
        s.hold = relaxed || dihedral_outside(s.p[0], s.p[1], s.p[2], s.p[3], low_, high_) || !(sine > 0.0)
                     ? Hold::NotWorse
                     : Hold::InsideWindow;
      } else {
        free_worst = std::min(free_worst, q);
      }
    }
    if (free_worst < kInf && held_worst < free_worst) {
      for (StarTet& s : star_tets_)
        if (s.hold == Hold::NotWorse) {
          s.least = held_worst;
          s.least_sine = held_sine;
        }
      return true;
    }
    for (StarTet& s : star_tets_) s.hold = Hold::None;
    return false;
  }

  /// Trade holds for the star of v (gathered), in the trade rounds where the strict and
  /// relaxed holds found no move: where the worst tet touching no small input angle is
  /// outside the window and a tet touching one is worse, every tet touching one is held
  /// (Hold::Traded) at or above kTradeFraction of the least window dihedral sine of them
  /// in the star, within the extreme dihedral angles such tets had when the trades
  /// started (trade_extremes) and within the bounds if it kept them; a tet touching none
  /// inside the window that breaks a bound is held by its angles (Hold::InsideWindow: the
  /// objective's penalty ranks it below every tet outside the window, so it, not the tet
  /// to free, would be the objective: on the tets left outside away from small angles
  /// after trade rounds without this hold, the worst tet touching none was such a tet at a
  /// vertex of 32 of 34, 17 of 28 and 64 of 67 of those that had no vertex with trade
  /// holds on gmsh-netgen-hinge, cgal-boeing and cgal-anchor); the other tets touching
  /// none make the objective and none of them falls below the least window dihedral sine
  /// of them before the move (free_tets_keep_least_sine). False (no holds set) when v
  /// touches a small angle itself or the star has no such tets.
  bool hold_for_trade(std::uint32_t v) {
    if (at_small_angle_.empty() || (v < at_small_angle_.size() && at_small_angle_[v] != 0)) return false;
    double free_worst = kInf, held_worst = kInf, held_sine = kInf;
    const StarTet* worst_free = nullptr;
    for (StarTet& s : star_tets_) {
      if (!in_domain(s.region)) continue;
      const double q = quality(s.region, s.p[0], s.p[1], s.p[2], s.p[3]);
      const double sine = min_window_dihedral_sine(s.p[0], s.p[1], s.p[2], s.p[3], obtuse_scale_);
      if (at_small_angle(s.tet)) {
        held_worst = std::min(held_worst, q);
        held_sine = std::min(held_sine, sine);
      } else if (q < 0.0 && sine > 0.0 && !dihedral_outside(s.p[0], s.p[1], s.p[2], s.p[3], low_, high_)) {
        // A bound breaker inside the window: held by its angles, not the objective.
        s.hold = Hold::InsideWindow;
        s.breaker = true;
      } else if (q < free_worst) {
        free_worst = q;
        worst_free = &s;
      }
    }
    const bool holds = worst_free != nullptr && held_worst < free_worst && held_sine > 0.0 &&
                       dihedral_outside(worst_free->p[0], worst_free->p[1], worst_free->p[2], worst_free->p[3], low_,
                                        high_);
    for (StarTet& s : star_tets_) {
      if (!holds) {
        s.hold = Hold::None;
        continue;
      }
      if (!in_domain(s.region) || !at_small_angle(s.tet)) continue;
      s.hold = Hold::Traded;
      s.least_sine = kTradeFraction * held_sine;
      s.breaker = breaks_bounds(s.region, s.p[0], s.p[1], s.p[2], s.p[3]);
    }
    return holds;
  }

  /// Moves v to raise the worst quality of its star (by kMinFlipGain at least); with
  /// `no_more_bad` (the polish), only if the star has no more tets outside the window
  /// after the move, and where that fails and a tet touching a small input angle holds
  /// the star's worst (hold_small_angle_tets), moves v to raise the worst tet touching
  /// none instead; where that fails too, tries again with relaxed holds, made only if the
  /// star has no more tets outside the window in all and no more of them touching no
  /// small angle (a tet touching one may leave the window, down to the worst of them,
  /// where a tet touching none enters it or the worst of them rises); in the trade rounds,
  /// where that fails too, a trade (hold_for_trade). Each kind of move is tried where the
  /// one before finds no gain or breaks one of its own rules (the floor of the star's
  /// least sine, a hold, a count rule): a move that gains but adds a tet outside the
  /// window may have a held or traded move that keeps the counts.
  bool smooth_vertex(std::uint32_t v, bool no_more_bad = false) {
    if (!gather_star(v)) return false;
    Vec3 p = mesh_.point(v);
    double start = 0.0, end = 0.0;
    // In the polish with small-angle holds, a move without holds must also keep every tet
    // of the star at or above the least window dihedral sine of the star before (the
    // objective alone lets a tet that keeps the bounds fall to any positive sine while a
    // breaker of a bound, the star's worst, rises: on cgal-anchor such moves made a tet
    // touching a small angle of 0.04 degrees, main's least there being 0.27).
    const bool floored = no_more_bad && !at_small_angle_.empty();
    if (optimize(v, p, start, end) && end > start + kMinFlipGain && !(floored && !keeps_least_sine(p)) &&
        (!no_more_bad || counts_kept(p, false, false)) && keeps_trade_extremes(p))
      return make_move(v, p, SmoothingKind::Plain);
    if (!no_more_bad) return false;
    if (hold_small_angle_tets(v, false)) {
      p = mesh_.point(v);
      if (optimize(v, p, start, end) && end > start + kMinFlipGain && holds_kept(p) && counts_kept(p, false, false) &&
          keeps_trade_extremes(p))
        return make_move(v, p, SmoothingKind::Held);
      if (!gather_star(v)) return false;
      p = mesh_.point(v);
      if (hold_small_angle_tets(v, true) && optimize(v, p, start, end) && end > start + kMinFlipGain &&
          holds_kept(p) && counts_kept(p, false, true) && keeps_trade_extremes(p))
        return make_move(v, p, SmoothingKind::Relaxed);
    }
    if (!trading_ || !gather_star(v) || !hold_for_trade(v)) return false;
    if (!trade_move(v, p, start) || !holds_kept(p) || !counts_kept(p, true, false)) return false;
    return make_move(v, p, SmoothingKind::Traded);
  }

  /// How smooth_vertex's move was judged.
  enum class SmoothingKind { Plain, Held, Relaxed, Traded };

  /// Moves v to p (smooth_vertex's move, star_tets_ its star with the holds it was judged
  /// by) and counts it; true.
  bool make_move(std::uint32_t v, const Vec3& p, SmoothingKind kind) {
    mesh_.move_point(v, p);  // the facet triangulations read the shared coordinates
    if (kind == SmoothingKind::Plain) return true;
    ++held_moves_;
    if (std::any_of(star_tets_.begin(), star_tets_.end(),
                    [](const StarTet& st) { return st.hold == Hold::InsideWindow && st.breaker; }))
      ++breaker_held_moves_;
    relaxed_held_moves_ += kind == SmoothingKind::Relaxed ? 1 : 0;
    traded_moves_ += kind == SmoothingKind::Traded ? 1 : 0;
    return true;
  }

  /// Do the star's counts of tets outside the window allow v at p (smooth_vertex, the
  /// polish)? Without holds, no more in all; with relaxed holds, no more in all and no
  /// more of them away from small angles; in a trade, no more away from small angles, and
  /// more of them touching a small angle only where fewer lie away from them or where the
  /// least window dihedral sine of the traded tets in the star does not fall (a traded tet
  /// crossing the window's edge while the worst of them stays as it is; before the
  /// improvement rounds, a probe found the count rules alone refusing every gaining move
  /// for 6, 6 and 20 of the tets left outside [20, 150] away from small angles on
  /// gmsh-netgen-hinge, cgal-boeing and cgal-anchor). With small-angle holds, no move adds
  /// a tet outside the window away from small angles, with or without holds: "no more in
  /// all" alone let a move take a tet touching one into the window while a tet touching
  /// none left it (with [20, 150], smoothing that tries its held and traded moves where
  /// such a move fails left gmsh-netgen-hinge 5 tets outside away from small angles, 3
  /// before, and 2 with this rule).
  bool counts_kept(const Vec3& p, bool traded, bool relaxed) const {
    std::array<std::size_t, 2> before{}, after{};
    std::size_t away_before = 0, away_after = 0;
    double held_before = kInf, held_after = kInf;
    for (const StarTet& st : star_tets_) {
      if (!in_domain(st.region)) continue;
      std::array<Vec3, 4> q = st.p;
      const int held_tet = st.hold != Hold::None ? 1 : 0;
      const bool away = !at_small_angle_.empty() && !at_small_angle(st.tet);
      const bool outside_before = dihedral_outside(q[0], q[1], q[2], q[3], low_, high_);
      before[held_tet] += outside_before ? 1 : 0;
      away_before += away && outside_before ? 1 : 0;
      if (st.hold == Hold::Traded)
        held_before = std::min(held_before, min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_));
      q[st.local] = p;
      const bool outside_after = dihedral_outside(q[0], q[1], q[2], q[3], low_, high_);
      after[held_tet] += outside_after ? 1 : 0;
      away_after += away && outside_after ? 1 : 0;
      if (st.hold == Hold::Traded)
        held_after = std::min(held_after, min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_));
    }
    if (traded)
      return after[0] <= before[0] && (after[1] <= before[1] || after[0] < before[0] || held_after >= held_before);
    return after[0] + after[1] <= before[0] + before[1] && away_after <= away_before &&
           (!relaxed || after[0] <= before[0]);
  }

  /// The move of a trade (hold_for_trade set the holds of v's star): the ascent of
  /// smoothing under the trade holds, then further ascents from the best point while each
  /// gains (kTradeAscents in all: one ascent stops after kSmoothIterations steps or where
  /// its line search fails, and the next starts with fresh gradients there); the point
  /// reached, or where it breaks a trade rule (a held tet beyond its floor or the trade's
  /// extremes, which the ascent scores by its sine alone, a tet touching none below the
  /// least of them, or the count rules), the first point back along the move that keeps
  /// them all and still gains (pulled_back). On success p is the point and `start` the
  /// star's worst quality before the move.
  bool trade_move(std::uint32_t v, Vec3& p, double& start) {
    const Vec3 origin = mesh_.point(v);
    p = origin;
    double end = 0.0;
    if (!optimize(v, p, start, end)) return false;
    for (int ascent = 1; ascent < kTradeAscents && end > start + kMinFlipGain; ++ascent) {
      Vec3 q = p;
      double from = 0.0, to = 0.0;
      if (!optimize(v, q, from, to) || !(to > from + kMinFlipGain)) break;
      p = q;
      end = to;
    }
    if (!(end > start + kMinFlipGain)) return false;
    return pulled_back(v, origin, p, start);
  }

  /// The first of p and the points back along the move from `origin` to p at a half, a
  /// quarter, ... of it (kLineSearchHalvings halvings) where the star's worst quality beats
  /// `start` by kMinFlipGain, the star is exactly valid and the rules of a trade hold
  /// (holds_kept, free_tets_keep_least_sine, counts_kept); into p. False if none.
  bool pulled_back(std::uint32_t v, const Vec3& origin, Vec3& p, double start) {
    const Vec3 step = p - origin;
    double fraction = 1.0;
    for (int k = 0; k <= kLineSearchHalvings; ++k, fraction *= 0.5) {
      const Vec3 q = constrain(origin + fraction * step);
      if (q == origin) return false;
      if (star_quality(q, start + kMinFlipGain) > start + kMinFlipGain && exactly_valid(v, q) && holds_kept(q) &&
          free_tets_keep_least_sine(q) && counts_kept(q, true, false)) {
        pulled_back_trades_ += k > 0 ? 1 : 0;
        p = q;
        return true;
      }
    }
    return false;
  }

  /// Steepest ascent of the star's worst quality (star_tets_, the moving vertex v at p,
  /// constrained by freedom_ and facets_). On return p is the best point found, `start`
  /// and `end` the worst quality before and after; false when the star is invalid at p.
  bool optimize(std::uint32_t v, Vec3& p, double& start, double& end) {
    double length = kInf;
    for (const StarTet& s : star_tets_)
      for (int i = 0; i < 4; ++i)
        if (i != s.local) length = std::min(length, (s.p[i] - p).norm());
    if (!(length > 0.0) || !std::isfinite(length)) return false;
    const double h = 1e-7 * length;
    double current = star_quality(p, -kInf);
    if (!(current > -kInf)) return false;
    // Worst tets first: trial points that fail mostly fail at the first tets.
    order_.resize(star_tets_.size());
    for (std::size_t k = 0; k < order_.size(); ++k) order_[k] = {values_[k], k};
    std::stable_sort(order_.begin(), order_.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    sorted_.clear();
    for (const auto& [value, k] : order_) sorted_.push_back(star_tets_[k]);
    star_tets_.swap(sorted_);
    current_values_.clear();
    for (const auto& [value, k] : order_) current_values_.push_back(value);
    start = current;
    for (int iter = 0; iter < kSmoothIterations; ++iter) {
      gradients_.clear();
      for (std::size_t k = 0; k < star_tets_.size(); ++k) {
        const StarTet& s = star_tets_[k];
        if (!in_domain(s.region)) continue;
        if (current_values_[k] > current + 0.02 * std::abs(current) + 1e-9) continue;
        Vec3 g;
        for (int c = 0; c < 3; ++c) {
          Vec3 plus = p, minus = p;
          plus[c] += h;
          minus[c] -= h;
          const double qp = min_dihedral_sine_at(s, plus), qm = min_dihedral_sine_at(s, minus);
          g[c] = (qp - qm) / (2.0 * h);
        }
        gradients_.push_back(tangent(g));
      }
      if (gradients_.empty()) break;
      const Vec3 d = min_norm_point(gradients_);
      const double norm = d.norm();
      if (!(norm > 0.0) || !std::isfinite(norm)) break;
      double alpha = 0.25 * length / norm;
      bool moved = false;
      for (int k = 0; k < kLineSearchHalvings; ++k, alpha *= 0.5) {
        const Vec3 q = constrain(p + alpha * d);
        if (q == p) break;
        const double value = star_quality(q, current);
        if (value > current && exactly_valid(v, q)) {
          p = q;
          current = value;
          current_values_ = values_;
          moved = true;
          break;
        }
      }
      if (!moved) break;
    }
    end = current;
    return true;
  }

  // ---- vertex insertion -------------------------------------------------------------

  /// Inserts a vertex for bad tet t if that raises the worst quality around it, trying
  /// the starting points of insertion_candidates in turn (insert_at; `holds`: judged
  /// under small-angle holds where the cavity allows, polish_insertion).
  bool try_insert(std::uint32_t t, bool holds = false) {
    if (mesh_.num_vertices() >= state_.vertex_cap) return false;
    insertion_candidates(t);
    const std::vector<Vec3> candidates = candidates_;
    for (const Vec3& p : candidates)
      if (insert_at(t, p, holds)) return true;
    return false;
  }

  /// Starting points for a vertex inserted for bad tet t: its centroid, then the
  /// centroid pushed off the tet's flat direction, both ways, by kInsertOffsets times
  /// the tet's longest edge. The flat direction is the common normal of the tet's worst
  /// edge and its opposite edge: a sliver, or a flat tet filling a fold of the boundary
  /// alone (its two boundary faces at the worst edge), is thinnest along it, and a vertex
  /// off its plane on the domain's side splits the worst angle between two tets (a
  /// point on the wrong side makes inverted tets and is rejected).
  void insertion_candidates(std::uint32_t t) {
    const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
    std::array<Vec3, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = mesh_.point(v[i]);
    const Vec3 centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
    candidates_.assign(1, centroid);
    const auto sines = window_dihedral_sines(p[0], p[1], p[2], p[3], obtuse_scale_);
    const int worst = static_cast<int>(std::min_element(sines.begin(), sines.end()) - sines.begin());
    const int a = kEdges[worst][0], b = kEdges[worst][1];
    const int c = kEdges[5 - worst][0], d = kEdges[5 - worst][1];
    const Vec3 n = (p[b] - p[a]).cross(p[d] - p[c]);
    double longest = 0.0;
    for (const auto& e : kEdges) longest = std::max(longest, (p[e[1]] - p[e[0]]).norm());
    const double norm = n.norm();
    if (!(norm > 0.0) || !std::isfinite(norm) || !(longest > 0.0)) return;
    for (const double offset : kInsertOffsets)
      for (const double side : {1.0, -1.0}) candidates_.push_back(centroid + (side * offset * longest / norm) * n);
  }

  /// Inserts a vertex starting at p for bad tet t if that raises the worst quality
  /// around it. The cavity is t and the tets of t's region whose circumspheres hold p,
  /// grown from t across faces that are not subfacets (at most kMaxCavity tets); it may
  /// not swallow a vertex or a subsegment. The new vertex joins the cavity's boundary
  /// faces; it starts at p and is placed by the ascent of smoothing, every new tet
  /// positively oriented (exact orient3d). Accepted only if the worst new tet beats the
  /// worst cavity tet by kMinFlipGain. With `holds` (the polish, polish_insertion) the
  /// cavity's tets touching a small input angle are judged apart where the worst of them
  /// is worse than every cavity tet touching none: the new tets touching one (those on a
  /// boundary face with such a vertex; the new vertex touches none) are held as
  /// constraints, none below the worst of the old ones and no more of them outside the
  /// window, and the worst new tet touching none must beat the worst old one; elsewhere
  /// the insertion is judged as without holds.
  bool insert_at(std::uint32_t t, Vec3 p, bool holds) {
    const int region = state_.tet_region[t];
    const std::uint32_t stamp = mesh_.new_stamp();
    cavity_.assign(1, t);
    mesh_.set_stamp(t, stamp);
    for (std::size_t k = 0; k < cavity_.size(); ++k) {
      const std::uint32_t c = cavity_[k];
      const std::array<std::uint32_t, 4> v = mesh_.tet(c).v;
      for (int f = 0; f < 4; ++f) {
        const std::uint32_t u = mesh_.neighbor(c, f);
        if (mesh_.stamp(u) == stamp || !in_domain_tet(u) || state_.tet_region[u] != region) continue;
        const auto& o = kFaceVertex[f];
        if (state_.subfaces.count(face_key(v[o[0]], v[o[1]], v[o[2]]))) continue;
        const auto& w = mesh_.tet(u).v;
        if (predicates::insphere(mesh_.coords(w[0]), mesh_.coords(w[1]), mesh_.coords(w[2]), mesh_.coords(w[3]),
                                 p.data()) != Sign::Positive)
          continue;
        if (cavity_.size() >= kMaxCavity) return false;
        mesh_.set_stamp(u, stamp);
        cavity_.push_back(u);
      }
    }
    // The boundary faces, each with the tet outside and the new tet it makes (the cavity
    // tet with the face's opposite vertex replaced by the new one).
    star_tets_.clear();
    outside_.clear();
    kept_vertices_.clear();
    kept_edges_.clear();
    double old_worst = kInf;
    for (const std::uint32_t c : cavity_) {
      old_worst = std::min(old_worst, tet_quality(c));
      const TetRecord& r = mesh_.tet(c);
      for (int f = 0; f < 4; ++f) {
        if (mesh_.stamp(r.adj[f] >> 2) == stamp) continue;
        StarTet st;
        st.tet = c;
        st.local = f;
        st.region = region;
        for (int i = 0; i < 4; ++i) st.p[i] = mesh_.point(r.v[i]);
        st.p[f] = p;
        star_tets_.push_back(st);
        outside_.push_back(r.adj[f]);
        const auto& o = kFaceVertex[f];
        for (int i = 0; i < 3; ++i) {
          kept_vertices_.push_back(r.v[o[i]]);
          kept_edges_.push_back(edge_key(r.v[o[i]], r.v[o[(i + 1) % 3]]));
        }
      }
    }
    // The boundary must be a topological sphere for the new vertex's tets to fill the
    // cavity: every edge in exactly two boundary faces, and V - E + F = 2.
    std::sort(kept_edges_.begin(), kept_edges_.end());
    for (std::size_t k = 0; k < kept_edges_.size(); k += 2)
      if (k + 1 >= kept_edges_.size() || kept_edges_[k] != kept_edges_[k + 1] ||
          (k + 2 < kept_edges_.size() && kept_edges_[k + 2] == kept_edges_[k]))
        return false;
    std::sort(kept_vertices_.begin(), kept_vertices_.end());
    kept_vertices_.erase(std::unique(kept_vertices_.begin(), kept_vertices_.end()), kept_vertices_.end());
    const std::size_t faces = star_tets_.size(), edges = kept_edges_.size() / 2;
    if (kept_vertices_.size() + faces != edges + 2) return false;
    for (const std::uint32_t c : cavity_) {
      const auto& v = mesh_.tet(c).v;
      for (const std::uint32_t x : v)
        if (!std::binary_search(kept_vertices_.begin(), kept_vertices_.end(), x)) return false;
      for (const auto& e : kEdges) {
        const std::uint64_t key = edge_key(v[e[0]], v[e[1]]);
        if (state_.subsegments.count(key) && !std::binary_search(kept_edges_.begin(), kept_edges_.end(), key))
          return false;
      }
    }
    freedom_ = Freedom::Free;
    facets_.clear();
    hull_checks_.clear();
    const bool held_cavity = holds && hold_cavity_tets(old_worst);
    double start = 0.0, end = 0.0;
    if (!optimize(kNone, p, start, end)) return false;
    if (!(end > old_worst + kMinFlipGain) || !exactly_valid(kNone, p)) return false;
    if (held_cavity && !holds_kept(p)) return false;
    // Fewer tets outside the window, or as many: a flat tet split into several tets that
    // are better but still outside (a thin wedge of the domain) is no gain. Under holds
    // the tets touching a small angle and the others are counted apart.
    std::array<std::size_t, 2> old_bad{}, new_bad{};
    for (const std::uint32_t c : cavity_) old_bad[held_cavity && at_small_angle(c) ? 1 : 0] += is_bad(c) ? 1 : 0;
    for (const StarTet& st : star_tets_) {
      std::array<Vec3, 4> q = st.p;
      q[st.local] = p;
      new_bad[st.hold != Hold::None ? 1 : 0] += dihedral_outside(q[0], q[1], q[2], q[3], low_, high_) ? 1 : 0;
    }
    if (new_bad[0] > old_bad[0] || new_bad[1] > old_bad[1]) return false;
    // Commit: the cavity tets give way to the new vertex's tets.
    quads_.clear();
    for (const StarTet& st : star_tets_) {
      std::array<std::uint32_t, 4> q = mesh_.tet(st.tet).v;
      q[st.local] = mesh_.num_vertices();
      quads_.push_back(q);
    }
    VertexInfo info;
    info.kind = VertexKind::Interior;
    info.floor = kInf;
    for (const std::uint32_t x : kept_vertices_) info.floor = std::min(info.floor, state_.vertices[x].floor);
    mesh_.add_vertex(p);
    state_.vertices.push_back(info);
    for (const std::uint32_t c : cavity_) mesh_.kill_tet(c);
    created_.clear();
    for (const auto& q : quads_) created_.push_back(mesh_.create_tet(q[0], q[1], q[2], q[3]));
    const bool glued = mesh_.glue_by_vertices(created_, outside_);
    DELMESH_CHECK(glued, "sliver improvement: the new vertex's tets do not close up with the mesh");
    for (const std::uint32_t c : created_)
      for (const std::uint32_t x : mesh_.tet(c).v) mesh_.set_vertex_tet(x, c);
    ++state_.stage_steiner;
    adopt(region);
    return true;
  }

  /// Small-angle holds for a vertex insertion (insert_at, cavity_ and its new tets in
  /// star_tets_): where the worst cavity tet touching a small input angle is worse than
  /// every cavity tet touching none, the new tets touching one are held (Hold::NotWorse,
  /// none below that worst) and `old_worst` becomes the worst cavity tet touching none.
  /// False (nothing held) otherwise, or when every new tet would touch a small angle.
  bool hold_cavity_tets(double& old_worst) {
    double free_worst = kInf, held_worst = kInf, held_sine = kInf;
    for (const std::uint32_t c : cavity_) {
      double& worst = at_small_angle(c) ? held_worst : free_worst;
      worst = std::min(worst, tet_quality(c));
      if (at_small_angle(c)) {
        const auto& v = mesh_.tet(c).v;
        held_sine = std::min(held_sine, min_window_dihedral_sine(mesh_.point(v[0]), mesh_.point(v[1]),
                                                                 mesh_.point(v[2]), mesh_.point(v[3]), obtuse_scale_));
      }
    }
    if (!(free_worst < kInf) || !(held_worst < free_worst)) return false;
    bool any_free = false;
    for (StarTet& st : star_tets_) {
      bool touches = false;
      for (int i = 0; i < 4; ++i) {
        const std::uint32_t x = mesh_.tet(st.tet).v[i];
        if (i != st.local && x < at_small_angle_.size() && at_small_angle_[x] != 0) touches = true;
      }
      st.hold = touches ? Hold::NotWorse : Hold::None;
      st.least = held_worst;
      st.least_sine = held_sine;
      any_free = any_free || !touches;
    }
    if (!any_free) {
      for (StarTet& st : star_tets_) st.hold = Hold::None;
      return false;
    }
    old_worst = free_worst;
    return true;
  }

  /// True the first time tet t's vertex set is offered to a polish step (`tried` keeps
  /// the sorted vertices of every tet offered before).
  bool first_offer(std::set<std::array<std::uint32_t, 4>>& tried, std::uint32_t t) const {
    std::array<std::uint32_t, 4> key = mesh_.tet(t).v;
    std::sort(key.begin(), key.end());
    return tried.insert(key).second;
  }

  /// Vertex insertion in the polish: for each bad tet in `tets` touching no small input
  /// angle, once per four vertices, a vertex inserted as in the passes' insertion (which
  /// tried each tet once, before the polish moved its vertices and their neighbours), and
  /// judged under small-angle holds where hold_cavity_tets sets them: where the
  /// termination floors left a tet touching a small angle outside the window in the
  /// cavity, the plain insertion compares the new tets with it and can gain nothing,
  /// however much the tets touching none would.
  void polish_insertion(const std::vector<std::uint32_t>& tets, std::size_t& budget, ImprovementStats& stats) {
    for (const std::uint32_t t : tets) {
      if (budget == 0) return;
      if (!is_bad(t) || at_small_angle(t)) continue;
      if (!first_offer(polish_insertions_tried_, t)) continue;
      --budget;
      ++stats.polish_tries;
      if (try_insert(t, true)) {
        ++stats.insertions;
        ++polish_insertions_;
      }
    }
  }

  /// Flips in the polish: for each bad tet in `tets` touching no small input angle, once
  /// per four vertices, the flips of step 1 (try_flips: edge removal, facet edge flips,
  /// 2-3 flips, judged by the worst tet as in the passes). The passes retried a tet's
  /// flips only while a pass followed; the polish's moves change the rings around the
  /// tets it leaves.
  void polish_flips(const std::vector<std::uint32_t>& tets, std::size_t& budget, ImprovementStats& stats) {
    for (const std::uint32_t t : tets) {
      if (budget == 0) return;
      if (!is_bad(t) || at_small_angle(t)) continue;
      if (!first_offer(polish_flips_tried_, t)) continue;
      --budget;
      ++stats.polish_tries;
      if (try_flips(t, stats)) ++polish_flips_;  // try_flips counts the flip by its kind
    }
  }

  /// Edge removal at the holders in the polish: for each bad tet in `tets` touching no
  /// small input angle, the tets of its vertices' stars that touch a small angle and are
  /// worse than it (the tets that hold its vertices at a local optimum: the held moves
  /// may not lower them) are offered edge removal, their edges in order, once per four
  /// vertices: made if the worst new tet beats the worst tet of the ring (as in the
  /// passes) and no new tet touching no small angle lies outside the window. Without that
  /// rule, and with 2-3 flips as well, the tets left outside away from small angles grew
  /// (sliver_improvement.h, step 5).
  void polish_holder_removals(const std::vector<std::uint32_t>& tets, std::size_t& budget, ImprovementStats& stats) {
    holders_.clear();
    for (const std::uint32_t t : tets) {
      if (!is_bad(t) || at_small_angle(t)) continue;
      const double q = tet_quality(t);
      for (const std::uint32_t v : mesh_.tet(t).v) {
        mesh_.star(v, star_);
        for (const std::uint32_t u : star_)
          if (in_domain_tet(u) && at_small_angle(u) && tet_quality(u) < q) holders_.push_back(u);
      }
    }
    std::sort(holders_.begin(), holders_.end());
    holders_.erase(std::unique(holders_.begin(), holders_.end()), holders_.end());
    for (const std::uint32_t h : holders_) {
      if (budget == 0) return;
      if (!in_domain_tet(h)) continue;
      if (!first_offer(polish_flips_tried_, h)) continue;
      --budget;
      ++stats.polish_tries;
      const std::array<std::uint32_t, 4> v = mesh_.tet(h).v;
      for (const auto& e : kEdges) {
        if (mesh_.is_dead(h) || mesh_.tet(h).v != v) break;
        mesh_.set_vertex_tet(v[e[0]], h);  // the edge search starts in h
        if (try_remove_edge(v[e[0]], v[e[1]], true)) {
          ++stats.edge_removals;
          ++polish_flips_;
          ++holder_removals_;
          break;
        }
      }
    }
  }

  /// The trade rules of this pass's window and trade limits (trade_rules.h).
  TradeRules trade_rules() {
    TradeRules rules;
    rules.low_deg = low_;
    rules.high_deg = high_;
    rules.obtuse_scale = obtuse_scale_;
    rules.trade_min_deg = trade_min_deg_;
    rules.trade_max_deg = trade_max_deg_;
    rules.trade_fraction = kTradeFraction;
    rules.min_gain = kMinFlipGain;
    rules.at_small_angle = &at_small_angle_;
    rules.breaks_bounds = [this](int region, const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
      return breaks_bounds(region, p, q, r, s);
    };
    return rules;
  }

  /// The six edges of tet v (indices into kEdges), worst window dihedral sine first
  /// (stable: ties keep kEdges' order).
  std::array<int, 6> edges_worst_first(const std::array<std::uint32_t, 4>& v) const {
    const auto sines = window_dihedral_sines(mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]),
                                             mesh_.point(v[3]), obtuse_scale_);
    std::array<int, 6> order{0, 1, 2, 3, 4, 5};
    std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return sines[x] < sines[y]; });
    return order;
  }

  /// The trade rules and the objective the joint moves are judged by (joint_move.h).
  JointMoveRules joint_move_rules() {
    JointMoveRules rules;
    static_cast<TradeRules&>(rules) = trade_rules();
    rules.quality = [this](int region, const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
      return quality(region, p, q, r, s);
    };
    return rules;
  }

  /// Moves the two vertices of joint_ (plan_joint_move's result) and records the change.
  void make_joint_move() {
    mesh_.move_point(joint_.a, joint_.pa);  // the facet triangulations read the shared coordinates
    mesh_.move_point(joint_.b, joint_.pb);
    clock_.moved(mesh_, joint_.tets);
    for (const std::uint32_t u : joint_.tets) touched_.push_back(u);
  }

  /// Joint moves (joint_move.h), at the end of each polish round and in each trade round
  /// after its trades: for each bad tet in `tets` touching no small input angle whose
  /// stars changed since its last try, the two vertices of its edges, worst angle first,
  /// moved together under the trade rules; the first move found is made. At most one try
  /// per such tet and round (the rounds are bounded), outside the polish's budget of
  /// tries, which the polish's other steps keep to themselves.
  void polish_joint_moves(const std::vector<std::uint32_t>& tets, ImprovementStats& stats) {
    const JointMoveRules rules = joint_move_rules();
    for (const std::uint32_t t : tets) {
      if (!is_bad(t) || at_small_angle(t)) continue;
      const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
      if (joint_failed_.still_fails(t, v, clock_)) continue;
      ++stats.joint_tries;
      const std::array<int, 6> order = edges_worst_first(v);
      bool moved = false;
      for (const int e : order) {
        if (!plan_joint_move(state_, rules, v[kEdges[e][0]], v[kEdges[e][1]], joint_)) continue;
        make_joint_move();
        ++joint_moves_;
        moved = true;
        break;
      }
      if (!moved) joint_failed_.record(t, clock_);
    }
  }

  /// Joint moves with a neighbour (joint_move.h), in each trade round after polish_joint_moves:
  /// for each bad tet in `tets` touching no small input angle whose neighbourhood changed
  /// since its last try, each vertex of its edges (worst angle first) moved together with
  /// each of its neighbours outside the tet, under the trade rules; the first move found is
  /// made. A tet's worst angle at an edge is set by the positions of the ring around that
  /// edge, and a ring vertex outside the tet can hold the tet's own vertex where only the
  /// two moving together gain. At most one try per such tet and round, outside the
  /// polish's budget of tries, as the joint moves.
  void polish_neighbour_joint_moves(const std::vector<std::uint32_t>& tets, ImprovementStats& stats) {
    const JointMoveRules rules = joint_move_rules();
    for (const std::uint32_t t : tets) {
      if (!is_bad(t) || at_small_angle(t)) continue;
      const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
      // The pairs, and the vertices whose stars the moves read: v and its neighbours.
      neighbour_pairs_.clear();
      neighbourhood_.assign(v.begin(), v.end());
      for (const int e : edges_worst_first(v)) {
        for (const int end : {kEdges[e][0], kEdges[e][1]}) {
          mesh_.vertex_neighbors(v[end], neighbors_);
          for (const std::uint32_t w : neighbors_) {
            if (w == kInfiniteVertex || std::find(v.begin(), v.end(), w) != v.end()) continue;
            const std::pair<std::uint32_t, std::uint32_t> pair{v[end], w};
            if (std::find(neighbour_pairs_.begin(), neighbour_pairs_.end(), pair) != neighbour_pairs_.end()) continue;
            neighbour_pairs_.push_back(pair);
            neighbourhood_.push_back(w);
          }
        }
      }
      if (neighbour_joint_failed_.still_fails(t, neighbourhood_, clock_)) continue;
      ++stats.neighbour_joint_tries;
      bool moved = false;
      for (const auto& [a, w] : neighbour_pairs_) {
        if (!plan_joint_move(state_, rules, a, w, joint_)) continue;
        make_joint_move();
        ++neighbour_joint_moves_;
        moved = true;
        break;
      }
      if (!moved) neighbour_joint_failed_.record(t, clock_);
    }
  }

  /// Flip trades (flip_trade.h), in each trade round after its joint moves: for each bad tet
  /// in `tets` touching no small input angle whose stars changed since its last try, its
  /// edges, worst angle first, offered to edge removal, then its faces to 2-3 flips, under
  /// the trade rules; the first flip found is made. At most one try per such tet and
  /// round, outside the polish's budget of tries, as the joint moves.
  void polish_flip_trades(const std::vector<std::uint32_t>& tets, ImprovementStats& stats) {
    FlipTradeRules rules;
    static_cast<TradeRules&>(rules) = trade_rules();
    rules.max_ring = kMaxRing;
    int region = kRegionUnknown;
    for (const std::uint32_t t : tets) {
      if (!is_bad(t) || at_small_angle(t)) continue;
      const std::array<std::uint32_t, 4> v = mesh_.tet(t).v;
      if (flip_trade_failed_.still_fails(t, v, clock_)) continue;
      ++stats.flip_trade_tries;
      const std::array<int, 6> order = edges_worst_first(v);
      bool flipped = false;
      for (const int e : order) {
        mesh_.set_vertex_tet(v[kEdges[e][0]], t);  // the edge search starts in t
        flipped = trade_remove_edge(state_, rules, v[kEdges[e][0]], v[kEdges[e][1]], created_, region);
        if (flipped) break;
      }
      for (int f = 0; f < 4 && !flipped; ++f) flipped = trade_flip23(state_, rules, t, f, created_, region);
      if (!flipped) {
        flip_trade_failed_.record(t, clock_);
        continue;
      }
      adopt(region);
      ++flip_trades_;
    }
  }

  /// Vertex deletion in the polish: for each bad tet in `tets` touching no small input
  /// angle, once per four vertices, its interior Steiner vertices offered to contraction
  /// as in the passes' deletion, judged by try_delete's holds where they apply.
  void polish_deletion(const std::vector<std::uint32_t>& tets, std::size_t& budget, ImprovementStats& stats) {
    for (const std::uint32_t t : tets) {
      if (budget == 0) return;
      if (!is_bad(t) || at_small_angle(t)) continue;
      if (!first_offer(polish_deletions_tried_, t)) continue;
      --budget;
      ++stats.polish_tries;
      if (try_delete(t, true)) {
        ++stats.deletions;
        ++polish_deletions_;
      }
    }
  }

  // ---- vertex deletion --------------------------------------------------------------

  /// Removes an interior Steiner vertex of bad tet t by contracting it onto the
  /// neighbour that makes the best worst tet (vertex_deletion.h), if that worst tet beats
  /// the worst tet of the vertex's star by kMinFlipGain and leaves no more tets outside
  /// the window. The star must lie in one region; an interior vertex has no subfacet or
  /// subsegment through it, so the boundary and the markers stay as they are. With
  /// `holds` (the polish, polish_deletion) the tets touching a small input angle and the
  /// others are judged apart where the worst star tet touching one is worse than every
  /// star tet touching none: the new tets touching one may not fall below that worst nor
  /// grow in number outside the window, and the worst new tet touching none must beat the
  /// worst old one, no more of them outside the window; elsewhere as without holds.
  bool try_delete(std::uint32_t t, bool holds = false) {
    const std::array<std::uint32_t, 4> tv = mesh_.tet(t).v;
    const int region = state_.tet_region[t];
    for (const std::uint32_t v : tv) {
      if (state_.vertices[v].kind != VertexKind::Interior) continue;
      if (holds && v < at_small_angle_.size() && at_small_angle_[v] != 0) continue;
      mesh_.star(v, star_);
      // [0]: tets touching no small angle (all of them without holds), [1]: touching one.
      std::array<double, 2> old_worst{kInf, kInf};
      double held_sine = kInf;  // the least window dihedral sine of the tets touching one
      std::array<std::size_t, 2> old_bad{};
      bool usable = true;
      neighbors_.clear();
      for (const std::uint32_t s : star_) {
        if (!in_domain_tet(s) || state_.tet_region[s] != region) {
          usable = false;
          break;
        }
        const int group = holds && at_small_angle(s) ? 1 : 0;
        old_worst[group] = std::min(old_worst[group], tet_quality(s));
        if (group == 1) {
          const auto& w = mesh_.tet(s).v;
          held_sine = std::min(held_sine, min_window_dihedral_sine(mesh_.point(w[0]), mesh_.point(w[1]),
                                                                   mesh_.point(w[2]), mesh_.point(w[3]), obtuse_scale_));
        }
        old_bad[group] += is_bad(s) ? 1 : 0;
        for (const std::uint32_t x : mesh_.tet(s).v)
          if (x != v) neighbors_.push_back(x);
      }
      if (!usable) continue;
      // Holds only where a tet touching a small angle is the worst of the star.
      const bool held = holds && old_worst[1] < old_worst[0];
      if (holds && !held) {
        old_worst = {std::min(old_worst[0], old_worst[1]), kInf};
        old_bad = {old_bad[0] + old_bad[1], 0};
      }
      std::sort(neighbors_.begin(), neighbors_.end());
      neighbors_.erase(std::unique(neighbors_.begin(), neighbors_.end()), neighbors_.end());
      double best = old_worst[0] + kMinFlipGain;
      bool found = false;
      for (const std::uint32_t u : neighbors_) {
        if (!plan_contraction(mesh_, star_, v, u, trial_)) continue;
        double worst = kInf;
        std::array<std::size_t, 2> new_bad{};
        bool kept = true;
        for (const auto& q : trial_.tets) {
          const Vec3 &a = mesh_.point(q[0]), &b = mesh_.point(q[1]), &c = mesh_.point(q[2]), &d = mesh_.point(q[3]);
          const double value = quality(region, a, b, c, d);
          bool touches = false;
          if (held)
            for (const std::uint32_t x : q) touches = touches || (x < at_small_angle_.size() && at_small_angle_[x] != 0);
          if (touches) {
            kept = value >= old_worst[1] && min_window_dihedral_sine(a, b, c, d, obtuse_scale_) >= held_sine;
          } else {
            worst = std::min(worst, value);
            kept = worst > best;
          }
          if (!kept) break;
          new_bad[touches ? 1 : 0] += dihedral_outside(a, b, c, d, low_, high_) ? 1 : 0;
        }
        if (!kept || new_bad[0] > old_bad[0] || new_bad[1] > old_bad[1]) continue;
        best = worst;
        contraction_ = trial_;
        found = true;
      }
      if (!found) continue;
      commit_contraction(mesh_, contraction_, created_);
      clock_.mark(std::span<const std::uint32_t>(&v, 1));  // v has no star now
      state_.vertices[v].kind = VertexKind::Unused;
      // The stage's Steiner count is net: a vertex this stage inserted and deleted again
      // is not in the output.
      if (v >= first_new_vertex_) --state_.stage_steiner;
      adopt(region);
      return true;
    }
    return false;
  }

  /// Raw minimum dihedral sine of a star tet with the moving vertex at p (no bounds).
  double min_dihedral_sine_at(const StarTet& s, const Vec3& p) const {
    std::array<Vec3, 4> q = s.p;
    q[s.local] = p;
    return min_window_dihedral_sine(q[0], q[1], q[2], q[3], obtuse_scale_);
  }

  RefineState& state_;
  TetMesh& mesh_;
  ImprovementTarget target_;
  double low_, high_;
  double obtuse_scale_;  ///< window_obtuse_scale of the window (toolkit/quality)
  double radius_edge_bound_;
  bool any_volume_bound_;
  std::uint32_t first_new_vertex_;  ///< vertices from here on were inserted by this pass
  /// small_angle_vertices at the start of the pass (empty without small-angle holds).
  std::vector<std::uint8_t> at_small_angle_;
  std::size_t held_moves_ = 0;  ///< smoothing moves made under small-angle holds
  std::size_t relaxed_held_moves_ = 0;  ///< of those, with relaxed holds
  std::size_t traded_moves_ = 0;  ///< of those, with trade holds (hold_for_trade)
  std::size_t pulled_back_trades_ = 0;  ///< of those, at a point pulled back (pulled_back)
  /// The smallest and largest dihedral angles of the tets touching a small angle when the
  /// trades start (trade_extremes): no trade takes such a tet beyond them.
  double trade_min_deg_ = 180.0, trade_max_deg_ = 0.0;
  std::size_t breaker_held_moves_ = 0;  ///< of those, holding a bound breaker inside the window by its angles
  std::size_t polish_insertions_ = 0;  ///< vertex insertions made by the polish
  std::set<std::array<std::uint32_t, 4>> polish_insertions_tried_;  ///< sorted vertices
  std::size_t polish_flips_ = 0;  ///< flips made by the polish
  std::size_t holder_removals_ = 0;  ///< of which edge removals at holders (polish_holder_removals)
  std::set<std::array<std::uint32_t, 4>> polish_flips_tried_;  ///< sorted vertices
  std::vector<std::uint32_t> holders_;  ///< polish_holder_removals' tets
  std::vector<Vec3> small_points_;     ///< try_remove_edge's ring points touching a small angle
  std::size_t polish_deletions_ = 0;  ///< vertex deletions made by the polish
  std::size_t joint_moves_ = 0;  ///< joint moves made in the trade rounds (polish_joint_moves)
  FailureRecords joint_failed_;  ///< per tet slot, polish_joint_moves
  std::size_t neighbour_joint_moves_ = 0;  ///< joint moves made by polish_neighbour_joint_moves
  FailureRecords neighbour_joint_failed_;  ///< per tet slot, polish_neighbour_joint_moves
  std::vector<std::pair<std::uint32_t, std::uint32_t>> neighbour_pairs_;
  std::vector<std::uint32_t> neighbourhood_;
  std::size_t flip_trades_ = 0;  ///< flip trades made (polish_flip_trades)
  FailureRecords flip_trade_failed_;  ///< per tet slot, polish_flip_trades
  JointMove joint_;
  std::set<std::array<std::uint32_t, 4>> polish_deletions_tried_;  ///< sorted vertices

  std::vector<std::uint32_t> bad_, work_, vertices_, touched_, polish_tets_;
  ChangeClock clock_;
  FailureRecords flips_failed_, deletion_failed_;  ///< per tet slot
  FailureRecords smoothing_failed_;                ///< per vertex
  FailureRecords polish_failed_;                   ///< per vertex, smoothing in polish()
  FailureRecords trade_failed_;                    ///< per vertex, smoothing with trades (trade_rounds)
  bool trading_ = false;  ///< smooth_vertex may trade (trade_rounds)
  bool trades_started_ = false;  ///< trade_rounds ran its rounds
  std::vector<std::uint32_t> cavity_, outside_, kept_vertices_;
  std::vector<Vec3> candidates_;
  std::vector<std::uint64_t> kept_edges_;
  std::vector<std::array<std::uint32_t, 4>> quads_;
  std::vector<std::uint32_t> ring_tets_, ring_, created_;
  std::vector<std::uint32_t> star_;
  std::vector<StarTet> star_tets_, sorted_;
  std::vector<double> values_, current_values_;
  std::vector<std::pair<double, std::size_t>> order_;
  std::vector<Vec3> gradients_;
  std::vector<std::uint32_t> neighbors_;
  Contraction trial_, contraction_;
  FacetEdgeFlip facet_flip_;
  std::vector<std::uint32_t> facets_;
  std::vector<HullCheck> hull_checks_;
  Freedom freedom_ = Freedom::Free;
  Vec3 origin_ = Vec3::Zero(), direction_ = Vec3::Zero(), span_ = Vec3::Zero();
  int axis_aligned_ = -1;
};

}  // namespace

void init_sliver_budget(RefineState& state) {
  state.sliver_splits_left =
      static_cast<std::size_t>(kSliverSplitsPerVertex * static_cast<double>(state.mesh.num_vertices()));
}

bool take_sliver_split(RefineState& state) {
  if (state.sliver_splits_left == 0) return false;
  --state.sliver_splits_left;
  return true;
}

ImprovementStats improve_slivers(RefineState& state) {
  ImprovementTarget target;
  target.min_dihedral_deg = state.options.min_dihedral_deg;
  target.max_dihedral_deg = state.options.max_dihedral_deg;
  return improve_slivers(state, target);
}

ImprovementStats improve_slivers(RefineState& state, const ImprovementTarget& target) {
  Improver improver(state, target);
  const ImprovementStats stats = improver.run();
  log(state.options.log, LogLevel::Info,
      "mesh: slivers " + std::to_string(stats.bad_before) + " -> " + std::to_string(stats.bad_after) +
          " tets outside the dihedral window (" + std::to_string(stats.edge_removals) + " edge removals, " +
          std::to_string(stats.flips23) + " 2-3 flips, " + std::to_string(stats.vertex_moves) + " vertex moves (" +
          std::to_string(stats.held_moves) + " under small-angle holds, " + std::to_string(stats.relaxed_held_moves) +
          " relaxed, " + std::to_string(stats.traded_moves) + " trading (" + std::to_string(stats.pulled_back_trades) + " pulled back), " + std::to_string(stats.joint_moves) + " joint of " + std::to_string(stats.joint_tries) + " tries, " + std::to_string(stats.neighbour_joint_moves) + " with a neighbour of " + std::to_string(stats.neighbour_joint_tries) + " tries, " + std::to_string(stats.flip_trades) + " flip trades of " + std::to_string(stats.flip_trade_tries) + " tries, " + std::to_string(stats.breaker_held_moves) + " holding bound breakers by their angles), " + std::to_string(stats.insertions) + " vertex insertions (" +
          std::to_string(stats.polish_insertions) + " in the polish), " + std::to_string(stats.deletions) +
          " vertex deletions (" + std::to_string(stats.polish_deletions) + " in the polish), " +
          std::to_string(stats.facet_edge_flips) + " facet edge flips, " + std::to_string(stats.polish_flips) +
          " flips in the polish (" + std::to_string(stats.holder_removals) + " at holders), " +
          std::to_string(stats.passes) + " passes, " + std::to_string(stats.tries) + " tries, " +
          std::to_string(stats.polish_tries) + " polish tries)");
  return stats;
}

}  // namespace delmesh::tet3d
