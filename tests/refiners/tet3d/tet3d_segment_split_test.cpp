// The per-stage counts of subsegment splits by the rule that fired (MeshStageStats,
// notes §4.2.1): every Steiner point of the segments stage is a counted split. And
// subsegment splits on the CCDT (split_subsegment, boundary_split.h): a corpus part whose
// refinement on the CCDT gave up before the alternate split points and the refusal of
// cavities keeping the subsegment now meshes there, valid.
#include <gtest/gtest.h>

#include <filesystem>

#include "importers/import.h"
#include "test_plcs.h"
#include "tests/support/test_paths.h"
#include "toolkit/check/check_mesh.h"

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

TEST(Tet3dSegmentSplit, TieRodRefinesOnTheCcdtWithValidMesh) {
  // as-tie-rod.step with strongly Delaunay segment recovery: refinement on the CCDT met
  // 664 missing subfacets and gave up (the run was meshed again with diametral recovery,
  // 68784 vertices); 655 subsegment splits were refused, each because the cavity shrunk
  // to a star of the split point left a subfacet the split removes on its boundary. With
  // the alternate split points alone the refinement finished but left a boundary face of
  // zero area (a split whose cavity kept the subsegment as an edge); with the edge check
  // as well it meshes on the CCDT (measured: 38804 vertices).
  const auto path = corpus_dir() / "step" / "as-tie-rod.step";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (DELMESH_CORPUS_DIR)";
  auto plc = import_file(path, ImportOptions{});
  ASSERT_TRUE(plc.has_value()) << path << ": " << plc.error().message;
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.segment_recovery = SegmentRecovery::StronglyDelaunay;
  const auto r = mesh_plc(*plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  EXPECT_FALSE(r->stats.strong_segments_fell_back);
  CheckMeshOptions check;
  check.check_delaunay = r->constrained_delaunay;
  for (const MeshCheckIssue& issue : check_mesh(r->mesh, *plc, r->boundary_face_facets, check))
    ADD_FAILURE() << issue.message;
}

}  // namespace
}  // namespace delmesh::test
