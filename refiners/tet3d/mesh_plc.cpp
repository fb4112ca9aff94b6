// The mesh_plc driver (see mesh_plc.h): preparation and Delaunay tetrahedralization,
// segment recovery, facet recovery, domain marking, quality refinement, extraction, with
// the time and Steiner points of each stage.
#include "refiners/tet3d/mesh_plc.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/ccdt_facet_recovery.h"
#include "refiners/tet3d/default_improvement.h"
#include "refiners/tet3d/domain_marking.h"
#include "refiners/tet3d/flat_facet_tets.h"
#include "refiners/tet3d/improvement_rounds.h"
#include "refiners/tet3d/plc_preparation.h"
#include "refiners/tet3d/progress_report.h"
#include "refiners/tet3d/quality_bound.h"
#include "refiners/tet3d/quality_refinement.h"
#include "refiners/tet3d/radius_edge_polish.h"
#include "refiners/tet3d/recovery_limit.h"
#include "refiners/tet3d/refine_state.h"
#include "refiners/tet3d/result_extraction.h"
#include "refiners/tet3d/sliver_improvement.h"
#include "refiners/tet3d/small_angles.h"
#include "refiners/tet3d/unmet_tets.h"
#include "refiners/tet3d/volume_bound.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/core/holding_log_sink.h"

namespace delmesh {

namespace {

class StageTimer {
 public:
  StageTimer(MeshStats& stats, tet3d::RefineState& state) : stats_(stats), state_(state) { restart(); }
  /// Starts the next stage's clock and counters here (what ran since the last stage
  /// belongs to no stage).
  void restart() {
    start_ = std::chrono::steady_clock::now();
    state_.stage_steiner = 0;
    state_.stage_segment_splits = {};
  }
  void finish(const char* name) {
    const auto now = std::chrono::steady_clock::now();
    stats_.stages.push_back({name, std::chrono::duration<double>(now - start_).count(), state_.stage_steiner});
    stats_.stages.back().segment_splits = state_.stage_segment_splits;
    log(state_.options.log, LogLevel::Info,
        std::string("mesh: ") + name + " " + std::to_string(stats_.stages.back().seconds) + " s, " +
            std::to_string(state_.stage_steiner) + " Steiner points");
    restart();
  }

