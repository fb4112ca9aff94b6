// The facet CDTs of PLC preparation (refiners/tet3d/facet_cdt.h, notes §4.2.1): a facet
// that is one triangle takes a shortcut (lone_triangle) that must give exactly what the
// general 2D CDT (triangulate_facet) gives, in the same vertex, triangle and subsegment
// order, since the facet triangulations and the segment ids are built from it:
//   * random triangles, in both orientations, every rotation of the polygon, projected
//     along each axis, with coordinates drawn from a coarse grid too (ties in the
//     Hilbert order) and nearly collinear ones;
//   * every other facet (a quad, a triangle with a hole point, two polygons, a repeated
//     vertex, a triangle collinear in its projection) is left to the general path.
#include <gtest/gtest.h>

#include <random>

#include "refiners/tet3d/facet_cdt.h"

namespace delmesh::tet3d {
namespace {

Plc triangle_plc(const std::array<Vec3, 3>& corners, const Plc::Polygon& polygon) {
  Plc plc;
  plc.points.assign(corners.begin(), corners.end());
  plc.facets.push_back({});
  plc.facets[0].polygons = {polygon};
  return plc;
}

void expect_same_cdt(const Plc& plc, Axis axis) {
  FacetCdt lone, general;
  ASSERT_TRUE(lone_triangle(plc, plc.facets[0], axis, lone));
  ASSERT_TRUE(triangulate_facet(plc, plc.facets[0], axis, general).has_value());
  EXPECT_EQ(lone.global, general.global);
  EXPECT_EQ(lone.triangles, general.triangles);
  EXPECT_EQ(lone.constrained, general.constrained);
}

TEST(Tet3dFacetCdt, LoneTriangleGivesTheGeneralCdt) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> real(-10.0, 10.0);
  std::uniform_int_distribution<int> grid(0, 3);
  const std::vector<Plc::Polygon> rotations{{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  std::size_t compared = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::array<Vec3, 3> corners;
    for (Vec3& c : corners) {
      c = trial % 3 == 0 ? Vec3(grid(rng), grid(rng), grid(rng)) : Vec3(real(rng), real(rng), real(rng));
    }
    if (trial % 5 == 1) corners[2] = 0.5 * (corners[0] + corners[1]) + Vec3(1e-9, -1e-9, 1e-9);
    for (const Plc::Polygon& polygon : rotations) {
      const Plc plc = triangle_plc(corners, polygon);
      for (const Axis axis : {Axis::X, Axis::Y, Axis::Z}) {
        const Vec3 &a = plc.points[0], &b = plc.points[1], &c = plc.points[2];
        if (predicates::orient2d_projected(a.data(), b.data(), c.data(), axis) == Sign::Zero) continue;
        expect_same_cdt(plc, axis);
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 8000u);
}

TEST(Tet3dFacetCdt, OtherFacetsTakeTheGeneralPath) {
  const std::array<Vec3, 3> corners{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
  FacetCdt cdt;
  Plc plc = triangle_plc(corners, {0, 1, 2});
  ASSERT_TRUE(lone_triangle(plc, plc.facets[0], Axis::Z, cdt));
  Plc with_hole = plc;
  with_hole.facets[0].holes.push_back(Vec3(1, 1, 0));
  EXPECT_FALSE(lone_triangle(with_hole, with_hole.facets[0], Axis::Z, cdt));
  Plc repeated = triangle_plc(corners, {0, 1, 1});
  EXPECT_FALSE(lone_triangle(repeated, repeated.facets[0], Axis::Z, cdt));
  Plc two_loops = plc;
  two_loops.facets[0].polygons.push_back({0, 1});
  EXPECT_FALSE(lone_triangle(two_loops, two_loops.facets[0], Axis::Z, cdt));
  Plc quad = plc;
  quad.points.push_back(Vec3(4, 4, 0));
  quad.facets[0].polygons = {{0, 1, 3, 2}};
  EXPECT_FALSE(lone_triangle(quad, quad.facets[0], Axis::Z, cdt));
  // Seen along x the triangle is a segment.
  EXPECT_FALSE(lone_triangle(plc, plc.facets[0], Axis::X, cdt));
}

}  // namespace
}  // namespace delmesh::tet3d
