// Split points of encroached subsegments (refiners/tet3d/boundary_split.h): a subsegment
// encroached by a vertex of another segment sharing an input endpoint is split at that
// vertex's distance from the shared endpoint when it falls in the middle third, else at
// the concentric-shell point or midpoint of subsegment_split_point.
#include <gtest/gtest.h>

#include <cmath>

#include "refiners/tet3d/boundary_split.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// A prism over the triangle (0,0) (10,0) (10,1): its bottom edges from the origin to
/// (10,0,0) and to (10,1,0) are segments meeting at about 5.7 degrees.
TestPlc needle_prism() {
  TestPlc t{"needle_prism", {}, 5.0, {}, true};
  add_prism(t.plc, {{0, 0}, {10, 0}, {10, 1}}, 1.0);
  return t;
}

std::uint32_t vertex_at(const RefineState& state, const Vec3& p) {
  for (std::uint32_t v = 1; v < state.mesh.num_vertices(); ++v)
    if (state.mesh.point(v) == p) return v;
  return kNone;
}

class Tet3dSplitPoint : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(prepare_plc(state).has_value());
    apex = vertex_at(state, Vec3(0, 0, 0));
    along = vertex_at(state, Vec3(10, 0, 0));
    slanted = vertex_at(state, Vec3(10, 1, 0));
    ASSERT_NE(apex, kNone);
    ASSERT_NE(along, kNone);
    ASSERT_NE(slanted, kNone);
    ASSERT_TRUE(state.subsegments.count(edge_key(apex, along)));
    ASSERT_TRUE(state.subsegments.count(edge_key(apex, slanted)));
  }

  /// Splits the slanted segment at `p` (a point of it) and returns the new vertex.
  std::uint32_t split_slanted(const Vec3& p) {
    const std::uint32_t v = split_subsegment(state, apex, slanted, p, 0.0);
    EXPECT_NE(v, kNone);
    EXPECT_EQ(state.vertices[v].kind, VertexKind::OnSegment);
    return v;
  }

  TestPlc input = needle_prism();
  MeshOptions options;
  RefineState state{input.plc, options};
  std::uint32_t apex = kNone, along = kNone, slanted = kNone;
};

TEST_F(Tet3dSplitPoint, MatchesTheDistanceOfTheEncroachingSegmentVertex) {
  // The midpoint (5, 0.5, 0) of the slanted segment lies sqrt(25.25) ~ 5.02 from the
  // apex, inside the middle third [3.33, 6.67] of the other segment's span [0, 10].
  const std::uint32_t by = split_slanted(Vec3(5, 0.5, 0));
  const Vec3 p = subsegment_split_point_for(state, apex, along, by);
  EXPECT_NEAR(p.x(), std::sqrt(25.25), 1e-12);
  EXPECT_EQ(p.y(), 0.0);
  EXPECT_EQ(p.z(), 0.0);
  // Either orientation of the subsegment gives the same point.
  EXPECT_EQ(subsegment_split_point_for(state, along, apex, by), p);
  // The new vertex encroaches the other segment's subsegment: the rule applies there.
  EXPECT_NE(predicates::dot3d(state.mesh.coords(apex), state.mesh.coords(along), state.mesh.coords(by)),
            Sign::Positive);
}

TEST_F(Tet3dSplitPoint, OutsideTheMiddleThirdFallsBackToShellsAndMidpoints) {
  // At distance 2.01 from the apex: outside [3.33, 6.67], so the shell rule decides (the
  // apex is shared by two segments: a power of two from it, 4).
  const std::uint32_t near_apex = split_slanted(Vec3(2, 0.2, 0));
  EXPECT_EQ(subsegment_split_point_for(state, apex, along, near_apex), subsegment_split_point(state, apex, along));
  EXPECT_EQ(subsegment_split_point(state, apex, along), Vec3(4, 0, 0));
  // An input vertex, or a vertex of the same segment, is not a vertex of another segment.
  EXPECT_EQ(subsegment_split_point_for(state, apex, along, slanted), subsegment_split_point(state, apex, along));
  EXPECT_EQ(subsegment_split_point_for(state, apex, along, kNone), subsegment_split_point(state, apex, along));
  const std::uint32_t own = split_subsegment(state, apex, along, Vec3(4, 0, 0), 0.0);
  ASSERT_NE(own, kNone);
  EXPECT_EQ(subsegment_split_point_for(state, own, along, own), subsegment_split_point(state, own, along));
  // (own, along) spans distances [4, 10]: the slanted vertex at 2.01 is outside it.
  EXPECT_EQ(subsegment_split_point_for(state, own, along, near_apex), subsegment_split_point(state, own, along));
}

TEST_F(Tet3dSplitPoint, SubsegmentAwayFromTheApexUsesDistancesFromTheApex) {
  const std::uint32_t own = split_subsegment(state, apex, along, Vec3(4, 0, 0), 0.0);
  ASSERT_NE(own, kNone);
  // (own, along) spans [4, 10], middle third [6, 8]; a slanted vertex 7.5 from the apex.
  const double s = 7.5 / std::sqrt(101.0);
  const std::uint32_t by = split_slanted(Vec3(10 * s, s, 0));
  const Vec3 p = subsegment_split_point_for(state, own, along, by);
  EXPECT_NEAR(p.x(), 7.5, 1e-12);
  EXPECT_EQ(p.y(), 0.0);
}

}  // namespace
}  // namespace delmesh::test
