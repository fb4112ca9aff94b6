// Local feature size of the input vertices (refiners/tet3d/feature_size.h, notes §4.2.2):
// the gaps from an input vertex to the nearest segment or facet sharing no vertex with
// the features containing it (separate) and not containing it (adjacent), and the
// quality stage's initial termination floors taken from them with the nearest vertex
// (plc_preparation.h; boundary recovery's stay with the nearest vertex).
//   * a 10-unit box with a box-shaped hole whose bottom face is 0.5 above the box's
//     bottom: the hole's bottom corners are 0.5 from the bottom facet, nearer than any
//     other vertex (1.5), and their floors are kFloorFactor * 0.5, not kFloorFactor * 1.5;
//   * the box's own corners are not measured against the facets and segments they lie on
//     (the answer would be 0), nor against the box's other facets (they share corners):
//     their nearest disjoint feature is the hole;
//   * a single tetrahedron: every facet shares a vertex with every other, so no vertex
//     has a separate feature (infinity); the adjacent gap of the origin to the opposite
//     facet is 1/sqrt(3), above a quarter of its nearest vertex (1), and sets its floor;
//   * a sliver-shaped triangle beside a vertex: its adjacent gap counts only down to a
//     quarter of the nearest vertex distance (kAdjacentGapShare);
//   * a segment crossing near another one without a shared endpoint sets the floors of
//     its ends by the gap, not by the (farther) vertices.
//   * measured only below each vertex's nearest vertex distance, as preparation does,
//     the gaps give the same floors bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "refiners/tet3d/feature_size.h"
#include "refiners/tet3d/plc_preparation.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

using namespace delmesh::tet3d;

/// Box [0,10]^3 (input points 0-7) with the hole [4,6] x [4,6] x [0.5,2] (points 8-15).
Plc box_with_low_hole() {
  Plc plc;
  add_box(plc, Vec3(0, 0, 0), Vec3(10, 10, 10), 1);
  add_box(plc, Vec3(4, 4, 0.5), Vec3(6, 6, 2), 11);
  plc.holes.emplace_back(5.0, 5.0, 1.0);
  return plc;
}

TEST(Tet3dFeatureSize, HoleNearAFacet) {
  const Plc plc = box_with_low_hole();
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  const FeatureGaps gaps = feature_gaps(state, plc.points.size());
  const std::vector<double>& d = gaps.separate;
  ASSERT_EQ(d.size(), state.mesh.num_vertices());
  ASSERT_EQ(gaps.adjacent.size(), state.mesh.num_vertices());
  // Tet mesh id = input index + 1. The hole's bottom corners (z = 0.5): inputs 8-11.
  for (std::uint32_t i = 8; i < 12; ++i) {
    EXPECT_DOUBLE_EQ(d[i + 1], 0.5) << "hole corner " << i;
    EXPECT_DOUBLE_EQ(state.vertices[i + 1].field_floor, kFloorFactor * 0.5) << "hole corner " << i;
    // Boundary recovery's floor stays with the nearest vertex.
    EXPECT_DOUBLE_EQ(state.vertices[i + 1].floor, kFloorFactor * 1.5) << "hole corner " << i;
  }
  // Its top corners (z = 2): the hole's facets all share corners with the ones at the
  // vertex, so the box's bottom facet, 2 below, is the nearest disjoint feature; the
  // bottom corners (1.5) set the floor.
  for (std::uint32_t i = 12; i < 16; ++i) {
    EXPECT_DOUBLE_EQ(d[i + 1], 2.0) << "hole corner " << i;
    EXPECT_DOUBLE_EQ(gaps.adjacent[i + 1], 1.5) << "hole corner " << i;  // the hole's bottom facet
    EXPECT_DOUBLE_EQ(state.vertices[i + 1].field_floor, kFloorFactor * 1.5) << "hole corner " << i;
  }
  // The box's corner (0,0,0): the hole's corner (4,4,0.5) is its nearest disjoint feature.
  EXPECT_DOUBLE_EQ(d[1], std::sqrt(16.0 + 16.0 + 0.25));
  EXPECT_DOUBLE_EQ(state.vertices[1].field_floor, kFloorFactor * std::sqrt(16.0 + 16.0 + 0.25));
}

TEST(Tet3dFeatureSize, SegmentsPassingClose) {
  // Unit cube with two free segments inside: one along x at (y, z) = (0.5, 0.5), one along
  // y at z = 0.5 + gap, crossing above the first at x = 0.5 without touching it.
  constexpr double kGap = 0.01;
  Plc plc = unit_cube().plc;
  const auto base = static_cast<std::uint32_t>(plc.points.size());
  plc.points.emplace_back(0.3, 0.5, 0.5);
  plc.points.emplace_back(0.7, 0.5, 0.5);
  plc.points.emplace_back(0.5, 0.3, 0.5 + kGap);
  plc.points.emplace_back(0.5, 0.7, 0.5 + kGap);
  plc.segments.push_back({base, base + 1, 0});
  plc.segments.push_back({base + 2, base + 3, 0});
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  const FeatureGaps gaps = feature_gaps(state, plc.points.size());
  const std::vector<double>& d = gaps.separate;
  // Each end is 0.2 (and a hair) from the other segment, the segment's middle: the
  // nearest vertex (0.2 * sqrt(2) away, or farther) is not the local feature size.
  const double expected = std::sqrt(0.2 * 0.2 + kGap * kGap);
  for (std::uint32_t i = base; i < base + 4; ++i) {
    EXPECT_NEAR(d[i + 1], expected, 1e-12) << "segment end " << i;
    EXPECT_NEAR(state.vertices[i + 1].field_floor, kFloorFactor * expected, 1e-12) << "segment end " << i;
  }
  // The cube's corners are about 0.77 from the nearest segment end; never 0 (the cube's
  // facets and edges are skipped).
  for (std::uint32_t i = 0; i < base; ++i) EXPECT_GT(d[i + 1], 0.5) << "cube corner " << i;
}

