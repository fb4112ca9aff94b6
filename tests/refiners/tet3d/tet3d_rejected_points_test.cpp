// Rejected circumcenters that used to leave skinny tets with nothing split
// (refiners/tet3d/quality_refinement.h): a tet whose circumcenter lies outside its region
// without encroaching a subfacet face of the tet. A prism over a regular 24-gon has two
// caps whose 24 boundary vertices are cocircular: the tets lying nearly flat on a cap,
// all four vertices on its boundary, have their circumcenters far off the cap, beyond
// every equatorial sphere. Such a tet is now deleted by splitting a cap subfacet whose
// circumcenter lies in its circumsphere (floored); before, 11 tets of this prism stayed
// above radius-edge 1.414, none of them at a small input angle.
// Second: a tet whose circumcenter is refused with nothing split (outside its region, or
// within a floor of the plane of an encroached subfacet whose own split the floors refuse)
// is split at another point of its circumsphere that respects the floors (split_inside in
// quality_refinement.cpp). On cgal_step.off (a needle of 0.00043 degrees and a strip 6e-4
// wide) refinement alone left 2 tets above 1.414 away from small input angles without it,
// none with it (162988 -> 163630 tets, `delmesh mesh --radius-edge 1.414 --no-improve`).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/mesh_plc.h"
#include "test_plcs.h"
#include "tests/support/test_paths.h"
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

TEST(Tet3dRejectedPoints, RefusedCircumcentersSplitTheTetAtAnotherPoint) {
  const auto plc = import_file(test_data_dir() / "mesh" / "cgal_step.off", ImportOptions{});
  ASSERT_TRUE(plc.has_value()) << plc.error().describe();
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.improve = false;  // refinement alone
  const auto result = mesh_plc(*plc, options);
  ASSERT_TRUE(result.has_value()) << result.error().describe();
  CheckMeshOptions check;
  check.check_delaunay = result->constrained_delaunay;
  EXPECT_TRUE(check_mesh(result->mesh, *plc, result->boundary_face_facets, check).empty());
  const auto& p = result->mesh.points;
  ASSERT_EQ(result->tet_at_small_angle.size(), result->mesh.tets.size());
  std::size_t above = 0, elsewhere = 0;
  for (std::size_t t = 0; t < result->mesh.tets.size(); ++t) {
    const auto& v = result->mesh.tets[t];
    if (!(radius_edge_ratio(p[v[0]], p[v[1]], p[v[2]], p[v[3]]) > options.max_radius_edge)) continue;
    ++above;
    if (!result->tet_at_small_angle[t]) ++elsewhere;
  }
  EXPECT_GT(above, 0u);  // the needle's and the strip's small angles leave tets
  EXPECT_EQ(elsewhere, 0u);
  EXPECT_EQ(result->stats.unmet_tets, above);
}

}  // namespace
}  // namespace delmesh::test