 private:
  MeshStats& stats_;
  tet3d::RefineState& state_;
  std::chrono::steady_clock::time_point start_;
};

bool changed_mesh(const tet3d::ImprovementStats& stats) {
  return stats.flips23 + stats.edge_removals + stats.vertex_moves + stats.insertions + stats.deletions +
             stats.facet_edge_flips >
         0;
}

/// Queues every subfacet, in the order of their keys (the table's iteration order follows
/// its hashing, not the input).
void queue_every_subface(tet3d::RefineState& state) {
  for (const auto& [key, facet] : state.subfaces) state.subface_queue.push_back({key});
  std::sort(state.subface_queue.begin(), state.subface_queue.end(),
            [](const tet3d::SubfaceTask& x, const tet3d::SubfaceTask& y) { return x.face > y.face; });
}

}  // namespace

/// mesh_plc for one segment recovery rule.
static Expected<MeshResult> mesh_plc_with(const Plc& plc, const MeshOptions& options) {
  if (options.quality && !(options.max_radius_edge >= 1.0))
    return make_error(ErrorCode::InvalidOption, "the radius-edge bound must be at least 1");
  // Every tet has a dihedral angle at most and one at least arccos(1/3) ~ 70.53 degrees.
  if (!(options.min_dihedral_deg >= 0.0 && options.min_dihedral_deg < 70.0) ||
      !(options.max_dihedral_deg > 71.0 && options.max_dihedral_deg <= 180.0))
    return make_error(ErrorCode::InvalidOption, "the dihedral angle targets must lie in [0, 70) and (71, 180] degrees");
  const bool strong = options.segment_recovery == SegmentRecovery::StronglyDelaunay;
  MeshResult result;
  result.stats.input_vertices = plc.points.size();
  result.stats.input_facets = plc.facets.size();

  // The refinement's log lines pass through a sink that can hold them back while a trial
  // runs, until it is kept (deferred_split.h); progress lines go straight out.
  HoldingLogSink run_log(options.log);
  MeshOptions run_options = options;
  if (options.log) run_options.log = &run_log;
  // Held by pointer so that it is freed as soon as the result is extracted: the result
  // check of refinement on the CCDT below builds arrays of the result's faces, which
  // would otherwise sit on top of the whole refinement state (the peak of the run).
  auto owned_state = std::make_unique<tet3d::RefineState>(plc, run_options);
  tet3d::RefineState& state = *owned_state;
  if (options.log) state.log_hold = &run_log;
  tet3d::ProgressReporter progress(options);
  state.progress = &progress;
  StageTimer timer(result.stats, state);
  progress.begin_stage("delaunay", state);
  if (auto ok = tet3d::prepare_plc(state); !ok) return ok.error();
  result.stats.input_segments = state.segments.size();
  const bool dihedral_target = options.min_dihedral_deg > 0.0 || options.max_dihedral_deg < 180.0;
  const bool refine = options.quality || tet3d::any_volume_bound(state) || dihedral_target;
  // Strongly Delaunay segments leave encroached subsegments, which conforming facet
  // recovery would split again: the facets are recovered as a CCDT.
  const bool ccdt = strong || options.facet_recovery == FacetRecovery::Ccdt ||
                    (options.facet_recovery == FacetRecovery::Auto && !refine);
  timer.finish("delaunay");
  progress.begin_stage("segments", state);
  state.recovery_limit = tet3d::recovery_vertex_limit(state);

  if (auto ok = tet3d::restore_conformity(state, true); !ok) return ok.error();
  timer.finish("segments");
  progress.begin_stage("facets", state);

  if (ccdt) {
    auto counts = tet3d::recover_facets_ccdt(state);
    if (!counts) return counts.error();
    result.stats.ccdt = {true,
                         counts->regions,
                         counts->recovered_regions,
                         counts->failed_regions,
                         counts->fallback_facets,
                         counts->enlargements,
                         counts->cocircular_flips};
  } else {
    queue_every_subface(state);
    if (auto ok = tet3d::restore_conformity(state, false); !ok) {
      if (options.facet_recovery != FacetRecovery::Auto || ok.error().code != ErrorCode::Unsupported)
        return ok.error();
      // The conforming recovery stopped at its bound (features nearly touching across
      // exterior space need ever smaller splits there): start again with a CCDT, whose
      // refinement ignores exterior tets (notes §3.5.1, §4.2.1 last paragraph).
      log(options.log, LogLevel::Warning,
          "mesh: conforming facet recovery stopped (" + ok.error().message +
              "); meshing again with facets recovered as a conforming CDT");
      MeshOptions again = options;
      again.facet_recovery = FacetRecovery::Ccdt;
      auto rerun = mesh_plc(plc, again);
      if (rerun) rerun->stats.ccdt.after_conforming = true;
      return rerun;
    }
  }
  state.recovery_limit = std::numeric_limits<std::size_t>::max();
  // Boundary recovery can queue far more elements at once than refinement does later:
  // give the emptied queues' memory back.
  state.subsegment_queue.shrink_to_fit();
  state.subface_queue.shrink_to_fit();
  timer.finish("facets");
  progress.begin_stage("domain", state);

  tet3d::mark_domain(state);
  timer.finish("domain");

  if (refine) {
    progress.begin_stage("quality", state);
    if (ccdt) {
      // Refinement on the CCDT: constrained insertions from here on, and the subsegments
      // and subfacets that vertices of domain tets encroach split first (notes §2.1.7).
      state.constrained = true;
      queue_every_subface(state);
      for (const auto& [key, segment] : state.subsegments)
        state.subsegment_queue.push_back({static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key)});
      std::sort(state.subsegment_queue.begin(), state.subsegment_queue.end(),
                [](const tet3d::SubsegmentTask& x, const tet3d::SubsegmentTask& y) {
                  return tet3d::edge_key(x.a, x.b) > tet3d::edge_key(y.a, y.b);
                });
      // Bounded: the conforming splits of subfacets a constrained split leaves missing
      // could cascade; past the quality stage's own bound the run ends with an error.
      state.recovery_limit = state.mesh.num_vertices() + tet3d::quality_steiner_bound(state);
      if (auto ok = tet3d::restore_conformity(state, false); !ok) return ok.error();
      // Every subfacet was queued above: give the drained queues' memory back before
      // the mesh grows.
      state.subsegment_queue.shrink_to_fit();
      state.subface_queue.shrink_to_fit();
      tet3d::mark_domain(state);
    }
    tet3d::init_sliver_budget(state);
    auto outcome = tet3d::refine_quality(state, plc.points.size());
    if (!outcome) return outcome.error();
    result.stats.budget_exhausted = outcome->budget_exhausted;
    result.stats.quality_bound_reached = outcome->bound_reached;
    // Quality refinement keeps the marks exact (domain_marking.h); marking the final
    // mesh from scratch costs one flood fill and does not depend on that.
    if (ccdt) {
      // Never a mesh whose boundary lost a subfacet (the domain's flood would leak).
      std::size_t missing = 0;
      for (const auto& [key, facet] : state.subfaces)
        if (!tet3d::find_face_ref(state, key[0], key[1], key[2])) ++missing;
      if (missing > 0)
        return make_error(ErrorCode::Unsupported, "refinement on the CCDT left " + std::to_string(missing) +
                                                      " subfacets missing: use --facet-recovery conforming");
      state.recovery_limit = std::numeric_limits<std::size_t>::max();
    }
    tet3d::mark_domain(state);
    result.stats.ccdt.cavity_shrinks = state.cavity_shrinks;
    result.stats.ccdt.cavity_rejections = state.cavity_rejections;
    // A shrunk cavity leaves tets whose circumspheres hold the new vertex and that see it:
    // the mesh is no longer constrained Delaunay (check_mesh found 37 such faces on
    // cgal-fandisk with 1338 shrunk cavities).
    if (state.cavity_shrinks > 0) result.constrained_delaunay = false;
    timer.finish("quality");
  }
  const bool improve = dihedral_target || (refine && options.improve);
  const double low = dihedral_target ? options.min_dihedral_deg : tet3d::kDefaultMinDihedralDeg;
  const double high = dihedral_target ? options.max_dihedral_deg : 180.0;
  if (improve) {
    // Flips and smoothing: the mesh is no longer Delaunay from here on. With a dihedral
    // target the window's tets, else the default improvement's (default_improvement.h:
    // tets below 10 degrees, never a new tet above the bounds).
    progress.begin_stage("slivers", state);
    // Flat tets lying on a facet first: left in place they are the worst tet of every star
    // and ring around them, which freezes smoothing of their vertices.
    std::size_t released = tet3d::release_flat_facet_tets(state, low, high);
    const tet3d::ImprovementStats stats =
        dihedral_target ? tet3d::improve_in_rounds(state) : tet3d::improve_default(state);
    if (changed_mesh(stats)) result.constrained_delaunay = false;
    released += tet3d::release_flat_facet_tets(state, low, high);
    // On a CCDT without a dihedral target, those the default improvement left lying on two
    // subfacets (flat_facet_tets.h), by edge removal: after the pass, whose trajectory it
    // would change, never adding a tet above the bounds.
    const std::size_t removed =
        state.constrained && !dihedral_target ? tet3d::remove_flat_boundary_tets(state, low, high) : 0;
    if (released + removed > 0) {
      result.constrained_delaunay = false;
      log(state.options.log, LogLevel::Info,
          "mesh: slivers: " + std::to_string(released) + " flat tets lying on a facet released, " +
              std::to_string(removed) + " lying on two subfacets removed");
    }
    timer.finish("slivers");
  }
  tet3d::release_lookup_tables(state);
  {
    const std::vector<std::uint8_t> small_angle = tet3d::small_angle_tets(state);
    if (improve && options.quality) {
      // The tets the improvement left above the radius-edge bound away from small angles:
      // their interior vertices moved where that lifts them (radius_edge_polish.h; vertex
      // moves only, so the small-angle marks stay valid). A stage of its own, "polish":
      // its objective is the radius-edge ratio, not the dihedral angles of "slivers".
      progress.begin_stage("polish", state);
      timer.restart();
      const tet3d::RadiusEdgePolishStats polish = tet3d::polish_radius_edge(state, small_angle, low, high);
      if (polish.moves > 0) result.constrained_delaunay = false;
      log(state.options.log, LogLevel::Info,
          "mesh: radius-edge polish: " + std::to_string(polish.moves) +
              " vertices moved, tets above the bound away from small angles " + std::to_string(polish.tets_before) +
              " -> " + std::to_string(polish.tets_after));
      timer.finish("polish");
    }
    tet3d::count_unmet(state, small_angle, result.stats);
    if (refine && (result.stats.unmet_tets > 0 || result.stats.budget_exhausted)) result.status = MeshStatus::Partial;
    tet3d::extract_result(state, small_angle, result);
  }
  owned_state.reset();
  if (ccdt && refine) {
    // Refinement on the CCDT is new and its cavities only approximately constrained
    // Delaunay: the result is checked against the input (check_mesh without the Delaunay
    // test, as `--check` runs when the mesh is not constrained Delaunay) and never
    // returned invalid (occt-tr12j gave a boundary face outside its facet's polygon).
    CheckMeshOptions check;
    check.check_delaunay = false;
    check.max_issues = 1;
    const auto issues = check_mesh(result.mesh, plc, result.boundary_face_facets, check);
    if (!issues.empty())
      return make_error(ErrorCode::Unsupported, "refinement on the CCDT gave an invalid mesh (" +
                                                    issues.front().message + "): use --facet-recovery conforming");
  }
  return result;
}

Expected<MeshResult> mesh_plc(const Plc& plc, const MeshOptions& options) {
  if (options.segment_recovery != SegmentRecovery::StronglyDelaunay) return mesh_plc_with(plc, options);
  if (options.facet_recovery == FacetRecovery::Conforming)
    return make_error(ErrorCode::InvalidOption,
                      "strongly Delaunay segment recovery needs facets recovered as a CCDT, not conforming");
  auto result = mesh_plc_with(plc, options);
  if (result || result.error().code != ErrorCode::Unsupported) return result;
  log(options.log, LogLevel::Warning,
      "mesh: refinement after strongly Delaunay segment recovery stopped (" + result.error().message +
          "); meshing again with diametral segment recovery");
  MeshOptions again = options;
  again.segment_recovery = SegmentRecovery::Diametral;
  auto rerun = mesh_plc_with(plc, again);
  if (rerun) rerun->stats.strong_segments_fell_back = true;
  return rerun;
}

}  // namespace delmesh
