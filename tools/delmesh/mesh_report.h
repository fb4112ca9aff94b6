// What `delmesh mesh` reports about a run: the summary printed on stderr and the same
// figures as the JSON document of --stats. Built from the input PLC's counts, the
// MeshResult (status, MeshStats stages) and a TetQualityReport of the output mesh.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "refiners/tet3d/mesh_plc.h"
#include "toolkit/plc/plc.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::cli {

struct MeshReport {
  std::string input;
  std::string input_format;
  std::size_t input_points = 0;
  std::size_t input_facets = 0;
  std::size_t input_segments = 0;  ///< extra segments (facet polygon edges not counted)
  std::size_t input_regions = 0;
  std::size_t input_holes = 0;

  /// The bounds asked for (quality off: radius_edge_bound is not reported as a target).
  bool quality = false;
  double radius_edge_bound = 2.0;
  InteriorStrategy interior_strategy = InteriorStrategy::Uniform;
  SegmentRecovery segment_recovery = SegmentRecovery::Diametral;
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 180.0;
  double max_volume = -1.0;

  std::size_t vertices = 0;
  std::size_t tets = 0;
  std::size_t boundary_faces = 0;
  std::size_t regions = 0;  ///< distinct region ids among the tets
  MeshStatus status = MeshStatus::Complete;
  MeshStats stats;
  TetQualityReport quality_report;
  /// The same over the tets that touch a small input angle (MeshResult::
  /// tet_at_small_angle) and over the others.
  TetQualityReport quality_at_small_angles;
  TetQualityReport quality_elsewhere;

  double import_seconds = 0.0;
  double mesh_seconds = 0.0;
  double write_seconds = 0.0;
  std::optional<double> check_seconds;       ///< set when --check ran
  std::optional<std::size_t> check_issues;   ///< set when --check ran
  std::vector<std::string> outputs;
};

/// Fills the input, output and quality parts of a report (timings and outputs are the
/// caller's).
MeshReport make_mesh_report(const Plc& plc, const MeshResult& result, const MeshOptions& options);

/// The human-readable summary (several lines, each ending in '\n').
std::string mesh_summary_text(const MeshReport& report);

/// The --stats document.
std::string mesh_stats_json(const MeshReport& report);

}  // namespace delmesh::cli