TEST(Tet3dFeatureSize, NoDisjointFeature) {
  // A single tetrahedron: the facet opposite a vertex shares the other three vertices
  // with the facets at it, so no feature is disjoint from the vertex's star.
  Plc plc;
  plc.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const std::uint32_t faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (const auto& f : faces) {
    Plc::Facet facet;
    facet.polygons.push_back({f[0], f[1], f[2]});
    plc.facets.push_back(facet);
  }
  MeshOptions options;
  RefineState state(plc, options);
  ASSERT_TRUE(prepare_plc(state).has_value());
  const FeatureGaps gaps = feature_gaps(state, plc.points.size());
  const std::vector<double>& d = gaps.separate;
  for (std::uint32_t v = 1; v <= 4; ++v) EXPECT_TRUE(std::isinf(d[v])) << v;
  EXPECT_NEAR(gaps.adjacent[1], 1.0 / std::sqrt(3.0), 1e-15);  // origin to the plane x + y + z = 1
  EXPECT_NEAR(state.vertices[1].field_floor, kFloorFactor / std::sqrt(3.0), 1e-15);
  for (std::uint32_t v = 2; v <= 4; ++v) {
    EXPECT_NEAR(gaps.adjacent[v], 1.0, 1e-15);  // to the opposite axis-plane facet
    EXPECT_DOUBLE_EQ(state.vertices[v].field_floor, kFloorFactor * 1.0);  // nearest vertex sqrt(2)
  }
}

TEST(Tet3dFeatureSize, AdjacentGapsAreBounded) {
  // floor_feature_size alone: nearest vertex 1, adjacent gap 0.01 (a thin triangle's
  // height), no separate feature: a quarter of the nearest vertex. A separate gap of
  // 0.01 counts in full; gaps of 0 (touching features) are ignored.
  FeatureGaps gaps;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  gaps.separate = {kInf, kInf, 0.01, 0.0};
  gaps.adjacent = {kInf, 0.01, 0.5, 0.0};
  EXPECT_DOUBLE_EQ(floor_feature_size(1.0, gaps, 0), 1.0);
  EXPECT_DOUBLE_EQ(floor_feature_size(1.0, gaps, 1), kAdjacentGapShare);
  EXPECT_DOUBLE_EQ(floor_feature_size(1.0, gaps, 2), 0.01);
  EXPECT_DOUBLE_EQ(floor_feature_size(1.0, gaps, 3), 1.0);
}

TEST(Tet3dFeatureSize, GapsBelowTheNearestVertexGiveTheSameFloors) {
  // Measured only below each vertex's nearest vertex distance (as plc_preparation.h
  // asks), the gaps give the same floor_feature_size, bit for bit; those left out are
  // infinity and were at least that distance.
  std::vector<TestPlc> inputs = all_test_plcs();
  TestPlc low_hole;
  low_hole.name = "box-with-low-hole";
  low_hole.plc = box_with_low_hole();
  inputs.push_back(low_hole);
  std::size_t cut = 0, kept = 0;
  for (const TestPlc& input : inputs) {
    MeshOptions options;
    RefineState state(input.plc, options);
    ASSERT_TRUE(prepare_plc(state).has_value()) << input.name;
    const std::vector<double> nearest = nearest_vertex_distances(state);
    const FeatureGaps full = feature_gaps(state, input.plc.points.size());
    const FeatureGaps below = feature_gaps(state, input.plc.points.size(), &nearest);
    for (std::uint32_t v = 1; v <= input.plc.points.size(); ++v) {
      EXPECT_EQ(floor_feature_size(nearest[v], below, v), floor_feature_size(nearest[v], full, v))
          << input.name << " vertex " << v;
      for (const auto& [gap, all] : {std::pair{below.separate[v], full.separate[v]},
                                     std::pair{below.adjacent[v], full.adjacent[v]}}) {
        if (gap == all) {
          kept += std::isfinite(gap);
          continue;
        }
        EXPECT_TRUE(std::isinf(gap)) << input.name << " vertex " << v;
        EXPECT_GE(all, nearest[v]) << input.name << " vertex " << v;
        ++cut;
      }
    }
  }
  EXPECT_GT(cut, 0u);
  EXPECT_GT(kept, 0u);
}

}  // namespace
}  // namespace delmesh::test
