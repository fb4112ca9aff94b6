// Subsegment splits judged after the polish (see deferred_split.h; notes §2.2.4, §4.4).
#include "refiners/tet3d/deferred_split.h"

#include <algorithm>
#include <cstdint>
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
  double min_deg = 180.0, max_deg = 0.0;  ///< the extreme dihedral angles
};

/// The tally of `state`, counted as count_unmet (unmet_tets.h) counts the result.
MeshTally tally(const RefineState& state) {
  const std::vector<std::uint8_t> small = small_angle_tets(state);
  const MeshOptions& options = state.options;
  MeshTally result;
  for (std::uint32_t t = 0; t < state.mesh.tet_slots(); ++t) {
    if (state.mesh.is_dead(t) || state.mesh.is_infinite(t) || !in_domain(state.tet_region[t])) continue;
    const auto& v = state.mesh.tet(t).v;
    const Vec3 &a = state.mesh.point(v[0]), &b = state.mesh.point(v[1]), &c = state.mesh.point(v[2]),
               &d = state.mesh.point(v[3]);
    const auto [low, high] = dihedral_extremes_deg(a, b, c, d);
    result.min_deg = std::min(result.min_deg, low);
    result.max_deg = std::max(result.max_deg, high);
    if (outside_dihedral_window(a, b, c, d, options.min_dihedral_deg, options.max_dihedral_deg))
      ++(small[t] != 0 ? result.outside_at_small : result.outside_elsewhere);
    bool above = options.quality && !(radius_edge_ratio(a, b, c, d) <= options.max_radius_edge);
    if (!above) above = misses_volume_bound(state, state.tet_region[t], a, b, c, d);
    result.above_bounds += above;
  }
  return result;
}

/// Whether the mesh after the splits and the polish (`after`) is kept: fewer tets outside
/// the window away from small angles than before the trial and than the polish alone
/// (`polished`) leaves, no more outside at small angles and no more above the bounds than
/// the polish alone leaves, and the extreme dihedral angles of before the trial.
bool kept(const MeshTally& after, const MeshTally& polished, const MeshTally& before) {
  return after.outside_elsewhere < before.outside_elsewhere && after.outside_elsewhere < polished.outside_elsewhere &&
         after.outside_at_small <= polished.outside_at_small && after.above_bounds <= polished.above_bounds &&
         after.min_deg >= before.min_deg && after.max_deg <= before.max_deg;
}

}  // namespace

std::optional<ImprovementStats> split_then_polish(RefineState& state, const ImprovementTarget& polish) {
  const MeshTally before = tally(state);
  if (before.outside_elsewhere == 0) return std::nullopt;
  const StateSnapshot snapshot(state);
  // The trial's log lines go out only if it is kept; the polish alone's never (it is
  // only what the splits are judged against).
  LogHold trial_log(state.log_hold);
  const bool split = insert_on_subsegments(state, SubsegmentJudgement::AfterPolish) > 0;
  // Put back in every case: without a split, the tries still prepared cavities (the
  // location walk's state among them).
  snapshot.restore(state);
  if (!split) return std::nullopt;
  // The polish alone from the same state, what the splits are judged against (its own
  // trades change the counts at small angles and above the bounds), then the same splits
  // again (the state is the same, so they are) and the polish after them.
  improve_slivers(state, polish);
  const MeshTally polished = tally(state);
  snapshot.restore(state);
  trial_log.discard();
  const std::size_t splits = insert_on_subsegments(state, SubsegmentJudgement::AfterPolish);
  const ImprovementStats round = improve_slivers(state, polish);
  const MeshTally after = tally(state);
  if (kept(after, polished, before)) {
    trial_log.release();
    return round;
  }
  snapshot.restore(state);
  trial_log.drop();
  log(state.options.log, LogLevel::Info,
      cat("mesh: slivers: subsegment splits undone after the polish (", splits,
          " splits; tets outside the window away from small angles ", before.outside_elsewhere,
          " before the trial, ", polished.outside_elsewhere, " after the polish alone, ", after.outside_elsewhere,
          " after the splits and the polish)"));
  return std::nullopt;
}

}  // namespace delmesh::tet3d
