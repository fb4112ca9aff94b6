// The pieces behind `delmesh mesh`'s output: the JSON writer, the throttled progress sink,
// and the summary / --stats report of a hand-built MeshResult (the six Kuhn tets of a cube).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "tests/support/json_value.h"
#include "tools/delmesh/json_writer.h"
#include "tools/delmesh/mesh_report.h"
#include "tools/delmesh/progress_sink.h"

namespace delmesh::cli {
namespace {

using test::JsonValue;
using test::parse_json;

TEST(JsonWriter, NestingCommasEscapesAndNonFiniteNumbers) {
  JsonWriter json;
  json.begin_object();
  json.key("name").value("a \"quoted\"\\path\n\x01");
  json.key("list").begin_array().value(1).value(2.5).value(true).null().end_array();
  json.key("empty").begin_object().end_object();
  json.key("none").begin_array().end_array();
  json.key("inf").value(std::numeric_limits<double>::infinity());
  json.key("big").value(std::uint64_t{18446744073709551615u});
  json.end_object();
  std::string error;
  const auto doc = parse_json(json.str(), &error);
  ASSERT_TRUE(doc.has_value()) << error << "\n" << json.str();
  EXPECT_EQ((*doc)["name"].string, "a \"quoted\"\\path\n\x01");
  ASSERT_EQ((*doc)["list"].array.size(), 4u);
  EXPECT_EQ((*doc)["list"].array[1].number, 2.5);
  EXPECT_TRUE((*doc)["list"].array[2].boolean);
  EXPECT_EQ((*doc)["list"].array[3].type, JsonValue::Type::Null);
  EXPECT_TRUE((*doc)["empty"].object.empty());
  EXPECT_TRUE((*doc)["none"].array.empty());
  EXPECT_EQ((*doc)["inf"].type, JsonValue::Type::Null);
  EXPECT_NE(json.str().find("18446744073709551615"), std::string::npos);
}

TEST(JsonWriter, DoublesRoundTrip) {
  JsonWriter json;
  json.begin_array().value(0.1).value(1e-300).value(-123456.789).end_array();
  const auto doc = parse_json(json.str());
  ASSERT_TRUE(doc.has_value()) << json.str();
  EXPECT_EQ(doc->array[0].number, 0.1);
  EXPECT_EQ(doc->array[1].number, 1e-300);
  EXPECT_EQ(doc->array[2].number, -123456.789);
}

TEST(ProgressLogSink, SilentForShortRunsThenThrottled) {
  double now = 0.0;
  std::ostringstream out;
  ProgressLogSink::Settings settings;
  ProgressLogSink sink(out, settings, [&] { return now; });
  sink.set_phase("meshing");
  sink.write(LogLevel::Progress, "early");
  now = 0.9;
  sink.tick();
  EXPECT_EQ(out.str(), "");
  now = 1.2;
  sink.write(LogLevel::Progress, "first");
  now = 1.3;
  sink.write(LogLevel::Progress, "throttled");
  now = 1.8;
  sink.tick();  // the library is silent: the elapsed time still moves
  sink.write(LogLevel::Info, "info needs verbose");
  sink.write(LogLevel::Warning, "careful");
  now = 2.5;
  sink.tick();  // Info messages become the status
  EXPECT_EQ(out.str(),
            "meshing 1.2 s: first\nmeshing 1.8 s: throttled\nwarning: careful\nmeshing 2.5 s: info needs verbose\n");
}

TEST(ProgressLogSink, TerminalRewritesOneLineAndQuietKeepsWarnings) {
  double now = 5.0;
  std::ostringstream out;
  ProgressLogSink::Settings settings;
  settings.terminal = true;
  settings.delay = 0.0;
  ProgressLogSink sink(out, settings, [&] { return now; });
  sink.write(LogLevel::Progress, "refining 10");
  now = 6.0;
  sink.set_phase("writing");
  sink.tick();
  sink.finish_line();
  EXPECT_EQ(out.str(), "\r0.0 s: refining 10\rwriting 1.0 s     \n");

  std::ostringstream quiet_out;
  settings.quiet = true;
  ProgressLogSink quiet(quiet_out, settings, [&] { return now; });
  quiet.write(LogLevel::Progress, "hidden");
  quiet.tick();
  quiet.write(LogLevel::Warning, "shown");
  EXPECT_EQ(quiet_out.str(), "warning: shown\n");
}

/// Unit cube as six Kuhn tets (positively oriented), two regions, no boundary faces needed.
MeshResult kuhn_result() {
  MeshResult result;
  TetraMesh& mesh = result.mesh;
  for (int i = 0; i < 8; ++i) mesh.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& a : axes) {
    const std::uint32_t v1 = 1u << a[0], v2 = v1 | (1u << a[1]);
    std::array<std::uint32_t, 4> t{0, v1, v2, 7};
    if (signed_volume(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]) < 0)
      std::swap(t[1], t[2]);
    mesh.tets.push_back(t);
  }
  mesh.tet_regions = {1, 1, 1, 2, 2, 2};
  result.status = MeshStatus::Partial;
  result.stats.unmet_tets = 6;
  result.stats.unmet_tets_at_small_angles = 4;
  result.stats.tets_at_small_angles = 4;
  result.tet_at_small_angle = {1, 1, 0, 1, 0, 1};
  result.stats.stages = {{"delaunay", 0.25, 0}, {"quality", 1.5, 42}};
  return result;
}

