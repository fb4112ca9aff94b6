// Unit tests of the merging of coordinate-plane values within the plane tolerance
// (importers/step/coordinate_planes.h): values a few ulps apart become one, groups span at
// most the tolerance, axes stay apart, the most used value wins, 0 merges nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "importers/step/coordinate_planes.h"

namespace delmesh::step {
namespace {

// The four placements of one plane found in an assembly of the corpus (SolidWorks).
constexpr double kPlaneA = 46.718433566482929;
constexpr double kPlaneB = 46.718433566482943;
constexpr double kPlaneC = 46.71843356648295;
constexpr double kPlaneD = 46.718433566482965;

TEST(CoordinatePlanes, ValuesUlpsApartBecomeTheMostUsedOne) {
  ASSERT_LT(kPlaneA, kPlaneB);
  ASSERT_LT(kPlaneC, kPlaneD);
  std::vector<PlaneSnap> snaps = {{0, 1, kPlaneA}, {1, 1, kPlaneB}, {2, 1, kPlaneC}, {3, 1, kPlaneD},
                                  {4, 1, kPlaneD}, {5, 1, kPlaneD}, {0, 1, kPlaneD}};
  EXPECT_EQ(merge_coordinate_plane_values(snaps, 1e-9), 3);
  for (const PlaneSnap& snap : snaps) EXPECT_EQ(snap.value, kPlaneD);
  // Vertex 0 was asked for two values (A and D): now it is asked for one.
  EXPECT_EQ(snaps[0].value, snaps[6].value);
}

TEST(CoordinatePlanes, TieKeepsTheSmallestValue) {
  std::vector<PlaneSnap> snaps = {{0, 2, 1.0 + 0x1p-52}, {1, 2, 1.0}};
  EXPECT_EQ(merge_coordinate_plane_values(snaps, 1e-12), 1);
  EXPECT_EQ(snaps[0].value, 1.0);
  EXPECT_EQ(snaps[1].value, 1.0);
}

TEST(CoordinatePlanes, DistinctPlanesAndAxesStayApart) {
  // 0, 0.5e-9 and 1e-9 chain within 1e-9 of the first; 1.6e-9 is more than 1e-9 above 0,
  // so it starts a group of its own although it lies within 1e-9 of its lower neighbour.
  std::vector<PlaneSnap> snaps = {{0, 0, 0.0}, {1, 0, 0.5e-9}, {2, 0, 1e-9}, {3, 0, 1.6e-9},
                                  {4, 0, 1.0}, {5, 1, 0.5e-9}, {6, 2, 0.25e-9}};
  EXPECT_EQ(merge_coordinate_plane_values(snaps, 1e-9), 2);
  EXPECT_EQ(snaps[0].value, 0.0);
  EXPECT_EQ(snaps[1].value, 0.0);
  EXPECT_EQ(snaps[2].value, 0.0);
  EXPECT_EQ(snaps[3].value, 1.6e-9);
  EXPECT_EQ(snaps[4].value, 1.0);
  EXPECT_EQ(snaps[5].value, 0.5e-9);  // another axis: not merged with x = 0
  EXPECT_EQ(snaps[6].value, 0.25e-9);
}

TEST(CoordinatePlanes, ZeroToleranceChangesNothing) {
  std::vector<PlaneSnap> snaps = {{0, 1, kPlaneA}, {1, 1, kPlaneB}};
  EXPECT_EQ(merge_coordinate_plane_values(snaps, 0.0), 0);
  EXPECT_EQ(snaps[0].value, kPlaneA);
  EXPECT_EQ(snaps[1].value, kPlaneB);
}

}  // namespace
}  // namespace delmesh::step
