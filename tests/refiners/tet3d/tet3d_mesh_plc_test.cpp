// mesh_plc on programmatic PLCs: validity, volumes, regions, quality, small angles,
// determinism.
#include <chrono>

#include "test_plcs.h"

namespace delmesh::test {
namespace {

TEST(Tet3dMeshPlc, ProgrammaticPlcsAtRadiusEdge1414) {
  for (const TestPlc& input : all_test_plcs()) {
    MeshOptions options;
    options.max_radius_edge = 1.414;
    auto r = mesh_plc(input.plc, options);
    ASSERT_TRUE(r.has_value()) << input.name << ": " << r.error().message;
    expect_valid_mesh(input, *r);
    const auto report = tet_quality_report(r->mesh, 1.414);
    std::printf("%-14s tets %7zu  points %6zu  max radius-edge %.3f  unmet %zu (%zu at small angles)  %s\n",
                input.name.c_str(), r->mesh.tets.size(), r->mesh.points.size(), report.max_radius_edge,
                r->stats.unmet_tets, r->stats.unmet_tets_at_small_angles, to_string(r->status));
    if (!input.small_angles) {
      EXPECT_EQ(r->status, MeshStatus::Complete) << input.name;
      EXPECT_EQ(r->stats.unmet_tets, 0u) << input.name;
      EXPECT_LE(report.max_radius_edge, 1.414 + 1e-9) << input.name;
    }
  }
}

}  // namespace
}  // namespace delmesh::test
