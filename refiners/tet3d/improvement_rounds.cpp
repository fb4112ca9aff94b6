// Rounds of the improvement pass (see improvement_rounds.h; notes §2.2.4).
#include "refiners/tet3d/improvement_rounds.h"

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "refiners/tet3d/deferred_split.h"
#include "refiners/tet3d/subfacet_insertion.h"
#include "refiners/tet3d/subsegment_insertion.h"
#include "toolkit/core/log.h"

namespace delmesh::tet3d {

namespace {

/// Adds the moves, passes and tries of `round` to `total`.
void add_round(ImprovementStats& total, const ImprovementStats& round) {
  total.flips23 += round.flips23;
  total.edge_removals += round.edge_removals;
  total.vertex_moves += round.vertex_moves;
  total.held_moves += round.held_moves;
  total.relaxed_held_moves += round.relaxed_held_moves;
  total.joint_moves += round.joint_moves;
  total.joint_tries += round.joint_tries;
  total.neighbour_joint_moves += round.neighbour_joint_moves;
  total.neighbour_joint_tries += round.neighbour_joint_tries;
  total.breaker_held_moves += round.breaker_held_moves;
  total.insertions += round.insertions;
  total.polish_insertions += round.polish_insertions;
  total.deletions += round.deletions;
  total.polish_deletions += round.polish_deletions;
  total.polish_flips += round.polish_flips;
  total.holder_removals += round.holder_removals;
  total.facet_edge_flips += round.facet_edge_flips;
  total.passes += round.passes;
  total.tries += round.tries;
  total.polish_tries += round.polish_tries;
  total.bad_after = round.bad_after;
}

}  // namespace

ImprovementStats improve_in_rounds(RefineState& state) {
  // The vertices from first_vertex on are the rounds' own: a later round may delete a
  // vertex an earlier one inserted, which the later round's count does not know as its own.
  const std::uint32_t first_vertex = state.mesh.num_vertices();
  const std::size_t steiner_before = state.stage_steiner;
  ImprovementStats total = improve_slivers(state);
  // The later rounds: the polish alone (no tries for the passes' steps).
  ImprovementTarget polish_only;
  polish_only.min_dihedral_deg = state.options.min_dihedral_deg;
  polish_only.max_dihedral_deg = state.options.max_dihedral_deg;
  polish_only.tries_per_bad_tet = 0;
  int rounds = 1;
  std::size_t left = total.bad_after;
  while (rounds < kMaxImprovementRounds && left > 0) {
    const ImprovementStats round = improve_slivers(state, polish_only);
    ++rounds;
    add_round(total, round);
    if (round.bad_after >= left) break;
    left = round.bad_after;
  }
  // Vertices on the subfacets and subsegments of the tets left, then the polish once more
  // around them, at most kInsertionRounds times while any is inserted. `away` is the
  // number of tets the insertions on subsegments could try, known where the mesh has not
  // changed since they counted them.
  std::size_t away = std::numeric_limits<std::size_t>::max();
  for (int k = 0; k < kInsertionRounds && left > 0; ++k) {
    const std::size_t on_subfacets = insert_on_subfacets(state);
    std::vector<std::array<std::uint32_t, 4>> tried;
    const std::size_t on_subsegments = insert_on_subsegments(state, SubsegmentJudgement::AtInsertion, &tried);
    if (on_subfacets + on_subsegments == 0) {
      away = tried.size();
      break;
    }
    log(state.options.log, LogLevel::Info,
        "mesh: slivers: " + std::to_string(on_subfacets) + " vertices inserted on subfacets, " +
            std::to_string(on_subsegments) + " on subsegments");
    const ImprovementStats round = improve_slivers(state, polish_only);
    ++rounds;
    add_round(total, round);
    left = round.bad_after;
  }
  // Splits judged after the polish that follows them, undone where the mesh is worse
  // (deferred_split.h), while they are kept; the splits at every tet together only until
  // they are refused once.
  bool together = true;
  for (int k = 0; k < kDeferredSplitRounds && left > 0 && away > 0; ++k) {
    const std::optional<ImprovementStats> round = split_then_polish(state, polish_only, together);
    if (!round) break;
    log(state.options.log, LogLevel::Info, "mesh: slivers: subsegment splits kept after the polish");
    ++rounds;
    add_round(total, *round);
    left = round->bad_after;
  }
  std::size_t kept = 0;
  for (std::uint32_t v = first_vertex; v < state.mesh.num_vertices(); ++v)
    if (state.vertices[v].kind != VertexKind::Unused) ++kept;
  state.stage_steiner = steiner_before + kept;
  log(state.options.log, LogLevel::Info,
      "mesh: slivers: " + std::to_string(rounds) + " rounds, " + std::to_string(total.bad_before) + " tets outside the window before, " +
          std::to_string(total.bad_after) + " after");
  return total;
}

}  // namespace delmesh::tet3d
