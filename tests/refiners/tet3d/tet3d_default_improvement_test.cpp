// The default improvement run (refiners/tet3d/default_improvement.h): without a dihedral
// window mesh_plc improves the tets with a dihedral angle below kDefaultMinDihedralDeg
// after refinement, never adding tets above the radius-edge or volume bounds, keeping the
// mesh valid and conforming with its markers, regions and volume, deterministically;
// MeshOptions::improve = false gives refinement's constrained Delaunay mesh.
#include <map>
#include <set>
#include <string>

#include "importers/import.h"
#include "refiners/tet3d/default_improvement.h"
#include "test_plcs.h"
#include "tests/support/test_paths.h"
#include "toolkit/check/check_mesh.h"

namespace delmesh::test {
namespace {

bool has_stage(const MeshResult& r, const std::string& name) {
  for (const MeshStageStats& s : r.stats.stages)
    if (s.name == name) return true;
  return false;
}

std::size_t below_target(const TetraMesh& mesh) {
  return tet_quality_report(mesh, 2.0, tet3d::kDefaultMinDihedralDeg, 180.0).outside_dihedral_window;
}

std::size_t above_bound(const TetraMesh& mesh, double bound) { return tet_quality_report(mesh, bound).above_radius_edge; }

std::map<int, double> region_volumes(const TetraMesh& mesh) {
  std::map<int, double> volume;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) volume[mesh.region_of(t)] += tet_volume(mesh, t);
  return volume;
}

void expect_checked(const Plc& plc, const MeshResult& r, bool delaunay, const std::string& name) {
  CheckMeshOptions check;
  check.check_delaunay = delaunay;
  const auto issues = check_mesh(r.mesh, plc, r.boundary_face_facets, check);
  EXPECT_TRUE(issues.empty()) << name << ": " << (issues.empty() ? "" : issues.front().message);
}

class Tet3dDefaultImprovement : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto read = import_file(test_data_dir() / "mesh" / "tetgen_example.poly", ImportOptions{});
    ASSERT_TRUE(read.has_value()) << read.error().describe();
    plc_ = new Plc(std::move(*read));
  }
  static void TearDownTestSuite() {
    delete plc_;
    plc_ = nullptr;
  }
  static Plc* plc_;
};

Plc* Tet3dDefaultImprovement::plc_ = nullptr;

TEST_F(Tet3dDefaultImprovement, LiftsTheSliversOfTetgensExample) {
  // TetGen's example.poly (a box with an inner box and a hole, right angles only) at the
  // default bound: refinement alone leaves tets below the target.
  MeshOptions off_options;
  off_options.improve = false;
  const auto off = mesh_plc(*plc_, off_options);
  ASSERT_TRUE(off.has_value()) << off.error().describe();
  const auto on = mesh_plc(*plc_, MeshOptions{});
  ASSERT_TRUE(on.has_value()) << on.error().describe();

  const auto before = tet_quality_report(off->mesh);
  const auto after = tet_quality_report(on->mesh);
  std::printf("tetgen_example: min dihedral %.2f -> %.2f, max %.2f -> %.2f, below %.0f deg %zu -> %zu, unmet %zu -> %zu\n",
              before.min_dihedral_deg, after.min_dihedral_deg, before.max_dihedral_deg, after.max_dihedral_deg,
              tet3d::kDefaultMinDihedralDeg, below_target(off->mesh), below_target(on->mesh), off->stats.unmet_tets,
              on->stats.unmet_tets);
  EXPECT_LT(before.min_dihedral_deg, tet3d::kDefaultMinDihedralDeg);
  EXPECT_GT(below_target(off->mesh), 0u);
  EXPECT_GE(after.min_dihedral_deg, tet3d::kDefaultMinDihedralDeg);
  EXPECT_EQ(below_target(on->mesh), 0u);
  EXPECT_LE(on->stats.unmet_tets, off->stats.unmet_tets);
  EXPECT_LE(above_bound(on->mesh, 2.0), above_bound(off->mesh, 2.0));

  // Off: refinement's constrained Delaunay mesh, no improvement stage.
  EXPECT_TRUE(off->constrained_delaunay);
  EXPECT_FALSE(has_stage(*off, "slivers"));
  expect_checked(*plc_, *off, true, "off");
  // On: valid and conforming, not Delaunay any more, same regions, volumes and markers.
  EXPECT_FALSE(on->constrained_delaunay);
  EXPECT_TRUE(has_stage(*on, "slivers"));
  expect_checked(*plc_, *on, false, "on");
  const auto volume_off = region_volumes(off->mesh), volume_on = region_volumes(on->mesh);
  ASSERT_EQ(volume_on.size(), volume_off.size());
  for (const auto& [region, volume] : volume_off) {
    ASSERT_TRUE(volume_on.count(region)) << "region " << region;
    EXPECT_NEAR(volume_on.at(region), volume, 1e-9 * volume) << "region " << region;
  }
  EXPECT_EQ(std::set<int>(on->mesh.boundary_markers.begin(), on->mesh.boundary_markers.end()),
            std::set<int>(off->mesh.boundary_markers.begin(), off->mesh.boundary_markers.end()));
}

TEST_F(Tet3dDefaultImprovement, IsDeterministic) {
  MeshOptions options;
  options.max_radius_edge = 1.414;
  const auto a = mesh_plc(*plc_, options);
  const auto b = mesh_plc(*plc_, options);
  ASSERT_TRUE(a.has_value() && b.has_value());
  EXPECT_EQ(a->mesh.points, b->mesh.points);
  EXPECT_EQ(a->mesh.tets, b->mesh.tets);
  EXPECT_EQ(a->mesh.boundary_faces, b->mesh.boundary_faces);
}

TEST(Tet3dDefaultImprovementPlcs, NeverAddsTetsAboveTheBounds) {
  // With a volume bound (interior tets, slivers among them) and at small input angles
  // (sharp_wedge: tets refinement's floors leave above the bound), the improvement keeps
  // the meshes valid and leaves no more tets above the radius-edge or volume bounds.
  for (const TestPlc& input : all_test_plcs()) {
    MeshOptions options;
    options.max_radius_edge = 1.414;
    if (!input.small_angles) options.max_volume = input.volume / 400.0;
    MeshOptions off_options = options;
    off_options.improve = false;
    const auto on = mesh_plc(input.plc, options);
    const auto off = mesh_plc(input.plc, off_options);
    ASSERT_TRUE(on.has_value() && off.has_value()) << input.name;
    expect_valid_mesh(input, *on);
    expect_checked(input.plc, *on, on->constrained_delaunay, input.name);
    EXPECT_LE(on->stats.unmet_tets, off->stats.unmet_tets) << input.name;
    EXPECT_LE(above_bound(on->mesh, 1.414), above_bound(off->mesh, 1.414)) << input.name;
    EXPECT_LE(below_target(on->mesh), below_target(off->mesh)) << input.name;
  }
}

}  // namespace
}  // namespace delmesh::test
