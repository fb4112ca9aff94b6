// Subsegment splits judged after the polish (see deferred_split.h; notes §2.2.4, §4.4).
#include "refiners/tet3d/deferred_split.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "refiners/tet3d/quality_refinement.h"
#include "refiners/tet3d/small_angles.h"
#include "refiners/tet3d/state_snapshot.h"
#include "refiners/tet3d/subsegment_insertion.h"
#include "refiners/tet3d/unmet_tets.h"
#include "toolkit/core/holding_log_sink.h"
#include "toolkit/core/str_cat.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::tet3d {

namespace {

/// What the judgement of a trial compares over the in-domain tets.
struct MeshTally {
  std::size_t outside_elsewhere = 0;  ///< outside the window, touching no small angle
  std::size_t outside_at_small = 0;   ///< outside the window, touching one
  std::size_t above_bounds = 0;       ///< above the radius-edge or volume bound
  /// The extreme dihedral angles: of the whole mesh for the tally before a trial, of the
  /// tets the trial changed for the tally after it (see tally_after).
  double min_deg = 180.0, max_deg = 0.0;
};

/// The classes a tet is counted in, as bits (0 for a tet outside the domain).
enum TetClass : std::uint8_t { kOutsideElsewhere = 1, kOutsideAtSmall = 2, kAboveBounds = 4 };

/// Classifies the in-domain tets of a state as count_unmet (unmet_tets.h) counts them.
class TetClassifier {
 public:
  explicit TetClassifier(const RefineState& state)
      : state_(state), small_(small_angle_tets(state)) {}

  /// Whether slot t holds a finite in-domain tet (the only tets a tally counts).
  bool counted(std::uint32_t t) const {
    const TetMesh& mesh = state_.mesh;
    return t < mesh.tet_slots() && !mesh.is_dead(t) && !mesh.is_infinite(t) && t < state_.tet_region.size() &&
           in_domain(state_.tet_region[t]);
  }

  /// The classes of the counted tet t, added to `tally` with its extreme angles.
  std::uint8_t add(std::uint32_t t, MeshTally& tally) const {
    const MeshOptions& options = state_.options;
    const auto& v = state_.mesh.tet(t).v;
    const Vec3 &a = state_.mesh.point(v[0]), &b = state_.mesh.point(v[1]), &c = state_.mesh.point(v[2]),
               &d = state_.mesh.point(v[3]);
    const auto [low, high] = dihedral_extremes_deg(a, b, c, d);
    tally.min_deg = std::min(tally.min_deg, low);
    tally.max_deg = std::max(tally.max_deg, high);
    std::uint8_t classes = 0;
    if (outside_dihedral_window(a, b, c, d, options.min_dihedral_deg, options.max_dihedral_deg))
      classes |= small_[t] != 0 ? kOutsideAtSmall : kOutsideElsewhere;
    bool above = options.quality && !(radius_edge_ratio(a, b, c, d) <= options.max_radius_edge);
    if (!above) above = misses_volume_bound(state_, state_.tet_region[t], a, b, c, d);
    if (above) classes |= kAboveBounds;
    tally.outside_elsewhere += (classes & kOutsideElsewhere) != 0;
    tally.outside_at_small += (classes & kOutsideAtSmall) != 0;
    tally.above_bounds += (classes & kAboveBounds) != 0;
    return classes;
  }

 private:
  const RefineState& state_;
  const std::vector<std::uint8_t> small_;
};

/// The tally of every in-domain tet of `state`, and each slot's classes into `classes`.
MeshTally tally(const RefineState& state, std::vector<std::uint8_t>& classes) {
  const TetClassifier classifier(state);
  MeshTally result;
  classes.assign(state.mesh.tet_slots(), 0);
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t)
    if (classifier.counted(t)) classes[t] = classifier.add(t, result);
  return result;
}

/// Whether vertex x of `now` is the vertex x of `then`: at the same point, with the same
/// record (kind, owner, floors), so every tet of its star is judged as before.
bool same_vertex(const TetMesh& then, const MappedArray<VertexInfo>& then_info, const TetMesh& now,
                 const MappedArray<VertexInfo>& now_info, std::uint32_t x) {
  if (x >= then.num_vertices() || x >= then_info.size()) return false;
  const VertexInfo &a = then_info[x], &b = now_info[x];
  return then.point(x) == now.point(x) && a.floor == b.floor && a.field_floor == b.field_floor &&
         a.owner == b.owner && a.kind == b.kind && a.small_angle == b.small_angle;
}

