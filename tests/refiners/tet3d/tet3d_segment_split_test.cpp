// Split points of subsegments (refiners/tet3d/boundary_split.h; notes §4.2.1, §3.8): a
// subsegment between two shared input vertices is bisected, and only a subsegment with
// exactly one shared input endpoint is split on a concentric shell around it; and the
// per-stage counts of subsegment splits by the rule that fired (MeshStageStats).
#include <gtest/gtest.h>

#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

TEST(Tet3dSegmentSplit, BisectsBetweenSharedVerticesThenSplitsOnShells) {
  // Box [0, 1.4] x [0, 1] x [0, 1]: the edge from corner (0,0,0) to (1.4,0,0) is tet
  // mesh vertices 1 -> 2; both corners are shared by three segments.
  Plc plc;
  add_box(plc, Vec3(0, 0, 0), Vec3(1.4, 1, 1), 1);
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  ASSERT_TRUE(state.subsegments.count(edge_key(1, 2)));
  const Vec3 first = subsegment_split_point(state, 1, 2);
  EXPECT_EQ(first, Vec3(0.7, 0, 0));
  EXPECT_EQ(subsegment_split_point(state, 2, 1), Vec3(0.7, 0, 0));

  const std::uint32_t v = split_subsegment(state, 1, 2, first, 0.0);
  ASSERT_NE(v, kNone);
  // (1, v) has one shared input endpoint, vertex 1: the split point is at the power of
  // two nearest half its length 0.7 (0.25), from vertex 1, whichever way it is named.
  for (const Vec3& q : {subsegment_split_point(state, 1, v), subsegment_split_point(state, v, 1)}) {
    EXPECT_NEAR(q.x(), 0.25, 1e-15);
    EXPECT_EQ(q.y(), 0.0);
    EXPECT_EQ(q.z(), 0.0);
  }
  // (v, 2): the shell is around vertex 2, at distance 0.25 from it.
  const Vec3 near_2 = subsegment_split_point(state, v, 2);
  EXPECT_NEAR(near_2.x(), 1.15, 1e-15);
  EXPECT_EQ(near_2.y(), 0.0);
  EXPECT_EQ(near_2.z(), 0.0);

  // The splits are counted: one for a rejected point (a direct split_subsegment call),
  // none of them on a shell.
  EXPECT_EQ(state.stage_segment_splits.for_rejected_points, 1u);
  EXPECT_EQ(state.stage_segment_splits.shell, 0u);
  EXPECT_EQ(state.stage_segment_splits.total(), 1u);
}

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
