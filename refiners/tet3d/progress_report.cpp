// ProgressReporter (see progress_report.h).
#include "refiners/tet3d/progress_report.h"

#include "refiners/tet3d/refine_state.h"

namespace delmesh::tet3d {

ProgressReporter::ProgressReporter(const MeshOptions& options)
    : options_(options),
      enabled_(options.log != nullptr || bool(options.progress)),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void ProgressReporter::begin_stage(const char* stage, const RefineState& state) {
  stage_ = stage;
  report(state);
}

void ProgressReporter::poll_clock(const RefineState& state) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() >= kInterval) report(state);
}

MeshProgress ProgressReporter::snapshot(const RefineState& state) const {
  MeshProgress p;
  p.stage = stage_;
  p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t vertices = state.mesh.num_vertices() > 0 ? state.mesh.num_vertices() - 1 : 0;
  p.vertices = vertices;
  p.tets = state.mesh.num_live_tets();
  p.steiner_points = vertices > state.plc.points.size() ? vertices - state.plc.points.size() : 0;
  p.subsegment_queue = state.subsegment_queue.size();
  p.subfacet_queue = state.subface_queue.size();
  p.tet_queue = state.tet_queue_size;
  return p;
}

void ProgressReporter::report(const RefineState& state) {
  if (!enabled_) return;
  last_ = std::chrono::steady_clock::now();
  const MeshProgress p = snapshot(state);
  if (options_.progress) options_.progress(p);
  if (options_.log) log(options_.log, LogLevel::Progress, describe(p));
}

std::string describe(const MeshProgress& p) {
  std::string text = std::string(p.stage) + ": " + std::to_string(p.vertices) + " vertices, " +
                     std::to_string(p.tets) + " tets, " + std::to_string(p.steiner_points) + " Steiner points";
  if (p.subsegment_queue + p.subfacet_queue + p.tet_queue > 0) {
    text += "; queued " + std::to_string(p.subsegment_queue) + " subsegments, " + std::to_string(p.subfacet_queue) +
            " subfacets, " + std::to_string(p.tet_queue) + " tets";
  }
  return text;
}

}  // namespace delmesh::tet3d