/// The tally of `state` after a trial made from the state `snapshot` copied, whose tally
/// was `before` and the slots' classes `classes`. A tet is unchanged when its slot holds
/// the same four vertices in the same region, none of them moved or re-recorded: its
/// classes are then those it had (the small-angle rules read only the tet's vertices,
/// small_angles.h; the bounds and angles only its corners and region). So the counts are
/// before's less the classes of the changed slots' old tets plus their new tets', which
/// is the whole mesh's tally; the extremes are those of the changed slots' new tets only,
/// and the whole mesh's extremes stay within before's exactly when those do (the
/// unchanged tets lie within before's).
MeshTally tally_after(const RefineState& state, const StateSnapshot& snapshot,
                      const std::vector<std::uint8_t>& classes, const MeshTally& before) {
  const TetMesh &then = snapshot.mesh(), &now = state.mesh;
  std::vector<std::uint8_t> moved(now.num_vertices(), 0);
  for (std::uint32_t x = 0; x < now.num_vertices(); ++x)
    moved[x] = !same_vertex(then, snapshot.vertices(), now, state.vertices, x);
  const TetClassifier classifier(state);
  MeshTally added, removed;
  const std::uint32_t slots = std::max(then.tet_slots(), now.tet_slots());
  for (std::uint32_t t = 0; t < slots; ++t) {
    const bool was = t < then.tet_slots() && !then.is_dead(t);
    const bool is = t < now.tet_slots() && !now.is_dead(t);
    if (!was && !is) continue;
    if (was && is && then.tet(t).v == now.tet(t).v && snapshot.tet_region()[t] == state.tet_region[t]) {
      const auto& v = now.tet(t).v;
      if (!moved[v[0]] && !moved[v[1]] && !moved[v[2]] && !moved[v[3]]) continue;
    }
    if (was && t < classes.size()) {
      removed.outside_elsewhere += (classes[t] & kOutsideElsewhere) != 0;
      removed.outside_at_small += (classes[t] & kOutsideAtSmall) != 0;
      removed.above_bounds += (classes[t] & kAboveBounds) != 0;
    }
    if (is && classifier.counted(t)) classifier.add(t, added);
  }
  MeshTally result = added;
  result.outside_elsewhere = before.outside_elsewhere + added.outside_elsewhere - removed.outside_elsewhere;
  result.outside_at_small = before.outside_at_small + added.outside_at_small - removed.outside_at_small;
  result.above_bounds = before.above_bounds + added.above_bounds - removed.above_bounds;
  return result;
}

/// The part of the judgement against the polish alone (`polished`): fewer tets outside
/// the window away from small angles than it leaves, no more outside at small angles and
/// no more above the bounds.
bool beats_polish_alone(const MeshTally& after, const MeshTally& polished) {
  return after.outside_elsewhere < polished.outside_elsewhere && after.outside_at_small <= polished.outside_at_small &&
         after.above_bounds <= polished.above_bounds;
}

/// The part of the judgement against the state before the trial: fewer tets outside the
/// window away from small angles, and its extreme dihedral angles.
bool better_than_before(const MeshTally& after, const MeshTally& before) {
  return after.outside_elsewhere < before.outside_elsewhere && after.min_deg >= before.min_deg &&
         after.max_deg <= before.max_deg;
}

/// The tets within `rings` rings of `centres`: the stars of the centres, then the stars
/// of the vertices of those tets, and so on (the infinite vertex's star aside).
std::vector<std::uint32_t> tets_around(TetMesh& mesh, const std::vector<std::uint32_t>& centres, int rings) {
  std::vector<std::uint8_t> seen(mesh.num_vertices(), 0);
  std::vector<std::uint32_t> frontier, next, star, tets;
  for (const std::uint32_t x : centres)
    if (!seen[x]) {
      seen[x] = 1;
      frontier.push_back(x);
    }
  for (int ring = 0; ring < rings; ++ring) {
    next.clear();
    for (const std::uint32_t x : frontier) {
      if (x == kInfiniteVertex) continue;
      mesh.star(x, star);
      for (const std::uint32_t t : star) {
        tets.push_back(t);
        for (const std::uint32_t y : mesh.tet(t).v)
          if (!seen[y]) {
            seen[y] = 1;
            next.push_back(y);
          }
      }
    }
    frontier.swap(next);
  }
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
  return tets;
}

