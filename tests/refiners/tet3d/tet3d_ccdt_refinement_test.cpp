// Quality refinement on a conforming CDT (RefineState::constrained; notes §2.1.7, §3.5.1,
// §4.2.1 last paragraph): two boxes 0.05 apart, whose exterior gap forces the conforming
// recovery to split the facing facets down to the gap's size, are refined on the CCDT with
// far fewer vertices; the result passes check_mesh and meets the radius-edge bound, and is
// the same from run to run.
#include <gtest/gtest.h>

#include "refiners/tet3d/mesh_plc.h"
#include "test_plcs.h"
#include "toolkit/check/check_mesh.h"

namespace delmesh::test {
namespace {

/// check_mesh as `delmesh mesh --check` runs it: the Delaunay test only while the result
/// is constrained Delaunay.
std::vector<MeshCheckIssue> check(const MeshResult& r, const Plc& plc) {
  CheckMeshOptions options;
  options.check_delaunay = r.constrained_delaunay;
  return check_mesh(r.mesh, plc, r.boundary_face_facets, options);
}

TestPlc boxes_with_gap() {
  TestPlc t{"boxes_with_gap", {}, 32.0, {}, false};
  add_box(t.plc, Vec3(0, 0, 0), Vec3(4, 4, 1), 1);
  // Offset across the gap, so that the second plate's corners face the first plate's
  // facet interior (and its edges cross the facet's diametral spheres).
  add_box(t.plc, Vec3(0.5, 0.3, 1.05), Vec3(4.5, 4.3, 2.05), 11);
  return t;
}

MeshOptions options_for(FacetRecovery recovery) {
  MeshOptions options;
  options.max_radius_edge = 1.414;
  options.facet_recovery = recovery;
  return options;
}

TEST(Tet3dCcdtRefinement, ThinExteriorGapNeedsFarFewerPointsOnTheCcdt) {
  const TestPlc input = boxes_with_gap();
  auto conforming = mesh_plc(input.plc, options_for(FacetRecovery::Conforming));
  auto ccdt = mesh_plc(input.plc, options_for(FacetRecovery::Ccdt));
  ASSERT_TRUE(conforming.has_value());
  ASSERT_TRUE(ccdt.has_value()) << ccdt.error().message;
  EXPECT_TRUE(ccdt->stats.ccdt.used);
  EXPECT_EQ(ccdt->stats.unmet_tets, 0u) << ccdt->stats.ccdt.cavity_shrinks << " shrinks, "
                                       << ccdt->stats.ccdt.cavity_rejections << " rejections, conforming unmet "
                                       << conforming->stats.unmet_tets << ", at small angles "
                                       << ccdt->stats.unmet_tets_at_small_angles;
  const auto issues = check(*ccdt, input.plc);
  for (const MeshCheckIssue& issue : issues) ADD_FAILURE() << issue.message;
  // Measured: 9322 vertices (37960 tets) conforming, 263 (660 tets) on the CCDT, none above
  // the bound either way (2 cavities shrunk, no point dropped).
  EXPECT_LT(4 * ccdt->mesh.points.size(), conforming->mesh.points.size())
      << ccdt->mesh.points.size() << " vertices on the CCDT, " << conforming->mesh.points.size() << " conforming";
}

TEST(Tet3dCcdtRefinement, SameMeshFromRunToRun) {
  const TestPlc input = boxes_with_gap();
  auto a = mesh_plc(input.plc, options_for(FacetRecovery::Ccdt));
  auto b = mesh_plc(input.plc, options_for(FacetRecovery::Ccdt));
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->mesh.points, b->mesh.points);
  EXPECT_EQ(a->mesh.tets, b->mesh.tets);
}

TEST(Tet3dCcdtRefinement, SmallPlcsRefineOnTheCcdtAndPassCheckMesh) {
  for (const TestPlc& input : all_test_plcs()) {
    auto r = mesh_plc(input.plc, options_for(FacetRecovery::Ccdt));
    ASSERT_TRUE(r.has_value()) << input.name << ": " << r.error().message;
    const auto issues = check(*r, input.plc);
    for (const MeshCheckIssue& issue : issues) ADD_FAILURE() << input.name << ": " << issue.message;
    if (!input.small_angles) {
      EXPECT_EQ(r->stats.unmet_tets, 0u) << input.name;
    }
  }
}

}  // namespace
}  // namespace delmesh::test
