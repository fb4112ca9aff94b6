// The per-stage counts of subsegment splits by the rule that fired (MeshStageStats,
// notes §4.2.1): every Steiner point of the segments stage is a counted split.
#include <gtest/gtest.h>

#include "test_plcs.h"

namespace delmesh::test {
namespace {

TEST(Tet3dSegmentSplit, StageStatsCountEverySegmentSplit) {
  // Every Steiner point of the segments stage splits a subsegment, for a rule of §4.2.1
  // (missing or encroached); none is for a rejected point there.
  for (const TestPlc& input : all_test_plcs()) {
    MeshOptions options;
    options.max_radius_edge = 1.414;
    const auto r = mesh_plc(input.plc, options);
    ASSERT_TRUE(r.has_value()) << input.name;
    ASSERT_GE(r->stats.stages.size(), 2u);
    const MeshStageStats& segments = r->stats.stages[1];
    ASSERT_EQ(segments.name, "segments");
    EXPECT_EQ(segments.segment_splits.total(), segments.steiner_points) << input.name;
    EXPECT_EQ(segments.segment_splits.for_rejected_points, 0u) << input.name;
    EXPECT_EQ(segments.segment_splits.encroached_by_facet_vertex, 0u) << input.name;
    EXPECT_EQ(segments.segment_splits.encroached_by_interior_vertex, 0u) << input.name;
    EXPECT_LE(segments.segment_splits.shell, segments.steiner_points) << input.name;
    for (const MeshStageStats& stage : r->stats.stages)
      EXPECT_LE(stage.segment_splits.total(), stage.steiner_points) << input.name << " " << stage.name;
  }
}

}  // namespace
}  // namespace delmesh::test
