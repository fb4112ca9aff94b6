// Sliver removal (notes §4.4 and §2.2.4): dihedral-bound refinement followed by the
// improvement pass of sliver_improvement.h. The meshes must stay valid and conforming
// (check_mesh without the Delaunay test), keep volumes, markers and regions, be
// deterministic, and meet a 20-degree target on inputs without small angles.
#include <algorithm>
#include <cstdio>
#include <set>

#include "importers/import.h"
#include "test_plcs.h"
#include "tests/support/test_paths.h"
#include "toolkit/check/check_mesh.h"

namespace delmesh::test {
namespace {

MeshOptions sliver_options(double low = 20.0, double high = 150.0) {
  MeshOptions options;
  options.min_dihedral_deg = low;
  options.max_dihedral_deg = high;
  return options;
}

void expect_conforming(const Plc& plc, const MeshResult& r, const std::string& name) {
  CheckMeshOptions check;
  check.check_delaunay = false;  // flips and smoothing leave a non-Delaunay mesh
  const auto issues = check_mesh(r.mesh, plc, r.boundary_face_facets, check);
  EXPECT_TRUE(issues.empty()) << name << ": " << (issues.empty() ? "" : issues.front().message);
}

double stage_seconds(const MeshResult& r, const std::string& name) {
  for (const MeshStageStats& s : r.stats.stages)
    if (s.name == name) return s.seconds;
  return -1.0;
}

TEST(Tet3dSlivers, ProgrammaticPlcsStayValidAndMeetTwentyDegrees) {
  for (const TestPlc& input : all_test_plcs()) {
    MeshOptions options = sliver_options();
    // A volume bound gives the clean inputs interior tets (and slivers) to work on.
    if (!input.small_angles) options.max_volume = input.volume / 400.0;
    auto r = mesh_plc(input.plc, options);
    ASSERT_TRUE(r.has_value()) << input.name << ": " << r.error().message;
    expect_valid_mesh(input, *r);
    expect_conforming(input.plc, *r, input.name);
    EXPECT_GE(stage_seconds(*r, "slivers"), 0.0) << input.name << ": no slivers stage";
    const auto report = tet_quality_report(r->mesh, 2.0, 20.0, 150.0);
    std::printf("%-14s tets %6zu  dihedral %.2f..%.2f  outside [20,150] %zu  unmet %zu (%zu at small angles)\n",
                input.name.c_str(), r->mesh.tets.size(), report.min_dihedral_deg, report.max_dihedral_deg,
                report.outside_dihedral_window, r->stats.unmet_tets, r->stats.unmet_tets_at_small_angles);
    EXPECT_LE(r->stats.unmet_tets_at_small_angles, r->stats.unmet_tets) << input.name;
    if (!input.small_angles) {
      EXPECT_EQ(report.outside_dihedral_window, 0u) << input.name;
      EXPECT_GE(report.min_dihedral_deg, 20.0) << input.name;
      EXPECT_LE(report.max_dihedral_deg, 150.0) << input.name;
      EXPECT_EQ(r->status, MeshStatus::Complete) << input.name;
    } else {
      // Tets left outside the window are all counted as unmet.
      EXPECT_GE(r->stats.unmet_tets, report.outside_dihedral_window) << input.name;
    }
  }
}

std::size_t stage_steiner(const MeshResult& r, const std::string& name) {
  for (const MeshStageStats& s : r.stats.stages)
    if (s.name == name) return s.steiner_points;
  return 0;
}

TEST(Tet3dSlivers, VertexInsertionKeepsTheMeshValid) {
  // On a surface whose slivers flips and smoothing cannot all fix, the improvement pass
  // inserts vertices (the Steiner points of its stage); the mesh stays valid, conforming
  // and of the same volume, and beats the mesh of the same refinement without them.
  ImportOptions import_options;
  auto plc = import_file(corpus_dir() / "surface" / "trimesh-busted.stl", import_options);
  ASSERT_TRUE(plc.has_value()) << plc.error().message;
  auto r = mesh_plc(*plc, sliver_options());
  ASSERT_TRUE(r.has_value()) << r.error().message;
  expect_conforming(*plc, *r, "trimesh-busted");
  const std::size_t inserted = stage_steiner(*r, "slivers");
  const auto report = tet_quality_report(r->mesh, 2.0, 20.0, 150.0);
  std::printf("trimesh-busted tets %6zu  outside [20,150] %zu  vertices inserted by improvement %zu\n",
              r->mesh.tets.size(), report.outside_dihedral_window, inserted);
  EXPECT_GT(inserted, 0u);
  // The inserted vertices are the last ones and lie inside the domain: on no boundary face.
  std::set<std::uint32_t> on_boundary;
  for (const auto& f : r->mesh.boundary_faces) on_boundary.insert(f.begin(), f.end());
  std::size_t interior_new = 0;
  for (std::size_t v = r->mesh.points.size() - inserted; v < r->mesh.points.size(); ++v)
    interior_new += on_boundary.count(static_cast<std::uint32_t>(v)) == 0 ? 1 : 0;
  EXPECT_EQ(interior_new, inserted);
  EXPECT_LE(report.outside_dihedral_window * 10000, report.tets);  // at most 0.01%
}

TEST(Tet3dSlivers, OffCentersMeetTwentyDegreesAndFollowTheSeed) {
  // Chew's off-centers (MeshOptions::sliver_off_centers): valid, conforming meshes that
  // meet the window on the clean programmatic inputs; the same seed gives the same mesh,
  // another seed (or circumcenters) a different one.
  for (const TestPlc& input : {l_prism(), box_with_hole(), two_boxes()}) {
    MeshOptions options = sliver_options();
    options.max_volume = input.volume / 400.0;
    options.sliver_off_centers = true;
    auto r = mesh_plc(input.plc, options);
    ASSERT_TRUE(r.has_value()) << input.name << ": " << r.error().message;
    expect_valid_mesh(input, *r);
    expect_conforming(input.plc, *r, input.name);
    const auto report = tet_quality_report(r->mesh, 2.0, 20.0, 150.0);
    std::printf("%-14s off-centers: tets %6zu  dihedral %.2f..%.2f  outside [20,150] %zu\n", input.name.c_str(),
                r->mesh.tets.size(), report.min_dihedral_deg, report.max_dihedral_deg,
                report.outside_dihedral_window);
    EXPECT_EQ(report.outside_dihedral_window, 0u) << input.name;
  }
  const TestPlc input = l_prism();
  MeshOptions options = sliver_options();
  options.max_volume = input.volume / 400.0;
  auto centers = mesh_plc(input.plc, options);
  options.sliver_off_centers = true;
  auto a = mesh_plc(input.plc, options);
  auto b = mesh_plc(input.plc, options);
  options.seed = 7;
  auto c = mesh_plc(input.plc, options);
  ASSERT_TRUE(centers.has_value() && a.has_value() && b.has_value() && c.has_value());
  EXPECT_EQ(a->mesh.points, b->mesh.points);
  EXPECT_EQ(a->mesh.tets, b->mesh.tets);
  EXPECT_NE(a->mesh.points, c->mesh.points);
  EXPECT_NE(a->mesh.points, centers->mesh.points);
}

TEST(Tet3dSlivers, MarkersAndRegionsKept) {
  const TestPlc input = two_boxes();
  MeshOptions plain_options;
  plain_options.max_volume = 0.005;
  MeshOptions options = sliver_options();
  options.max_volume = plain_options.max_volume;
  auto plain = mesh_plc(input.plc, plain_options);
  auto improved = mesh_plc(input.plc, options);
  ASSERT_TRUE(plain.has_value() && improved.has_value());
  expect_valid_mesh(input, *improved);
  // The same boundary area per marker and the same volume per region.
  auto marker_area = [](const TetraMesh& m) {
    std::map<int, double> area;
    for (std::size_t f = 0; f < m.boundary_faces.size(); ++f) {
      const auto& v = m.boundary_faces[f];
      area[m.boundary_markers[f]] +=
          0.5 * (m.points[v[1]] - m.points[v[0]]).cross(m.points[v[2]] - m.points[v[0]]).norm();
    }
    return area;
  };
  const auto a0 = marker_area(plain->mesh), a1 = marker_area(improved->mesh);
  ASSERT_EQ(a0.size(), a1.size());
  for (const auto& [marker, area] : a0) EXPECT_NEAR(a1.at(marker), area, 1e-12) << "marker " << marker;
  std::set<int> regions(improved->mesh.tet_regions.begin(), improved->mesh.tet_regions.end());
  EXPECT_EQ(regions, (std::set<int>{1, 2}));
}

TEST(Tet3dSlivers, Deterministic) {
  const TestPlc input = box_with_hole();
  MeshOptions options = sliver_options(25.0, 145.0);
  options.max_volume = 0.2;
  auto a = mesh_plc(input.plc, options);
  auto b = mesh_plc(input.plc, options);
  ASSERT_TRUE(a.has_value() && b.has_value());
  ASSERT_EQ(a->mesh.points.size(), b->mesh.points.size());
  for (std::size_t i = 0; i < a->mesh.points.size(); ++i) ASSERT_EQ(a->mesh.points[i], b->mesh.points[i]) << i;
  EXPECT_EQ(a->mesh.tets, b->mesh.tets);
  EXPECT_EQ(a->mesh.boundary_faces, b->mesh.boundary_faces);
}

TEST(Tet3dSlivers, TargetBeatsRadiusEdgeAlone) {
  const TestPlc input = l_prism();
  MeshOptions plain_options;
  plain_options.max_volume = input.volume / 400.0;
  MeshOptions options = sliver_options();
  options.max_volume = plain_options.max_volume;
  auto plain = mesh_plc(input.plc, plain_options);
  auto improved = mesh_plc(input.plc, options);
  ASSERT_TRUE(plain.has_value() && improved.has_value());
  const auto q0 = tet_quality_report(plain->mesh, 2.0, 20.0, 150.0);
  const auto q1 = tet_quality_report(improved->mesh, 2.0, 20.0, 150.0);
  std::printf("l_prism radius-edge only: dihedral %.2f..%.2f, %zu of %zu tets outside [20,150]\n",
              q0.min_dihedral_deg, q0.max_dihedral_deg, q0.outside_dihedral_window, q0.tets);
  EXPECT_GT(q0.outside_dihedral_window, 0u);
  EXPECT_EQ(q1.outside_dihedral_window, 0u);
  EXPECT_GT(q1.min_dihedral_deg, q0.min_dihedral_deg);
  EXPECT_LT(q1.max_dihedral_deg, q0.max_dihedral_deg);
}

TEST(Tet3dSlivers, RejectsImpossibleTargets) {
  const TestPlc input = unit_cube();
  EXPECT_FALSE(mesh_plc(input.plc, sliver_options(71.0, 180.0)).has_value());
  EXPECT_FALSE(mesh_plc(input.plc, sliver_options(0.0, 60.0)).has_value());
}

TEST(Tet3dSlivers, CorpusSphereMeetsTwentyDegrees) {
  ImportOptions import_options;
  auto plc = import_file(corpus_dir() / "surface" / "cgal-sphere.off", import_options);
  ASSERT_TRUE(plc.has_value()) << plc.error().message;
  MeshOptions options = sliver_options();
  options.max_volume = 0.001;  // ~1000 tets, most of them slivers before improvement
  auto r = mesh_plc(*plc, options);
  ASSERT_TRUE(r.has_value()) << r.error().message;
  expect_conforming(*plc, *r, "cgal-sphere");
  const auto report = tet_quality_report(r->mesh, 2.0, 20.0, 150.0);
  std::printf("cgal-sphere    tets %6zu  dihedral %.2f..%.2f  outside [20,150] %zu\n", r->mesh.tets.size(),
              report.min_dihedral_deg, report.max_dihedral_deg, report.outside_dihedral_window);
  EXPECT_EQ(report.outside_dihedral_window, 0u);
  EXPECT_EQ(r->status, MeshStatus::Complete);
}

TEST(Tet3dSlivers, SkinnyTetsTheFloorsLeaveGetBetterAngles) {
  // gmsh-part.step: radius-edge refinement alone leaves hundreds of tets above the bound
  // where the termination floors stop it, away from small input angles. The improvement
  // pass ranks such tets by their angles too (a skinny tet may give way to skinny tets
  // with better angles, never worse), so at most 60% of them stay both skinny and
  // outside [20, 150]; the rest of the mesh keeps the bound. Valid and conforming.
  // (Measured: 135 unmet alone, 61 skinny and outside with the window, before quality
  // refinement split subfacets for rejected circumcenters that used to split nothing;
  // 127 and 71 since: radius-edge refinement alone leaves fewer.)
  ImportOptions import_options;
  auto plc = import_file(corpus_dir() / "step" / "gmsh-part.step", import_options);
  ASSERT_TRUE(plc.has_value()) << plc.error().message;
  auto plain = mesh_plc(*plc, MeshOptions{});
  auto r = mesh_plc(*plc, sliver_options());
  ASSERT_TRUE(plain.has_value() && r.has_value());
  expect_conforming(*plc, *r, "gmsh-part");
  std::size_t skinny_outside = 0;
  for (const auto& v : r->mesh.tets) {
    const auto &a = r->mesh.points[v[0]], &b = r->mesh.points[v[1]], &c = r->mesh.points[v[2]],
               &d = r->mesh.points[v[3]];
    skinny_outside += radius_edge_ratio(a, b, c, d) > 2.0 && dihedral_outside(a, b, c, d, 20.0, 150.0) ? 1 : 0;
  }
  std::printf("gmsh-part      unmet radius-edge alone %zu, skinny and outside [20,150] with the window %zu\n",
              plain->stats.unmet_tets, skinny_outside);
  EXPECT_GT(plain->stats.unmet_tets, 0u);
  EXPECT_LE(5 * skinny_outside, 3 * plain->stats.unmet_tets);
}

}  // namespace
}  // namespace delmesh::test
