// Progress reports of mesh_plc (refiners/tet3d/progress_report.h): the callback and the
// Progress-level log lines name each stage in order, and the figures they carry grow with
// the mesh and end at its size.
#include <string>
#include <vector>

#include "refiners/tet3d/progress_report.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

class RecordingSink final : public LogSink {
 public:
  void write(LogLevel level, std::string_view message) override {
    if (level == LogLevel::Progress) progress.emplace_back(message);
  }
  std::vector<std::string> progress;
};

TEST(Tet3dProgress, EveryStageIsReportedInOrderWithGrowingCounts) {
  const TestPlc input = box_with_hole();
  std::vector<MeshProgress> seen;
  RecordingSink sink;
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.max_volume = 0.01;
  options.log = &sink;
  options.progress = [&](const MeshProgress& p) { seen.push_back(p); };
  auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;

  std::vector<std::string> stages;
  for (const MeshProgress& p : seen) {
    if (stages.empty() || stages.back() != p.stage) stages.emplace_back(p.stage);
  }
  EXPECT_EQ(stages,
            (std::vector<std::string>{"delaunay", "segments", "facets", "domain", "quality", "slivers", "polish"}));
  for (std::size_t k = 1; k < seen.size(); ++k) {
    EXPECT_GE(seen[k].seconds, seen[k - 1].seconds);
    EXPECT_GE(seen[k].vertices, seen[k - 1].vertices);  // refinement only adds vertices
    EXPECT_GE(seen[k].steiner_points, seen[k - 1].steiner_points);
  }
  // The quality stage starts from the recovered boundary: the input vertices are all in.
  const MeshProgress* start = nullptr;
  for (const MeshProgress& p : seen) {
    if (!start && p.stage == std::string("quality")) start = &p;
  }
  ASSERT_NE(start, nullptr);
  const MeshProgress& quality = *start;
  EXPECT_GE(quality.vertices, input.plc.points.size());
  EXPECT_LE(quality.vertices, r->mesh.points.size());
  EXPECT_GT(quality.tets, 0u);
  // The log gets the same reports as text, starting with the stage name.
  ASSERT_EQ(sink.progress.size(), seen.size());
  for (std::size_t k = 0; k < seen.size(); ++k) {
    EXPECT_EQ(sink.progress[k].rfind(std::string(seen[k].stage) + ": ", 0), 0u) << sink.progress[k];
    EXPECT_NE(sink.progress[k].find(std::to_string(seen[k].vertices) + " vertices"), std::string::npos);
  }
}

TEST(Tet3dProgress, DescribeNamesStageCountsAndQueues) {
  MeshProgress p;
  p.stage = "quality";
  p.vertices = 1200;
  p.tets = 6100;
  p.steiner_points = 900;
  EXPECT_EQ(tet3d::describe(p), "quality: 1200 vertices, 6100 tets, 900 Steiner points");
  p.subfacet_queue = 3;
  p.tet_queue = 250;
  EXPECT_EQ(tet3d::describe(p),
            "quality: 1200 vertices, 6100 tets, 900 Steiner points; queued 0 subsegments, 3 subfacets, 250 tets");
}

}  // namespace
}  // namespace delmesh::test