TEST(MeshReport, DihedralWindowAndHistogram) {
  Plc plc;
  plc.points.resize(8);
  plc.facets.resize(6);
  MeshOptions options;
  options.min_dihedral_deg = 50.0;  // every Kuhn tet has a 45 degree dihedral angle
  options.max_dihedral_deg = 150.0;
  const MeshReport report = make_mesh_report(plc, kuhn_result(), options);
  const std::string text = mesh_summary_text(report);
  EXPECT_NE(text.find("dihedral window [50, 150] deg: 6 tets (100.00%) outside; at small input angles 4 of 4 "
                      "(100.00%), elsewhere 2 of 2 (100.00%)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("tets touching small input angles: 4 (66.67%), dihedral angles 45.00 to 90.00 deg; elsewhere "
                      "45.00 to 90.00 deg"),
            std::string::npos)
      << text;
  // Every Kuhn tet has dihedral angles of 45, 60 and 90 degrees.
  EXPECT_NE(text.find("  [40, 50)  6 (100.00%); 4 / 2"), std::string::npos) << text;
  EXPECT_NE(text.find("  [80, 90)     0 (0.00%); 0 / 0\n  [90, 100)    6 (100.00%); 4 / 2"), std::string::npos)
      << text;
  // Without a target the window line is left out, the histograms are not.
  const std::string plain = mesh_summary_text(make_mesh_report(plc, kuhn_result(), MeshOptions{}));
  EXPECT_EQ(plain.find("dihedral window"), std::string::npos) << plain;
  EXPECT_NE(plain.find("minimum dihedral histogram (all tets; at small input angles / elsewhere):"),
            std::string::npos)
      << plain;
  EXPECT_NE(plain.find("maximum dihedral histogram (all tets; at small input angles / elsewhere):"),
            std::string::npos)
      << plain;

  // The same split in --stats.
  std::string error;
  const auto doc = parse_json(mesh_stats_json(report), &error);
  ASSERT_TRUE(doc.has_value()) << error;
  EXPECT_EQ((*doc)["tets_at_small_angles"].number, 4);
  const JsonValue& quality = (*doc)["quality"];
  EXPECT_EQ(quality["outside_dihedral_window"].number, 6);
  EXPECT_EQ(quality["at_small_angles"]["tets"].number, 4);
  EXPECT_EQ(quality["at_small_angles"]["outside_dihedral_window"].number, 4);
  EXPECT_EQ(quality["elsewhere"]["tets"].number, 2);
  EXPECT_EQ(quality["elsewhere"]["outside_dihedral_window"].number, 2);
  EXPECT_NEAR(quality["elsewhere"]["min_dihedral_deg"].number, 45.0, 1e-9);
  ASSERT_EQ(quality["elsewhere"]["min_dihedral_histogram"].array.size(), 8u);
  EXPECT_EQ(quality["elsewhere"]["min_dihedral_histogram"].array[4]["count"].number, 2);
  const auto& max_histogram = quality["max_dihedral_histogram"].array;
  ASSERT_EQ(max_histogram.size(), 11u);
  EXPECT_EQ(max_histogram[0]["from_deg"].number, 70.53);
  EXPECT_EQ(max_histogram[2]["from_deg"].number, 90);
  EXPECT_EQ(max_histogram[2]["count"].number, 6);
}

TEST(MeshReport, SummaryAndStatsOfAKnownMesh) {
  Plc plc;
  plc.points.resize(8);
  plc.facets.resize(6);
  MeshOptions options;
  options.max_radius_edge = 0.8;  // every Kuhn tet has ratio sqrt(3)/2 ~ 0.866
  const MeshResult result = kuhn_result();
  MeshReport report = make_mesh_report(plc, result, options);
  report.input = "cube.poly";
  report.input_format = "poly";
  report.outputs = {"cube.vtu"};
  report.check_issues = 0;
  report.check_seconds = 0.01;
  EXPECT_EQ(report.regions, 2u);
  EXPECT_EQ(report.quality_report.above_radius_edge, 6u);

  const std::string text = mesh_summary_text(report);
  EXPECT_NE(text.find("mesh: 8 vertices, 6 tets, 0 boundary faces, 2 regions"), std::string::npos) << text;
  EXPECT_NE(text.find("status: Partial (6 tets miss the bounds, 4 of them at small input angles)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  <= 0.9    6 (100.00%)"), std::string::npos) << text;
  EXPECT_NE(text.find("quality    1.500 s, 42 Steiner points"), std::string::npos) << text;
  EXPECT_NE(text.find("wrote cube.vtu"), std::string::npos) << text;

  std::string error;
  const auto doc = parse_json(mesh_stats_json(report), &error);
  ASSERT_TRUE(doc.has_value()) << error;
  for (const char* key : {"input", "options", "mesh", "status", "unmet_tets", "quality", "stages", "seconds",
                          "check_issues", "outputs"}) {
    EXPECT_TRUE(doc->has(key)) << key;
  }
  EXPECT_EQ((*doc)["status"].string, "Partial");
  EXPECT_EQ((*doc)["mesh"]["tets"].number, 6);
  EXPECT_NEAR((*doc)["mesh"]["volume"].number, 1.0, 1e-12);
  EXPECT_NEAR((*doc)["quality"]["max_radius_edge"].number, std::sqrt(3.0) / 2, 1e-9);
  const auto& histogram = (*doc)["quality"]["radius_edge_histogram"].array;
  ASSERT_EQ(histogram.size(), report.quality_report.radius_edge_bounds.size() + 1);
  EXPECT_EQ(histogram[2]["upper"].number, 0.9);
  EXPECT_EQ(histogram[2]["count"].number, 6);
  EXPECT_EQ(histogram.back()["upper"].type, JsonValue::Type::Null);
  ASSERT_EQ((*doc)["stages"].array.size(), 2u);
  EXPECT_EQ((*doc)["stages"].array[1]["steiner_points"].number, 42);
  EXPECT_EQ((*doc)["options"]["max_volume"].type, JsonValue::Type::Null);
}

}  // namespace
}  // namespace delmesh::cli
