// Inputs conforming boundary recovery cannot finish (refiners/tet3d/recovery_limit.h,
// notes §4.2.2-4.2.3): mesh_plc ends with an error naming the features, never with a
// hang or an internal error.
//   (cgal_step.off, whose needle at vertex 7 stopped here, recovers since its segments
//   split on a common grid: tet3d_grid_split_test.cpp; trimesh-box-sides.step, whose
//   facets 0.05 apart stop the conforming facet recovery, is meshed on a CCDT instead:
//   tet3d_corpus_test.cpp.)
//   * wing_fuselage_root.poly (facets of the corpus's wing-fuselage model around the wing
//     root): recovery splits segments ever closer to the trailing-edge vertex 15 until a
//     piece would be shorter than 2^-30 of its coordinates (before that stop, until a
//     split point rounded onto a vertex: once the internal error "a subsegment split point
//     coincides with a vertex"); the error names the segment and the vertex.
#include <gtest/gtest.h>

#include <algorithm>

#include "importers/tetgen/tetgen_reader.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/test_paths.h"

namespace delmesh::test {
namespace {

bool has_id(const Error& error, std::uint32_t id) {
  return std::find(error.entity_ids.begin(), error.entity_ids.end(), id) != error.entity_ids.end();
}

TEST(Tet3dRecoveryLimit, RecoveryAtDoublePrecisionEndsWithAnErrorNamingTheSegment) {
  auto plc = read_tetgen(test_data_dir() / "mesh" / "wing_fuselage_root.poly");
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  MeshOptions options;
  options.quality = false;
  // The conforming recovery's limit (the CCDT default would reach it in its fallback,
  // after another order of splits).
  options.facet_recovery = FacetRecovery::Conforming;
  auto result = mesh_plc(*plc, options);
  ASSERT_FALSE(result.has_value());
  const Error& error = result.error();
  EXPECT_EQ(error.code, ErrorCode::Unsupported);
  EXPECT_NE(error.message.find("resolution of double precision"), std::string::npos) << error.message;
  // Stopped where a piece would fall below 2^-30 of the coordinates (boundary_split.h),
  // on the segment 137-15 of the cluster around the trailing-edge vertex 15.
  EXPECT_NE(error.message.find("shorter than 2^-30"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("segment 137-15"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("input vertex 15"), std::string::npos) << error.message;
  EXPECT_TRUE(has_id(error, 15));
  EXPECT_TRUE(has_id(error, 137));
}

TEST(Tet3dRecoveryLimit, InputsRecoveryFinishesAreNotStopped) {
  // The corpus's TetGen example needs recovery points but far fewer than the bound.
  auto plc = read_tetgen(test_data_dir() / "mesh" / "tetgen_example.poly");
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  auto result = mesh_plc(*plc, MeshOptions{});
  ASSERT_TRUE(result.has_value()) << result.error().describe();
  std::size_t recovery = 0;
  for (const MeshStageStats& stage : result->stats.stages)
    if (stage.name == "segments" || stage.name == "facets") recovery += stage.steiner_points;
  EXPECT_GT(recovery, 0u);
}

}  // namespace
}  // namespace delmesh::test
