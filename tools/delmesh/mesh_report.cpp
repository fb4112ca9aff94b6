// Summary text and --stats JSON of `delmesh mesh` (see mesh_report.h).
#include "tools/delmesh/mesh_report.h"

#include <cstdio>
#include <set>
#include <sstream>

#include "refiners/tet3d/interior_strategy.h"
#include "tools/delmesh/json_writer.h"

namespace delmesh::cli {

namespace {

std::string fixed(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

std::string percent(std::size_t part, std::size_t whole) {
  return whole == 0 ? "0%" : fixed(100.0 * static_cast<double>(part) / static_cast<double>(whole), 2) + "%";
}

std::uint64_t u64(std::size_t n) { return static_cast<std::uint64_t>(n); }

/// "<= 0.7", ..., "> 4" for the radius-edge bins.
std::string bin_label(const TetQualityReport& q, std::size_t bin) {
  std::ostringstream text;
  if (bin < q.radius_edge_bounds.size()) {
    text << "<= " << q.radius_edge_bounds[bin];
  } else {
    text << "> " << q.radius_edge_bounds.back();
  }
  return text.str();
}

/// "min_dihedral_histogram" and "max_dihedral_histogram": arrays of {from_deg, count}.
void dihedral_histograms(JsonWriter& json, const TetQualityReport& q) {
  json.key("min_dihedral_histogram").begin_array();
  for (std::size_t bin = 0; bin < q.min_dihedral_counts.size(); ++bin) {
    json.begin_object();
    json.key("from_deg").value(static_cast<int>(10 * bin));
    json.key("count").value(u64(q.min_dihedral_counts[bin]));
    json.end_object();
  }
  json.end_array();
  json.key("max_dihedral_histogram").begin_array();
  for (std::size_t bin = 0; bin < q.max_dihedral_counts.size(); ++bin) {
    json.begin_object();
    if (bin == 0) {
      json.key("from_deg").value(70.53);
    } else {
      json.key("from_deg").value(static_cast<int>(70 + 10 * bin));
    }
    json.key("count").value(u64(q.max_dihedral_counts[bin]));
    json.end_object();
  }
  json.end_array();
}

/// The dihedral figures of one group of tets (touching small input angles, or not).
void dihedral_group(JsonWriter& json, const TetQualityReport& q) {
  json.begin_object();
  json.key("tets").value(u64(q.tets));
  json.key("min_dihedral_deg").value(q.min_dihedral_deg);
  json.key("max_dihedral_deg").value(q.max_dihedral_deg);
  json.key("outside_dihedral_window").value(u64(q.outside_dihedral_window));
  dihedral_histograms(json, q);
  json.end_object();
}

}  // namespace

MeshReport make_mesh_report(const Plc& plc, const MeshResult& result, const MeshOptions& options) {
  MeshReport report;
  report.input_points = plc.points.size();
  report.input_facets = plc.facets.size();
  report.input_segments = plc.segments.size();
  report.input_regions = plc.regions.size();
  report.input_holes = plc.holes.size();
  report.quality = options.quality;
  report.radius_edge_bound = options.max_radius_edge;
  report.interior_strategy = options.interior_strategy;
  report.segment_recovery = options.segment_recovery;
  report.min_dihedral_deg = options.min_dihedral_deg;
  report.max_dihedral_deg = options.max_dihedral_deg;
  report.max_volume = options.max_volume;
  const TetraMesh& mesh = result.mesh;
  report.vertices = mesh.points.size();
  report.tets = mesh.tets.size();
  report.boundary_faces = mesh.boundary_faces.size();
  const std::set<int> regions(mesh.tet_regions.begin(), mesh.tet_regions.end());
  report.regions = mesh.tet_regions.empty() ? (mesh.tets.empty() ? 0 : 1) : regions.size();
  report.status = result.status;
  report.stats = result.stats;
  TetQualitySplit split = tet_quality_split(mesh, result.tet_at_small_angle, options.max_radius_edge,
                                            options.min_dihedral_deg, options.max_dihedral_deg);
  report.quality_report = std::move(split.all);
  report.quality_at_small_angles = std::move(split.selected);
  report.quality_elsewhere = std::move(split.unselected);
  return report;
}

std::string mesh_summary_text(const MeshReport& r) {
  std::ostringstream out;
  const TetQualityReport& q = r.quality_report;
  out << "input: " << r.input;
  if (!r.input_format.empty()) out << " (" << r.input_format << ")";
  out << ": " << r.input_points << " vertices, " << r.input_facets << " facets, " << r.input_segments
      << " extra segments, " << r.input_regions << " region points, " << r.input_holes << " hole points\n";
  out << "mesh: " << r.vertices << " vertices, " << r.tets << " tets, " << r.boundary_faces << " boundary faces, "
      << r.regions << (r.regions == 1 ? " region\n" : " regions\n");
  out << "status: " << to_string(r.status);
  if (r.status == MeshStatus::Partial) {
    out << " (" << r.stats.unmet_tets << " tets miss the bounds, " << r.stats.unmet_tets_at_small_angles
        << " of them at small input angles";
    if (r.stats.quality_bound_reached)
      out << "; automatic bound on quality Steiner points reached";
    else if (r.stats.budget_exhausted)
      out << "; Steiner budget exhausted";
    out << ")";
  }
  out << '\n';
  if (r.tets > 0) {
    out << "dihedral angles: min " << fixed(q.min_dihedral_deg, 2) << " deg, max " << fixed(q.max_dihedral_deg, 2)
        << " deg\n";
    const TetQualityReport& qs = r.quality_at_small_angles;
    const TetQualityReport& qe = r.quality_elsewhere;
    out << "tets touching small input angles: " << qs.tets << " (" << percent(qs.tets, q.tets) << ")";
    if (qs.tets > 0) {
      out << ", dihedral angles " << fixed(qs.min_dihedral_deg, 2) << " to " << fixed(qs.max_dihedral_deg, 2)
          << " deg";
    }
    out << "; elsewhere " << fixed(qe.min_dihedral_deg, 2) << " to " << fixed(qe.max_dihedral_deg, 2) << " deg\n";
    if (r.min_dihedral_deg > 0.0 || r.max_dihedral_deg < 180.0) {
      out << "dihedral window [" << r.min_dihedral_deg << ", " << r.max_dihedral_deg << "] deg: "
          << q.outside_dihedral_window << " tets (" << percent(q.outside_dihedral_window, q.tets)
          << ") outside; at small input angles " << qs.outside_dihedral_window << " of " << qs.tets << " ("
          << percent(qs.outside_dihedral_window, qs.tets) << "), elsewhere " << qe.outside_dihedral_window << " of "
          << qe.tets << " (" << percent(qe.outside_dihedral_window, qe.tets) << ")\n";
    }
    out << "minimum dihedral histogram (all tets; at small input angles / elsewhere):\n";
    for (std::size_t bin = 0; bin < q.min_dihedral_counts.size(); ++bin) {
      std::string label = "[" + std::to_string(10 * bin) + ", " +
                          (bin + 1 < q.min_dihedral_counts.size() ? std::to_string(10 * (bin + 1)) + ")" : "70.53]");
      label.resize(std::max<std::size_t>(label.size(), 9), ' ');
      out << "  " << label << ' ' << q.min_dihedral_counts[bin] << " (" << percent(q.min_dihedral_counts[bin], q.tets)
          << "); " << qs.min_dihedral_counts[bin] << " / " << qe.min_dihedral_counts[bin] << '\n';
    }
    out << "maximum dihedral histogram (all tets; at small input angles / elsewhere):\n";
    for (std::size_t bin = 0; bin < q.max_dihedral_counts.size(); ++bin) {
      std::string label = "[" + (bin == 0 ? std::string("70.53") : std::to_string(70 + 10 * bin)) + ", " +
                          std::to_string(80 + 10 * bin) + (bin + 1 < q.max_dihedral_counts.size() ? ")" : "]");
      label.resize(std::max<std::size_t>(label.size(), 12), ' ');
      out << "  " << label << ' ' << q.max_dihedral_counts[bin] << " (" << percent(q.max_dihedral_counts[bin], q.tets)
          << "); " << qs.max_dihedral_counts[bin] << " / " << qe.max_dihedral_counts[bin] << '\n';
    }
    out << "radius-edge ratio: max " << fixed(q.max_radius_edge, 3) << ", mean " << fixed(q.mean_radius_edge, 3);
    if (q.flat_ratio_tets > 0) out << ", flat (ratio overflow): " << q.flat_ratio_tets;
    if (r.quality) {
      out << "; " << q.above_radius_edge << " tets (" << percent(q.above_radius_edge, q.tets) << ") above the bound "
          << r.radius_edge_bound;
    }
    out << '\n';
    out << "radius-edge histogram:\n";
    for (std::size_t bin = 0; bin < q.radius_edge_counts.size(); ++bin) {
      std::string label = bin_label(q, bin);
      label.resize(std::max<std::size_t>(label.size(), 9), ' ');
      out << "  " << label << ' ' << q.radius_edge_counts[bin] << " (" << percent(q.radius_edge_counts[bin], q.tets)
          << ")\n";
    }
  }
  out << "stages:\n";
  for (const MeshStageStats& stage : r.stats.stages) {
    std::string name = stage.name;
    name.resize(std::max<std::size_t>(name.size(), 10), ' ');
    out << "  " << name << ' ' << fixed(stage.seconds, 3) << " s, " << stage.steiner_points << " Steiner points\n";
  }
  if (r.stats.ccdt.used) {
    const CcdtStats& c = r.stats.ccdt;
    out << "facet recovery: ccdt, " << c.recovered_regions << " of " << c.regions
        << " regions of missing subfacets recovered without Steiner points, " << c.fallback_facets
        << " facets split instead\n";
  }
  out << "time: import " << fixed(r.import_seconds, 3) << " s, mesh " << fixed(r.mesh_seconds, 3) << " s, write "
      << fixed(r.write_seconds, 3) << " s";
  if (r.check_seconds) out << ", check " << fixed(*r.check_seconds, 3) << " s";
  out << '\n';
  for (const std::string& file : r.outputs) out << "wrote " << file << '\n';
  return out.str();
}

std::string mesh_stats_json(const MeshReport& r) {
  const TetQualityReport& q = r.quality_report;
  JsonWriter json;
  json.begin_object();
  json.key("input").begin_object();
  json.key("file").value(r.input);
  json.key("format").value(r.input_format);
  json.key("vertices").value(u64(r.input_points));
  json.key("facets").value(u64(r.input_facets));
  json.key("segments").value(u64(r.input_segments));
  json.key("regions").value(u64(r.input_regions));
  json.key("holes").value(u64(r.input_holes));
  json.end_object();

  json.key("options").begin_object();
  json.key("quality").value(r.quality);
  json.key("radius_edge_bound").value(r.radius_edge_bound);
  json.key("interior_strategy").value(to_string(r.interior_strategy));
  json.key("segment_recovery")
      .value(r.segment_recovery == SegmentRecovery::StronglyDelaunay ? "strongly-delaunay" : "diametral");
  json.key("min_dihedral_deg").value(r.min_dihedral_deg);
  json.key("max_dihedral_deg").value(r.max_dihedral_deg);
  if (r.max_volume > 0) {
    json.key("max_volume").value(r.max_volume);
  } else {
    json.key("max_volume").null();
  }
  json.end_object();

  json.key("mesh").begin_object();
  json.key("vertices").value(u64(r.vertices));
  json.key("tets").value(u64(r.tets));
  json.key("boundary_faces").value(u64(r.boundary_faces));
  json.key("regions").value(u64(r.regions));
  json.key("volume").value(q.total_volume);
  json.end_object();

  json.key("status").value(to_string(r.status));
  json.key("unmet_tets").value(u64(r.stats.unmet_tets));
  json.key("unmet_tets_at_small_angles").value(u64(r.stats.unmet_tets_at_small_angles));
  json.key("tets_at_small_angles").value(u64(r.stats.tets_at_small_angles));
  json.key("budget_exhausted").value(r.stats.budget_exhausted);
  json.key("quality_bound_reached").value(r.stats.quality_bound_reached);
  json.key("facet_recovery").value(r.stats.ccdt.used ? "ccdt" : "conforming");
  json.key("strong_segments_fell_back").value(r.stats.strong_segments_fell_back);
  if (r.stats.ccdt.used) {
    json.key("ccdt").begin_object();
    json.key("regions").value(u64(r.stats.ccdt.regions));
    json.key("recovered_regions").value(u64(r.stats.ccdt.recovered_regions));
    json.key("failed_regions").value(u64(r.stats.ccdt.failed_regions));
    json.key("fallback_facets").value(u64(r.stats.ccdt.fallback_facets));
    json.key("enlargements").value(u64(r.stats.ccdt.enlargements));
    json.key("cocircular_flips").value(u64(r.stats.ccdt.cocircular_flips));
    json.key("after_conforming").value(r.stats.ccdt.after_conforming);
    json.key("cavity_shrinks").value(u64(r.stats.ccdt.cavity_shrinks));
    json.key("cavity_rejections").value(u64(r.stats.ccdt.cavity_rejections));
    json.end_object();
  }

  json.key("quality").begin_object();
  json.key("min_dihedral_deg").value(q.min_dihedral_deg);
  json.key("max_dihedral_deg").value(q.max_dihedral_deg);
  json.key("max_radius_edge").value(q.max_radius_edge);
  json.key("mean_radius_edge").value(q.mean_radius_edge);
  json.key("flat_ratio_tets").value(u64(q.flat_ratio_tets));
  json.key("min_volume").value(q.min_volume);
  json.key("above_radius_edge_bound").value(u64(q.above_radius_edge));
  json.key("outside_dihedral_window").value(u64(q.outside_dihedral_window));
  json.key("radius_edge_histogram").begin_array();
  for (std::size_t bin = 0; bin < q.radius_edge_counts.size(); ++bin) {
    json.begin_object();
    if (bin < q.radius_edge_bounds.size()) {
      json.key("upper").value(q.radius_edge_bounds[bin]);
    } else {
      json.key("upper").null();
    }
    json.key("count").value(u64(q.radius_edge_counts[bin]));
    json.end_object();
  }
  json.end_array();
  dihedral_histograms(json, q);
  json.key("at_small_angles");
  dihedral_group(json, r.quality_at_small_angles);
  json.key("elsewhere");
  dihedral_group(json, r.quality_elsewhere);
  json.end_object();

  json.key("stages").begin_array();
  for (const MeshStageStats& stage : r.stats.stages) {
    json.begin_object();
    json.key("name").value(stage.name);
    json.key("seconds").value(stage.seconds);
    json.key("steiner_points").value(u64(stage.steiner_points));
    const SegmentSplitStats& splits = stage.segment_splits;
    json.key("segment_splits").begin_object();
    json.key("missing").value(u64(splits.missing));
    json.key("encroached_by_input").value(u64(splits.encroached_by_input));
    json.key("encroached_by_segment_vertex").value(u64(splits.encroached_by_segment_vertex));
    json.key("encroached_by_facet_vertex").value(u64(splits.encroached_by_facet_vertex));
    json.key("encroached_by_interior_vertex").value(u64(splits.encroached_by_interior_vertex));
    json.key("for_rejected_points").value(u64(splits.for_rejected_points));
    json.key("shell").value(u64(splits.shell));
    json.end_object();
    json.end_object();
  }
  json.end_array();

  json.key("seconds").begin_object();
  json.key("import").value(r.import_seconds);
  json.key("mesh").value(r.mesh_seconds);
  json.key("write").value(r.write_seconds);
  if (r.check_seconds) json.key("check").value(*r.check_seconds);
  json.end_object();

  if (r.check_issues) json.key("check_issues").value(u64(*r.check_issues));
  json.key("outputs").begin_array();
  for (const std::string& file : r.outputs) json.value(file);
  json.end_array();
  json.end_object();
  return json.str();
}

}  // namespace delmesh::cli