/// The polish after a trial's splits or alone: from every bad tet of the mesh for the
/// splits at every tet together (`only` == BoundaryInserter::kEveryTet), else from the bad
/// tets within kTrialPolishRings rings of the tried tet's vertices and of the vertices
/// from `first_new` on (the splits' new vertices).
ImprovementStats polish_after(RefineState& state, const ImprovementTarget& polish,
                              const std::vector<std::array<std::uint32_t, 4>>& bad, std::size_t only,
                              std::uint32_t first_new) {
  if (only == BoundaryInserter::kEveryTet) return improve_slivers(state, polish);
  std::vector<std::uint32_t> centres(bad[only].begin(), bad[only].end());
  for (std::uint32_t x = first_new; x < state.mesh.num_vertices(); ++x) centres.push_back(x);
  const std::vector<std::uint32_t> start = tets_around(state.mesh, centres, kTrialPolishRings);
  ImprovementTarget local = polish;
  local.start_tets = &start;
  return improve_slivers(state, local);
}

}  // namespace

std::optional<ImprovementStats> split_then_polish(RefineState& state, const ImprovementTarget& polish,
                                                  bool& together) {
  std::vector<std::uint8_t> classes;
  const MeshTally before = tally(state, classes);
  if (before.outside_elsewhere == 0) return std::nullopt;
  const StateSnapshot snapshot(state);
  std::vector<std::array<std::uint32_t, 4>> bad;
  bool split = false;
  {
    // The lines of this first try never go out: it only finds the tets and whether any
    // split is made.
    const LogHold probe_log(state.log_hold);
    split = insert_on_subsegments(state, SubsegmentJudgement::AfterPolish, &bad) > 0;
  }
  // Put back in every case: without a split, the tries still prepared cavities (the
  // location walk's state among them).
  snapshot.restore(state);
  if (!split) return std::nullopt;
  // The splits at every tet together (unless refused in an earlier trial), then, where
  // more than one tet was tried, at each tet alone.
  std::vector<std::size_t> trials;
  if (together) trials.push_back(BoundaryInserter::kEveryTet);
  for (std::size_t k = 0; bad.size() > 1 && k < bad.size(); ++k) trials.push_back(k);
  for (const std::size_t only : trials) {
    // The trial's log lines go out only if it is kept; those of the polish alone never
    // (it is only what the splits are judged against).
    LogHold trial_log(state.log_hold);
    if (only != BoundaryInserter::kEveryTet) {
      // Whether the split at this tet alone is made at all, before any polish for it.
      const bool made = insert_on_subsegments(state, SubsegmentJudgement::AfterPolish, nullptr, only) > 0;
      snapshot.restore(state);
      if (!made) continue;
    }
    // The polish alone from the same state (around the same tet for a tet alone), what
    // the splits are judged against (its own trades change the counts at small angles and
    // above the bounds), then the same splits again (the state is the same, so they are)
    // and the polish after them.
    polish_after(state, polish, bad, only, state.mesh.num_vertices());
    const MeshTally polished = tally_after(state, snapshot, classes, before);
    snapshot.restore(state);
    trial_log.discard();
    const std::uint32_t first_new = state.mesh.num_vertices();
    const std::size_t splits = insert_on_subsegments(state, SubsegmentJudgement::AfterPolish, nullptr, only);
    ImprovementStats round = polish_after(state, polish, bad, only, first_new);
    const MeshTally after = tally_after(state, snapshot, classes, before);
    if (better_than_before(after, before) && beats_polish_alone(after, polished)) {
      round.bad_before = before.outside_elsewhere + before.outside_at_small;
      round.bad_after = after.outside_elsewhere + after.outside_at_small;
      trial_log.release();
      return round;
    }
    snapshot.restore(state);
    trial_log.drop();
    log(state.options.log, LogLevel::Info,
        cat("mesh: slivers: subsegment splits undone after the polish (", splits, " splits ",
            only == BoundaryInserter::kEveryTet ? std::string("at every tet") : cat("at tet ", only + 1, " of ", bad.size()),
            "; tets outside the window away from small angles ", before.outside_elsewhere, " before the trial, ",
            polished.outside_elsewhere, " after the polish alone, ", after.outside_elsewhere,
            " after the splits and the polish)"));
    if (only == BoundaryInserter::kEveryTet) together = false;
  }
  return std::nullopt;
}

}  // namespace delmesh::tet3d
