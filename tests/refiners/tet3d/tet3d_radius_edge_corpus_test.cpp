// Radius-edge bound 1.414 on the corpus inputs item 9 of issue 5 lists as free of small
// input angles: the STEP models (tessellated by the importer with the bound
// tet3d::tessellation_min_angle_deg(1.414) = 26 degrees, as `delmesh mesh --radius-edge
// 1.414` does; 20 where 26 makes it give up on faces), TetGen's example.poly and
// the clean corpus surfaces are meshed with MeshOptions::max_radius_edge = 1.414 (other
// options at their defaults, no Steiner budget) and the result is recounted independently
// of the refiner's bookkeeping:
//   * valid and conforming: check_mesh finds nothing (constrained Delaunay included
//     unless the default improvement changed the mesh: MeshResult::constrained_delaunay);
//   * the unmet counters of MeshStats cover a recount on the output (tets above 1.414, and
//     of those the ones touching a small input angle, MeshResult::tet_at_small_angle; the
//     counters add the tets above a volume bound), and the status is Partial exactly when
//     tets are unmet;
//   * at most 0.1% of the tets that touch no small input angle exceed 1.414 ("elsewhere").
//     The tessellations do have small angles by the §4.2.3 rules (refiners/tet3d/
//     small_angles.h): most of their vertices are corners of triangles below 60 degrees
//     (1257 of the 1641 input vertices of pocc-io1-ug-214), so the tets at those vertices
//     are counted apart, as the lead's measure of item 9 does.
// Inputs that miss the target today, or take minutes, are listed with the measured figures
// (on a loaded 2-core machine) and not run; fixing one means deleting its reason. Each input
// runs in a child process with a hang guard.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/angle_bearing.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/corpus_inputs.h"
#include "tests/support/forked_run.h"
#include "tests/support/test_paths.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {
namespace {

constexpr double kBound = 1.414;

struct RadiusEdgeInput {
  const char* path;  ///< relative to corpus_dir(), or "data:" + relative to test_data_dir()
  /// Measured failure of the target, or why the input is not run (nullptr: it runs).
  const char* known_failure = nullptr;
  /// For an input with small input angles: the most tets above the bound away from them
  /// (-1: only the 0.1% target).
  int max_elsewhere = -1;
};

// Measured today at B = 1.414 (tets, tets above the bound away from small angles and their
// share; CPU s of the CLI without --check on a loaded 2-core machine).
const RadiusEdgeInput kInputs[] = {
    // With its region volume bounds (the default options, as `delmesh mesh` does): 24821
    // tets, none above 1.414 (one above its region's volume bound). Without the volume
    // bounds 5 of 1020 tets stay above 1.414 (0.49%).
    {"data:mesh/tetgen_example.poly"},
    // Clean corpus surfaces (no triangle angle under 15 degrees, no dihedral under 60).
    {"surface/cgal-fandisk.off"},
    {"surface/cgal-sphere.off"},
    {"surface/trimesh-busted.stl"},
    // 582569 tets, 4 above 1.414, 1 elsewhere; 7.4 CPU s with --check.
    {"surface/cgal-bear.off"},
    // 2454312 tets, 225 above 1.414 (0.009%), 4 elsewhere; 33 CPU s with --check.
    {"surface/cgal-bunny00.off"},
    // Surfaces with small input angles (needle triangles, thin wedges), with the tets left
    // above 1.414 away from them today. A tet whose circumcenter encroaches a subfacet
    // whose split the floor refuses (its circumcenter encroaches a subsegment too short to
    // split) is split at its own circumcenter when that lies at least the floor off the
    // subfacet's plane and deletes no subfacet (quality_refinement.h); before, 5 such tets
    // of 312615 stayed above 1.414 on cgal-boeing (2.2 degree corners of needle fans) and 8
    // of 648836 on cgal-dino. Then 312753 tets, 5441 above 1.414, 2 elsewhere (3.4 CPU s
    // with --check); 649425 tets, 4889 above, 2 elsewhere (7.1 CPU s). Since boundary
    // recovery splits an encroached subfacet only above the field floor too
    // (boundary_recovery.h; facets stage 6029 -> 6008 Steiner points) cgal-boeing has
    // 311647 tets, 5448 above 1.414, 3 elsewhere. Since the floors on a segment follow the
    // gap to the segments of its facet that share no vertex with it (narrow_facet_floor.h;
    // the importer merges its coplanar triangles into strips 0.2 wide among others) 317747
    // tets, 5463 above, 5 elsewhere: the 2 more lie at (1.91, -11.81, -1.705) beside a fan
    // of needle triangles (corners of 1.3-4.5 degrees), at the edge of its floor zone (of the
    // tets within 0.1 of that point, 10 of 455 above the bound, 8 of them at small angles;
    // 9 of 432, all at small angles, before). Since a tet whose circumcenter is refused with
    // nothing split is split at a point between its circumcenter and centroid that respects
    // the floors, or toward one of its vertices (quality_refinement.cpp, split_inside):
    // 321077 tets, 5359 above, 2 elsewhere (5 before); cgal-dino 652152 tets, 4835 above, 0
    // elsewhere (648835 tets, 4883 above, 2 elsewhere before; this test). Since the
    // radius-edge polish moves the interior vertex the 2 left shared, 0.002 above facet 347
    // (radius_edge_polish.h): 324429 tets, 5198 above, 0 elsewhere (5201 above, 2 elsewhere
    // before; the CLI, --stats).
    {"surface/cgal-boeing.off", nullptr, 0},
    {"surface/cgal-dino.off", nullptr, 0},
    // A needle of 0.00043 degrees and a strip 6e-4 wide and 2168 long (issue 5 item 4):
    // stopped at the recovery bound before its segments split on a common grid and
    // recovery's subfacet splits respected the field floor; now 160856 tets, 17125 above
    // 1.414, 2 elsewhere (3290 + 3540 recovery Steiner points; 9.8 s of meshing on a loaded
    // machine, --stats); 161504 tets, 17129 above, 0 elsewhere since split_inside
    // (quality_refinement.cpp; this test).
    {"surface/cgal-step.off", nullptr, 0},
    // 200830 tets, 5623 above 1.414, 2 elsewhere (4 CPU s): tets reaching across the 38.3
    // degree wedge between facets 402 and 465 where it is narrower than two floors count as
    // touching the small angle (small_angles.h, rule (f)); 11 elsewhere before the rule,
    // all of them across that wedge, 0.19-0.37 from its sharp segment. 202828 tets, 5394
    // above, 0 elsewhere (this test) since split_inside (quality_refinement.cpp); 201894
    // tets, 5423 above, 0 elsewhere before (main's CLI, --stats).
    {"surface/gmsh-netgen-hinge.stl", nullptr, 0},
    // Tets whose circumradius is 1.4-1.6 floors beside subsegments too short to split
    // (their circumcenter within a floor of the plane of the subfacet it encroaches, or
    // deleting a subfacet): split_inside's points toward the centroid and the vertices all
    // lay within a floor of a vertex or of that plane; with points toward 26 fixed
    // directions of the circumsphere too (quality_refinement.cpp) 1476158 tets, 20840 above
    // 1.414, 1 elsewhere (1468752 tets, 21005 above, 9 elsewhere before; the CLI, --stats,
    // 9.3 user CPU s without --check against 7.2 on a loaded machine); 1475883 tets, 20844
    // above, 1 elsewhere since split_inside splits the subsegments its points encroach;
    // 20843 above, 0 elsewhere since the radius-edge polish moves the tet's interior vertex
    // (radius_edge_polish.h; its two vertices on the arms of a 16.5 degree corner lie 1.10
    // floors apart, just beyond rule (d) of small_angles.h).
    {"surface/occt-sh2.stl", nullptr, 0},
    // The same at the first shell of a 33.5 degree corner (its arms 1.05 floors apart):
    // 639973 tets, 2177 above 1.414, 1 elsewhere; 2176 above, 0 elsewhere since the
    // radius-edge polish moves the tet's interior vertex (the CLI, --stats; 4.3-5.2 user CPU
    // s without --check).
    {"surface/cgal-knot2.off", nullptr, 0},
    // A circumcenter whose cavity held a vertex 0.00072 from it, under the floor 0.00153
    // (circumradius 0.0020), was inserted: the edge it made left 3 tets above 1.414 with
    // four interior vertices. Since the insertion radius of a circumcenter is checked
    // against the floor (quality_refinement.cpp) 831430 tets, 11019 above 1.414, 0
    // elsewhere (824400 tets, 11108 above, 4 elsewhere before; the CLI, --stats, 6.2 user
    // CPU s without --check against 5.2); 831387 tets, 11019 above, 0 elsewhere since
    // split_inside splits the subsegments its points encroach.
    {"surface/cgal-couplingdown.off", nullptr, 0},
    // Two degenerate input triangles merged into a 4-gon facet 21.3 long and 0.001-0.016
    // wide (and its mirror image) at x = +-142.5, y ~ -159: 4219548 tets, 64681 above 1.414,
    // 26 elsewhere (38 s of meshing in the CLI without --check) since the floors on a segment
    // follow the gap to the segments of its facet that share no vertex with it
    // (narrow_facet_floor.h); 3993389 tets, 66818 above, 148 elsewhere (128 of them at the
    // two 4-gons) before. 4234131 tets, 64573 above, 10 elsewhere since a refused
    // circumcenter is replaced by another point of the circumsphere (quality_refinement.cpp,
    // split_inside; 34.6 user CPU s in the CLI without --check). 4260920 tets, 64636 above,
    // 7 elsewhere since a circumcenter's insertion radius is checked against the floor and
    // split_inside tries points toward 26 fixed directions of the circumsphere too (32.0 user
    // CPU s in the CLI without --check, 32.3 before on the same loaded machine); 4262247
    // tets, 64609 above, 7 elsewhere since split_inside splits the subsegments its points
    // encroach; 64598 above, 0 elsewhere since the radius-edge polish moves interior vertices
    // of the tets left (radius_edge_polish.h; 5 moves; 34.9 user CPU s in the CLI without
    // --check, 34.5 before, single runs).
    {"surface/occt-tr12j.stl", nullptr, 0},
    {"surface/occt-propeller.stl",
     "not run: about a minute (45-60 s of meshing in the CLI without --check); 3988639 tets, 202450 above "
     "1.414, 2 elsewhere since the radius-edge polish (radius_edge_polish.h; the 2 at blade tips where "
     "the circumsphere lies almost all outside the domain); 202452 above, "
     "3 elsewhere since split_inside splits the subsegments its points encroach; 3988442 tets, "
     "202412 above, 3 elsewhere since a circumcenter's insertion radius is checked against the floor and "
     "split_inside tries 26 fixed directions too (quality_refinement.cpp); 3966331 tets, 203454 above, "
     "5 elsewhere since split_inside; 3953123 tets, 203731 above, 13 "
     "elsewhere before and since narrow_facet_floor.h (27 before that, 14 of them on its planar strips "
     "31 long and 0.1-0.2 wide at x ~ 61.3, z ~ -88.5)"},
    // STEP models.
    {"step/pocc-io1-ug-214.stp"},
    {"step/as-wavy-cube.stp"},
    {"step/gmsh-angled.step"},
    {"step/as-mechanism.stp"},
    {"step/gmsh-boundary-colors.stp"},
    {"step/pocc-multi-shape-root.stp"},
    // 653756 tets, 101 above 1.414 (0.015%), 88 elsewhere; before the split rules for
    // rejected circumcenters (quality_refinement.h) and the 26-degree tessellation,
    // 573314 tets, 1107 above 1.414 (0.19%), 509 elsewhere (0.089%).
    {"step/as-anc101.stp"},
    // 557748 tets, 532 above 1.414 (0.095%), 271 elsewhere (0.049%); before: 0.31%, 0.13%.
    {"step/as-capot-40mm.stp"},
    // 310722 tets, 161 above 1.414 (0.052%), 127 elsewhere; before: 0.27%, 0.135%.
    {"step/as-tie-rod.step"},
    // 853893 tets, 230 above 1.414 (0.027%), 136 elsewhere; before: 0.24%, 0.115%.
    {"step/gmsh-as1-tu-203.stp"},
    // 79300 tets, 261 above 1.414 (0.33%), 2 elsewhere (the same with and without
    // small_angles.h rule (e)): nearly all lie at the 1.05 degree corners of two wall faces
    // at (56.9, +-7.94, 61.92) and at facet corners of 0 and 5.4 degrees (docs/MESHING.md,
    // "Termination of quality refinement"), in the floor zones of those angles (rule (d);
    // 249 elsewhere before the rule).
    {"step/gmsh-part.step"},
    // 129030 tets, 39 above 1.414 (0.030%), 36 elsewhere; before: 0.49%, 0.37%.
    {"step/pocc-eight-cyl.stp"},
    // 1476741 tets, 4955 above 1.414 (0.34%), 8 elsewhere (this test) since the importer's
    // lifted points; 1448603 tets, 4932 above, 8 elsewhere before (21 CPU s with --check).
    {"step/gmsh-fusee-rocket.stp"},
    // 815459 tets, 136 above 1.414 (0.017%), 20 elsewhere; 16 CPU s with --check.
    {"step/gmsh-laufrad-impeller.stp"},
    // 269356 tets, 25 above 1.414 (0.009%), 20 elsewhere, 4 CPU s; before the split rules
    // and the 26-degree tessellation 248468 tets, 347 above (0.14%), 162 elsewhere.
    {"step/gmsh-mambo-s34.step"},
    // 449867 tets, 113 above 1.414 (0.025%), 0 elsewhere; 9 CPU s with --check (646934
    // tets, 836 above, before the pole handling of the import).
    {"step/gmsh-periodic-u.step"},
    // Tessellated at 20 degrees: at 26 surface refinement gives up on B-spline face 1.
    // 165766 tets, 600 above 1.414 (0.36%), 0 elsewhere (this test) since the importer's
    // lifted points (166266 tets, 570 above, 0 elsewhere before; 392 elsewhere before rule
    // (d) of small_angles.h).
    {"step/gmsh-t20-data.step"},
    // 349275 tets, 48 above 1.414 (0.014%), 24 elsewhere; 6 CPU s.
    {"step/gmsh-wrenchnut.stp"},
    // 689646 tets, 138 above 1.414 (0.020%), 113 elsewhere; 9 CPU s.
    {"step/occt-linkrods.step"},
    // 93264 tets, 159 above 1.414 (0.17%), 53 elsewhere (0.057%); tessellated at 20
    // degrees: at 26 surface refinement gives up on its torus (it folds).
    {"step/occt-screw.step"},
    // Tessellated at 26 degrees since the importer blends extrusion face 3's edge offsets
    // into it (offset_blend.h; at 26 surface refinement excluded extrusion faces 3 and 6
    // before, and the import fell back to 20): 104583 tets, 16 above 1.414 (0.015%), all at
    // small angles, 5.0 s of wall time with --check (delmesh mesh --stats). Before: 160069
    // tets, 13422 above (8.4%), 132 elsewhere (0.082%), all at the trailing edge's lip,
    // with face 3 refined on its own tessellation (5.9 degrees); earlier 408911 tets, 29268
    // above (7.2%), 8 elsewhere (0.002%) while faces 3 and 4 kept BRepMesh's needles, and
    // with four such faces before that, 338789 tets, 25255 above (7.5%), 2 elsewhere.
    {"step/gmsh-t106-blade.step"},
    // Tessellated at 20 degrees since the importer's lifted points: at 26 surface refinement
    // folds B-spline face 3 (a wing tip). 889221 tets, 1517 above 1.414 (0.17%), 2 elsewhere
    // (this test, 21 s of wall time); at 26 degrees before, 939126 tets, 460 above (0.049%),
    // 3 elsewhere after the importer's pole rules (928426 tets, 550 above, 34 elsewhere before
    // them, counted before rule (c) by vertex; 15 CPU s with --check).
    {"step/gmsh-wing-fuselage.step"},
    // Meshed on a CCDT (its conforming facet recovery stops at the 0.0508 clearance under
    // its tabs; mesh_plc.h): 613328 tets, 505 above 1.414, 484 of them away from small
    // angles (0.079%), 17.6 CPU s with the conforming attempt (delmesh mesh --radius-edge
    // 1.414 --stats; the same mesh with --facet-recovery ccdt, 12.9 CPU s with --check).
    // Before a constrained split's insertion radius counted only vertices of domain tets
    // (boundary_split.h): 612703 tets, 1044 away from small angles (0.17%), not run.
    {"step/trimesh-box-sides.step"},
    {"step/gmsh-cube-fillet.stp", "not run: an open set of faces, refused by the importer (tet3d_corpus_test.cpp)"},
};

void PrintTo(const RadiusEdgeInput& input, std::ostream* os) { *os << input.path; }

std::filesystem::path input_path(const RadiusEdgeInput& input) { return test::corpus_input_path(input.path); }

TEST(Tet3dRadiusEdgeCorpus, ListsEverySTEPModel) {
  std::vector<std::string> listed;
  for (const RadiusEdgeInput& input : kInputs) listed.emplace_back(input.path);
  for (const auto& entry : std::filesystem::directory_iterator(test::corpus_dir() / "step")) {
    const std::string path = "step/" + entry.path().filename().string();
    EXPECT_NE(std::find(listed.begin(), listed.end(), path), listed.end()) << path << " is not listed";
  }
  for (const RadiusEdgeInput& input : kInputs) EXPECT_TRUE(std::filesystem::exists(input_path(input))) << input.path;
}

/// Imports and meshes one input; returns the summary line, then one line per failure.
std::string mesh_and_check(const RadiusEdgeInput& input) {
  std::vector<std::string> failures;
  auto expect = [&](bool ok, const std::string& what) {
    if (!ok) failures.push_back(what);
  };
  auto finish = [&](const std::string& summary) {
    std::string text = summary + "\n";
    for (const std::string& f : failures) text += f + "\n";
    return text;
  };
  // As `delmesh mesh --radius-edge 1.414` imports a CAD model: curved faces refined to
  // 26 degrees, above the bearing threshold of the bound (angle_bearing.h).
  ImportOptions import_options;
  import_options.step.surface_min_angle_deg = tet3d::tessellation_min_angle_deg(kBound);
  auto plc = import_file(input_path(input), import_options);
  if (!plc) {
    expect(false, "import failed: " + plc.error().describe());
    return finish("import failed");
  }
  MeshOptions options;
  options.max_radius_edge = kBound;
  auto result = mesh_plc(*plc, options);
  if (!result) {
    expect(false, "mesh_plc failed: " + result.error().describe());
    return finish("mesh failed");
  }
  const TetraMesh& mesh = result->mesh;
  const MeshStats& stats = result->stats;
  const auto& small = result->tet_at_small_angle;
  if (mesh.tets.empty() || small.size() != mesh.tets.size()) {
    expect(false, "no tets, or tet_at_small_angle does not have one entry per tet");
    return finish("no tets");
  }
  CheckMeshOptions check;
  check.check_delaunay = result->constrained_delaunay;  // not after the default improvement
  const auto issues = check_mesh(mesh, *plc, result->boundary_face_facets, check);
  for (std::size_t k = 0; k < issues.size() && k < 5; ++k)
    expect(false, std::string("check_mesh: ") + to_string(issues[k].kind) + ": " + issues[k].message);

  std::size_t unmet = 0, unmet_small = 0;
  double worst_elsewhere = 0.0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& v = mesh.tets[t];
    const double ratio = radius_edge_ratio(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]], mesh.points[v[3]]);
    if (ratio <= kBound) continue;
    ++unmet;
    if (small[t]) {
      ++unmet_small;
    } else if (ratio > worst_elsewhere) {
      worst_elsewhere = ratio;
    }
  }
  const std::size_t tets = mesh.tets.size();
  const std::size_t elsewhere = unmet - unmet_small;
  char line[300];
  std::snprintf(line, sizeof line,
                "%zu tets, above %.3f: %zu at small angles, %zu elsewhere (%.3f%% of the tets, worst ratio %.2f), %s",
                tets, kBound, unmet_small, elsewhere, 100.0 * static_cast<double>(elsewhere) / static_cast<double>(tets),
                worst_elsewhere, to_string(result->status));

  // MeshStats also counts tets above a volume bound (example.poly's regions have some).
  expect(stats.unmet_tets >= unmet, "unmet_tets " + std::to_string(stats.unmet_tets) + ", but " +
                                        std::to_string(unmet) + " tets above the bound");
  expect(stats.unmet_tets_at_small_angles >= unmet_small, "unmet_tets_at_small_angles " +
                                                              std::to_string(stats.unmet_tets_at_small_angles) +
                                                              ", but " + std::to_string(unmet_small) +
                                                              " tets at small angles above the bound");
  expect((result->status == MeshStatus::Partial) == (stats.unmet_tets > 0), "status Partial must mean unmet tets");
  expect(!stats.budget_exhausted, "budget exhausted without a budget");
  expect(elsewhere * 1000 <= tets, std::to_string(elsewhere) + " of " + std::to_string(tets) +
                                       " tets away from small angles above the bound: more than 0.1%");
  if (input.max_elsewhere >= 0)
    expect(elsewhere <= static_cast<std::size_t>(input.max_elsewhere),
           std::to_string(elsewhere) + " tets away from small angles above the bound, more than " +
               std::to_string(input.max_elsewhere));
  return finish(line);
}

// A run that has not answered after this long is taken as a hang (not a performance
// target: the slowest input here takes a small fraction of it on a loaded 2-core machine).
constexpr int kHangSeconds = 400;

class Tet3dRadiusEdgeCorpus : public ::testing::TestWithParam<RadiusEdgeInput> {};

TEST_P(Tet3dRadiusEdgeCorpus, MeetsTheBoundAwayFromSmallAngles) {
  const RadiusEdgeInput& input = GetParam();
  ASSERT_TRUE(std::filesystem::exists(input_path(input))) << input.path;
  const test::ForkedRun run = test::run_forked([&] { return mesh_and_check(input); }, kHangSeconds);
  test::report_findings(input.path, run, kHangSeconds);
}

INSTANTIATE_TEST_SUITE_P(Corpus, Tet3dRadiusEdgeCorpus, ::testing::ValuesIn(test::inputs_without_known_failure(kInputs)),
                         test::corpus_test_name<RadiusEdgeInput>);

}  // namespace
}  // namespace delmesh
