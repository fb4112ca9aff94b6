// Rejected circumcenters that used to leave skinny tets with nothing split
// (refiners/tet3d/quality_refinement.h): a tet whose circumcenter lies outside its region
// without encroaching a subfacet face of the tet. A prism over a regular 24-gon has two
// caps whose 24 boundary vertices are cocircular: the tets lying nearly flat on a cap,
// all four vertices on its boundary, have their circumcenters far off the cap, beyond
// every equatorial sphere. Such a tet is now deleted by splitting a cap subfacet whose
// circumcenter lies in its circumsphere (floored); before, 11 tets of this prism stayed
// above radius-edge 1.414, none of them at a small input angle.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "refiners/tet3d/mesh_plc.h"
#include "test_plcs.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh::test {
namespace {

TestPlc regular_prism(int sides, double height) {
  std::vector<std::array<double, 2>> polygon;
  for (int k = 0; k < sides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / sides;
    polygon.push_back({std::cos(a), std::sin(a)});
  }
  TestPlc t{"regular_prism", {}, 0.5 * sides * std::sin(2.0 * std::numbers::pi / sides) * height, {}, false};
  add_prism(t.plc, polygon, height);
  return t;
}

TEST(Tet3dRejectedPoints, FlatTetsOnACocircularCapAreRefined) {
  const TestPlc input = regular_prism(24, 4.0);
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.improve = false;  // refinement alone: a constrained Delaunay mesh
  const auto result = mesh_plc(input.plc, options);
  ASSERT_TRUE(result.has_value()) << result.error().describe();
  expect_valid_mesh(input, *result);
  EXPECT_TRUE(check_mesh(result->mesh, input.plc, result->boundary_face_facets).empty());
  std::size_t above = 0;
  for (const auto& v : result->mesh.tets) {
    const auto& p = result->mesh.points;
    if (radius_edge_ratio(p[v[0]], p[v[1]], p[v[2]], p[v[3]]) > options.max_radius_edge) ++above;
  }
  EXPECT_EQ(above, 0u);
  EXPECT_EQ(result->stats.unmet_tets, 0u);
  EXPECT_EQ(result->status, MeshStatus::Complete);
}

}  // namespace
}  // namespace delmesh::test
