// The §4.3 interior strategy (refiners/tet3d/interior_strategy.h): names; on the
// programmatic PLCs a graded mesh is valid, meets the requested bound like a uniform one
// and holds the tets away from the boundary to B = 1; small angles still terminate; a
// requested bound of 1 makes both strategies the same.
#include "refiners/tet3d/interior_strategy.h"
#include "test_plcs.h"

namespace delmesh::test {
namespace {

TEST(Tet3dInteriorStrategy, NamesRoundTrip) {
  for (const InteriorStrategy s : {InteriorStrategy::Uniform, InteriorStrategy::Graded}) {
    const auto parsed = parse_interior_strategy(to_string(s));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(*parsed, s);
  }
  EXPECT_FALSE(parse_interior_strategy("insertion-radius").has_value());
  EXPECT_FALSE(parse_interior_strategy("").has_value());
}

/// Largest radius-edge ratio among the tets none of whose vertices lies on a boundary face
/// (tets of the §4.3 interior class, whatever the strategy).
double max_ratio_away_from_boundary(const TetraMesh& mesh) {
  std::vector<char> on_boundary(mesh.points.size(), 0);
  for (const auto& f : mesh.boundary_faces) {
    for (const std::uint32_t v : f) on_boundary[v] = 1;
  }
  double worst = 0.0;
  for (const auto& t : mesh.tets) {
    if (on_boundary[t[0]] || on_boundary[t[1]] || on_boundary[t[2]] || on_boundary[t[3]]) continue;
    worst = std::max(worst, radius_edge_ratio(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]));
  }
  return worst;
}

TEST(Tet3dInteriorStrategy, GradedMeetsTheBoundAndHoldsTheInteriorToOne) {
  for (const TestPlc& input : {unit_cube(), box_with_hole(), l_prism()}) {
    MeshOptions options;
    options.max_radius_edge = 1.414;
    options.max_volume = input.volume / 1000.0;  // enough tets for an interior
    auto uniform = mesh_plc(input.plc, options);
    options.interior_strategy = InteriorStrategy::Graded;
    auto graded = mesh_plc(input.plc, options);
    ASSERT_TRUE(uniform.has_value()) << input.name << ": " << uniform.error().message;
    ASSERT_TRUE(graded.has_value()) << input.name << ": " << graded.error().message;
    expect_valid_mesh(input, *graded);
    const auto report = tet_quality_report(graded->mesh, 1.414);
    EXPECT_EQ(graded->status, MeshStatus::Complete) << input.name;
    EXPECT_EQ(graded->stats.unmet_tets, 0u) << input.name;
    EXPECT_LE(report.max_radius_edge, 1.414 + 1e-9) << input.name;
    const double u = max_ratio_away_from_boundary(uniform->mesh), g = max_ratio_away_from_boundary(graded->mesh);
    std::printf("%-14s uniform %6zu tets, interior max radius-edge %.3f; graded %6zu tets, interior max %.3f\n",
                input.name.c_str(), uniform->mesh.tets.size(), u, graded->mesh.tets.size(), g);
    EXPECT_GT(u, 1.0) << input.name;  // the uniform bound leaves interior tets above 1
    EXPECT_LE(g, 1.0 + 1e-9) << input.name;
  }
}

TEST(Tet3dInteriorStrategy, SmallAnglesStillTerminateAndCountAgainstTheRequestedBound) {
  const TestPlc input = sharp_wedge();
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.interior_strategy = InteriorStrategy::Graded;
  auto r = mesh_plc(input.plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  expect_valid_mesh(input, *r);
  EXPECT_EQ(r->status, MeshStatus::Partial);
  EXPECT_EQ(r->stats.unmet_tets, tet_quality_report(r->mesh, 1.414).above_radius_edge);
}

TEST(Tet3dInteriorStrategy, GradedIsCappedByTheRequestedBound) {
  // With B = 1, no higher than any §4.3 level, the graded strategy is the uniform one.
  const TestPlc input = l_prism();
  MeshOptions options;
  options.max_radius_edge = 1.0;
  options.max_steiner_points = 3000;
  auto uniform = mesh_plc(input.plc, options);
  options.interior_strategy = InteriorStrategy::Graded;
  auto graded = mesh_plc(input.plc, options);
  ASSERT_TRUE(uniform.has_value()) << uniform.error().message;
  ASSERT_TRUE(graded.has_value()) << graded.error().message;
  EXPECT_EQ(uniform->mesh.tets, graded->mesh.tets);
  EXPECT_EQ(uniform->mesh.points, graded->mesh.points);
}

}  // namespace
}  // namespace delmesh::test
