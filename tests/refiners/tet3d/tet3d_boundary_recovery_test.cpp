// Boundary recovery (refiners/tet3d/boundary_recovery.h, notes §4.2.1, §4.2.3): the
// straight walk that finds the subsegment between a subfacet and a point outside its
// facet (Projection Lemma, Lemma 17), and a cut of a corpus surface whose facet recovery
// used to split subfacets for vertices projecting outside their facet until a missing
// subfacet degenerated into a needle that could not be split (internal error).
#include <gtest/gtest.h>

#include "importers/tetgen/tetgen_reader.h"
#include "refiners/tet3d/boundary_recovery.h"
#include "refiners/tet3d/plc_preparation.h"
#include "tests/support/test_paths.h"
#include "test_plcs.h"
#include "toolkit/tetmesh/tet_check.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

TEST(Tet3dBoundaryRecovery, SubsegmentTowardFindsTheSegmentBetween) {
  const TestPlc input = unit_cube();
  MeshOptions options;
  RefineState state(input.plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  // Facet 4 is z = 0 with corners (0,0,0) (1,0,0) (0,1,0) (1,1,0): tet ids 1, 2, 3, 4.
  const auto subfaces = state.facets[4].subfaces();
  ASSERT_EQ(subfaces.size(), 2u);
  for (const Subface& s : subfaces) {
    const FaceKey from = face_key(s[0], s[1], s[2]);
    EXPECT_EQ(subsegment_toward(state, 4, from, Vec3(0.5, -1.0, 0.0)), edge_key(1, 2));
    EXPECT_EQ(subsegment_toward(state, 4, from, Vec3(-1.0, 0.5, 0.0)), edge_key(1, 3));
    EXPECT_EQ(subsegment_toward(state, 4, from, Vec3(0.5, 2.0, 0.3)), edge_key(3, 4));
    EXPECT_EQ(subsegment_toward(state, 4, from, Vec3(0.25, 0.25, 0.7)), std::nullopt);
    EXPECT_EQ(subsegment_toward(state, 4, from, Vec3(0.9, 0.6, -0.2)), std::nullopt);
  }
}

TEST(Tet3dBoundaryRecovery, HomerCutRecoversEveryFacetWithFewSteinerPoints) {
  auto plc = read_tetgen(test_data_dir() / "mesh" / "homer_cut.poly");
  ASSERT_TRUE(plc.has_value()) << plc.error().message;
  ASSERT_EQ(plc->points.size(), 15u);
  MeshOptions options;
  RefineState state(*plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  ASSERT_TRUE(restore_conformity(state, true).has_value());
  for (const auto& [key, facet] : state.subfaces) state.subface_queue.push_back({key});
  state.stage_steiner = 0;
  ASSERT_TRUE(restore_conformity(state, false).has_value());
  // Recovery once inserted facet vertices 1e-9 apart here before failing; now a few dozen.
  EXPECT_LT(state.stage_steiner, 100u);
  EXPECT_TRUE(check_topology(state.mesh).empty());
  EXPECT_TRUE(check_delaunay(state.mesh, 20, true).empty());
  for (const auto& [key, seg] : state.subsegments) {
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
    EXPECT_TRUE(state.mesh.find_edge(a, b).has_value()) << "subsegment missing";
  }
  for (const auto& [key, facet] : state.subfaces)
    EXPECT_TRUE(state.mesh.find_face(key[0], key[1], key[2]).has_value()) << "subfacet missing";
  for (const auto& tri : state.facets) EXPECT_TRUE(tri.check().empty());
}

}  // namespace
}  // namespace delmesh::test
