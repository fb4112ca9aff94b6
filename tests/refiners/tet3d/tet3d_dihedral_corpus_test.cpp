// Dihedral window on the corpus (issue 6 item 4): every clean input of the public corpus
// (surfaces the importer accepts, TetGen PLCs, STEP models) and TetGen's example.poly is
// meshed with a 20 / 150 degree dihedral target, MeshOptions::min_dihedral_deg and
// max_dihedral_deg, default radius-edge bound, and the result is recounted independently
// of the refiner's bookkeeping:
//   * valid and conforming (check_mesh without the Delaunay test: sliver removal trades
//     it away);
//   * MeshResult::tet_at_small_angle has one entry per tet, and MeshStats agrees with a
//     recount on the output mesh: tets touching small input angles, tets outside the
//     window in either group, unmet tets (outside the window or above the radius-edge
//     bound) and of those the ones touching small angles; Partial exactly when tets are
//     unmet;
//   * inputs without small input angles (kNoSmallAngles: TetGen's example.poly): at most
//     0.01% of all tets outside [20, 150];
//   * STEP models (kStep), whose tessellation delmesh controls but whose CAD corners and
//     edges do make small input angles: at most 0.01% of all tets outside [20, 150] away
//     from small input angles (the tets touching one are counted and printed; the lead's
//     target for this issue item: "<= 0.01% outside [20,150] (unforced)");
//   * every other input (kOthers): no tet that does not touch a small input angle
//     (refiners/tet3d/small_angles.h) has a dihedral angle outside [20, 150]; the tets
//     touching one are counted and printed.
// The corpus surfaces without small angles (cgal-bear, cgal-bunny00, cgal-fandisk,
// cgal-sphere, trimesh-busted) are large and are measured by bench/parts/slivers.sh.
// Inputs on which the target is not met today are listed with the measured failure
// (survey of this test's introduction, on a loaded 2-core machine) and not run; fixing
// one means deleting its reason. No input runs with a Steiner budget: with the corpus
// test's 20000 point budget the slow surfaces stop with some 40% of their tets outside
// the window, which says nothing about the window. Each input runs in a child process
// with a hang guard.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "importers/import.h"
#include "refiners/tet3d/mesh_plc.h"
#include "tests/support/corpus_inputs.h"
#include "tests/support/forked_run.h"
#include "tests/support/test_paths.h"
#include "toolkit/check/check_mesh.h"
#include "toolkit/quality/tet_quality.h"

namespace delmesh {
namespace {

constexpr double kLow = 20.0, kHigh = 150.0;

enum class Group { kNoSmallAngles, kStep, kOthers };

struct DihedralInput {
  const char* path;  ///< relative to corpus_dir(), or "data:" + relative to test_data_dir()
  Group group;
  /// Measured failure of the target today (nullptr: none); listed inputs are not run.
  const char* known_failure = nullptr;
};

// Measured failures (default radius-edge bound 2, window [20, 150]; "elsewhere" counts
// tets touching no small input angle; "boundary" the ones among them with all four
// vertices on the boundary, i.e. flat tets between nearly coplanar facets or across a thin
// wedge; "N before": the same run before the improvement pass balanced its objective
// between the window's ends and gained its boundary steps, sliver_improvement.h).
const DihedralInput kInputs[] = {
    {"data:mesh/tetgen_example.poly", Group::kNoSmallAngles},
    // Surfaces the importer accepts (closed, or repaired).
    {"surface/cgal-schonhardt.off", Group::kOthers},
    // 313895 tets, 409 outside [20, 150], all at small angles, since subsegment splits judged
    // after the polish that follows them (deferred_split.h; bench_dihedral_classify). Before, as
    // a known failure: 313885 tets, 413 outside [20, 150]: 412 at small angles, 1 elsewhere (the
    // cap in a 162 degree fold) since the joint moves' ascent keeps any rule its shortest step
    // broke as a direction and the trade rounds' joint moves with a neighbour
    // (bench_dihedral_classify); 313885 tets, 414 outside [20, 150]: 412 at small angles, 2
    // elsewhere with the joint moves along a radius-edge bound and the trade rounds' own tries
    // (main at c262af0, bench_dihedral_classify); 313893 tets, 418 outside [20, 150]: 417 at
    // small angles, 1 elsewhere with the refinement changes of main at 930acea and the polish's
    // joint moves and flip trades (bench_dihedral_classify); before the refinement changes and
    // the flip trades 313472 tets, 393 outside [20, 150]: 390 at small angles, 3 elsewhere; 4.9 s
    // of user time on a loaded machine (main at ae163f1, before the polish's joint moves: 313475
    // tets, 399 and 4; main at 3296913, before the improvement rounds, the polish's trades and
    // insertions on subfacets, the narrow-facet floors and split_inside: 313256 tets, 456 and 13;
    // main at 84cb640, before the polish's holds of bound breakers by angles and edge removal at
    // holding tets: 313295 tets, 493 and 32; main at 2efc1b9, before the polish's relaxed holds
    // and insertions: 313244 tets, 492 and 44; 564 and 37 before the polish's small-angle holds,
    // 60 elsewhere before small_angles.h rule (e), 973 before the improvement pass changes and
    // rules (c) by vertex and (d))
    {"surface/cgal-homer.off", Group::kOthers},
    // 277623 tets, 5 outside [20, 150], all at small angles, 2.8 s of CPU, since the polish's
    // vertex insertions; 277617 tets, 1 elsewhere before (a subfacet with an interior vertex
    // at a local optimum, 17.9 to 19.7 degrees).
    {"surface/cgal-knot2.off", Group::kOthers},
    // 356868 tets, 1152 outside [20, 150], all at small angles, since subsegment splits judged
    // after the polish that follows them (deferred_split.h; bench_dihedral_classify). Before, as
    // a known failure: 356846 tets, 1174 outside [20, 150]: 1172 at small angles, 2 elsewhere
    // since the joint moves' ascent keeps any rule its shortest step broke as a direction and the
    // trade rounds' joint moves with a neighbour (bench_dihedral_classify); 356846 tets, 1171
    // outside [20, 150]: 1168 at small angles, 3 elsewhere with the joint moves along a radius-
    // edge bound and the trade rounds' own tries (main at c262af0, bench_dihedral_classify);
    // 356864 tets, 1160 outside [20, 150]: 1149 at small angles, 11 elsewhere with the refinement
    // changes of main at 930acea and the polish's joint moves and flip trades
    // (bench_dihedral_classify); before the refinement changes and the flip trades 355229 tets,
    // 1191 outside [20, 150]: 1181 at small angles, 10 elsewhere; 8.0 s of user time on a loaded
    // machine (main at ae163f1, before the polish's joint moves: 355235 tets, 1199 and 25; main
    // at 3296913, before the improvement rounds, the polish's trades and insertions on subfacets,
    // the narrow-facet floors and split_inside: 354334 tets, 1325 and 38; main at 84cb640, before
    // the polish's holds of bound breakers by angles and edge removal at holding tets: 354364
    // tets, 1469 and 68; main at 2efc1b9, before the polish's relaxed holds and insertions:
    // 354278 tets, 1483 and 84; 103 elsewhere before the polish's small-angle holds, 111 before
    // small_angles.h rule (e), 7464 before the improvement pass changes and rules (c) by vertex
    // and (d))
    {"surface/cgal-couplingdown.off", Group::kOthers},
    // 117339 tets, 2093 outside [20, 150], all at small angles, since the joint moves' ascent
    // keeps any rule its shortest step broke as a direction and the trade rounds move a bad
    // tet's vertex jointly with a neighbour (main at 1efa86a: 117343 tets, 2095 outside and 3
    // elsewhere, at edges inside the domain or a facet; bench_dihedral_classify).
    {"surface/gmsh-netgen-hinge.stl", Group::kOthers},
    // 167391 tets, 8518 outside [20, 150], all at small angles, since the joint moves' ascent
    // keeps any rule its shortest step broke as a direction and the trade rounds move a bad
    // tet's vertex jointly with a neighbour (main at 1efa86a: 167408 tets, 8511 outside and 5
    // elsewhere; 9 at 6829b7e, 38 at ae163f1, 134 at 3296913; bench_dihedral_classify).
    {"surface/cgal-anchor.off", Group::kOthers},
    // 1307886 tets, 83 outside [20, 150], all at small angles, since the joint moves keep a
    // tet at the radius-edge bound as a direction of their ascent (main at c262af0,
    // bench_dihedral_classify); 1 or 2 elsewhere before (1307896 tets, 85 outside at 930acea).
    {"surface/cgal-armadillo.off", Group::kOthers},
    // 261145 tets, 185 outside [20, 150], all at small angles, 3.9 s of user time on a loaded
    // machine, with the polish's joint moves (261147 and 186 on main at ae163f1 without
    // them); since the improvement rounds, the polish's trades and insertions on
    // subfacets, the narrow-facet floors and split_inside (main at 3296913: 261052 tets, 224
    // outside, 6 elsewhere; at 84cb640 269 and 11; at 2efc1b9 263 and 15; 187 elsewhere before the improvement pass
    // changes and small_angles.h rules (c) by vertex and (d)).
    {"surface/cgal-dino.off", Group::kOthers},
    {"surface/cgal-u-arch.off", Group::kOthers},
    // 547252 tets, 989 outside [20, 150], all at small angles, since the joint moves' ascent
    // keeps any rule its shortest step broke as a direction and the trade rounds move a bad
    // tet's vertex jointly with a neighbour (joint_move.h, sliver_improvement.cpp; main at
    // 1efa86a: 547253 tets, 990 and 2 elsewhere, bench_dihedral_classify).
    {"surface/occt-sh2.stl", Group::kOthers},
    // 69505 tets, none outside [20, 150], since the joint moves keep a tet at the radius-edge
    // bound as a direction of their ascent (joint_move.cpp); before, 69510 tets and 2
    // outside, elsewhere (the input has no small angles), each a subfacet with an interior
    // vertex at a local optimum, 17.93 and 19.22 degrees, the joint moves of the worst
    // edge's vertices stopped at their first step by a tet at radius-edge 1.998.
    {"surface/trimesh-tray-bottom.stl", Group::kOthers},
    // 167710 tets, 1642 outside [20, 150], all at small angles, since subsegment splits judged
    // after the polish that follows them (deferred_split.h; bench_dihedral_classify). Before, as
    // a known failure: 167661 tets, 1665 outside [20, 150]: 1661 at small angles, 4 elsewhere (in
    // rings of a subsegment whose angles no move changes) since the joint moves' ascent keeps any
    // rule its shortest step broke as a direction and the trade rounds' joint moves with a
    // neighbour (bench_dihedral_classify); 167680 tets, 1665 outside [20, 150]: 1660 at small
    // angles, 5 elsewhere with the joint moves along a radius-edge bound and the trade rounds'
    // own tries (main at c262af0, bench_dihedral_classify); 167680 tets, 1673 outside [20, 150]:
    // 1663 at small angles, 10 elsewhere with the refinement changes of main at 930acea and the
    // polish's joint moves and flip trades (bench_dihedral_classify); before the refinement
    // changes and the flip trades 167781 tets, 1602 outside [20, 150]: 1591 at small angles, 11
    // elsewhere (0.007%); 6.5 s of user time on a loaded machine (main at ae163f1, before the
    // polish's joint moves: 167772 tets, 1616 and 15; main at 3296913, before the improvement
    // rounds, the polish's trades and insertions on subfacets, the narrow-facet floors and
    // split_inside: 166847 tets, 1835 and 73; main at 84cb640, before the polish's holds of bound
    // breakers by angles and edge removal at holding tets: 166902 tets, 1912 and 104; 167232
    // tets, 1908 and 88 before boundary recovery's field floor; main at 2efc1b9, before the
    // polish's relaxed holds, flips, insertions and deletions: 167098 tets, 1910 and 138; 151
    // elsewhere before the polish's small-angle holds, 170 before small_angles.h rule (e), 2221
    // before the improvement pass changes and rules (c) by vertex and (d))
    {"surface/cgal-boeing.off", Group::kOthers},
    {"surface/occt-propeller.stl", Group::kOthers,
     "2182887 tets, 66243 outside [20, 150]: 66235 at small angles, 8 elsewhere (2 flat tets with four boundary "
     "vertices at (30.5, 369.5, 3.3), 5 with worst angles of 7.4 to 17.8 degrees at x = 0 to 0.4, y = +-17.2 to "
     "17.7, z = -89 to -103, 1 at (-324.9, 12.6, 18.4)); 9 elsewhere before the deferred splits at one tet alone "
     "(deferred_split.h); 311 s of CPU, 668 MB on a loaded machine (bench_dihedral_classify)"},
    // TetGen PLCs.
    {"poly3d/td-slit-10.smesh", Group::kOthers},
    {"poly3d/td-slit-5.smesh", Group::kOthers},
    // 19408 tets, 121 outside [20, 150], all at small angles, since the trade rounds make
    // their joint moves and flip trades where the polish's tries are spent
    // (sliver_improvement.cpp, trade_rounds): before, 120 at small angles and 1 elsewhere,
    // around the slit's 4 degree edge (x = 0.5, z = 0.5), 0.9 s of user time on a loaded
    // machine (19407 tets, 130 and 5 on main at ae163f1, before the polish's joint moves; 146
    // and 6 on main at 3296913, before the improvement rounds and the polish's trades; 19414
    // tets, 155 and 10 on main at 84cb640, before the polish's holds of bound breakers by
    // angles and edge removal at holding tets; 19402 tets, 160 and 19 before the polish's
    // relaxed holds, flips, insertions and deletions; 140 elsewhere before the improvement
    // pass changes and small_angles.h rule (c) by vertex).
    {"poly3d/td-slit-1.smesh", Group::kOthers},
    {"poly3d/td-spike-10-4.smesh", Group::kOthers},
    {"poly3d/td-spike-5-7.smesh", Group::kOthers},
    // 857 tets, 137 outside [20, 150], all at small angles (5 caps across the wedge counted
    // elsewhere while rule (c) of small_angles.h asked all four vertices in its zone).
    // 875 tets, 127 outside [20, 150], all at small angles (5 caps across the wedge counted
    // elsewhere while rule (c) of small_angles.h asked all four vertices in its zone).
    {"poly3d/td-wedge-10.smesh", Group::kOthers},
    // 2579 tets, 342 outside [20, 150], all at small angles (1 elsewhere while rule (c) of
    // small_angles.h asked all four vertices in its zone).
    // 2579 tets, 324 outside [20, 150], all at small angles (1 elsewhere before the improvement
    // pass's window-balanced objective and rule (c) of small_angles.h by vertex).
    {"poly3d/td-wedge-5.smesh", Group::kOthers},
    // STEP models (tessellated by the importer).
    {"step/as-mechanism.stp", Group::kStep},
    {"step/gmsh-boundary-colors.stp", Group::kStep},
    {"step/pocc-io1-ug-214.stp", Group::kStep},
    // 37559 tets, 60 outside [20, 150]: 59 at small angles, 1 elsewhere (0.0027%), since the
    // improvement rounds, the polish's trades and the narrow-facet floors; 35620 tets, 69 and
    // 2 with the trades alone, 77 and 1 on main at 3296913 (by delmesh mesh). Before:
    // 35619 tets, 88 outside [20, 150]: 86 at small angles, 2 elsewhere (0.0056%); 5 elsewhere
    // (0.014%) before small_angles.h rule (e), three of them flat tets on CAD face 23 beside
    // the 1.05 degree corners of wall faces 19 and 20 at (56.93, +-7.94, 61.92); 108 before
    // rule (d).
    {"step/gmsh-part.step", Group::kStep},
    {"step/as-wavy-cube.stp", Group::kStep},
    {"step/pocc-eight-cyl.stp", Group::kStep},
    // 207128 tets, 6 outside [20, 150]: 4 at small angles, 2 elsewhere (0.0010%), 4.4 s of
    // CPU; 23 elsewhere (0.0111%) before the improvement pass's window-balanced objective.
    {"step/pocc-multi-shape-root.stp", Group::kStep},
    {"step/gmsh-angled.step", Group::kStep},
    // 260241 tets, 49 outside [20, 150]: 43 at small angles, 6 elsewhere (0.0023%), 7.2 s of
    // CPU; 28 elsewhere (0.011%) before the improvement pass changes and small_angles.h rule (d).
    {"step/as-capot-40mm.stp", Group::kStep},
    // 552349 tets, 34 outside [20, 150]: 31 at small angles, 3 elsewhere (0.0005%), the same
    // before and after the polish's holds of bound breakers by angles and edge removal at
    // holding tets (main at 84cb640); 552350
    // tets, 31 and 3 since the polish's relaxed holds and vertex insertions (552336 tets, 31
    // and 5 on main at 2efc1b9).
    // Before:
    // 577906 tets, 843 outside [20, 150]: 808 at small angles, 35 elsewhere (0.0061%), 11.3 s
    // of CPU; 50 elsewhere (0.0087%) before small_angles.h rule (e); 58 of 579820 elsewhere
    // (0.0100%, one over the bound) before the importer's lifted points, 1900 of 603974 before
    // its balancing splits and node moves, the improvement pass changes and rule (d).
    {"step/gmsh-fusee-rocket.stp", Group::kStep},
    {"step/as-anc101.stp", Group::kStep},
    {"step/as-tie-rod.step", Group::kStep},
    {"step/gmsh-as1-tu-203.stp", Group::kStep},
    // 377577 tets, 24 outside [20, 150]: 11 at small angles, 13 elsewhere (0.0034%), the same
    // before and after the polish's holds of bound breakers by angles and edge removal at
    // holding tets (main at 84cb640); 381693
    // tets, 11 and 14 since the polish's relaxed holds and vertex insertions (381656 tets, 11
    // and 22 on main at 2efc1b9).
    // Before:
    // 381656 tets, 32 outside [20, 150]: 7 at small angles, 25 elsewhere (0.0066%), 9.2 s of
    // CPU; 44 elsewhere (0.0118%) before the improvement pass changes.
    {"step/gmsh-laufrad-impeller.stp", Group::kStep},
    {"step/gmsh-mambo-s34.step", Group::kStep},
    // 195947 tets, 21 outside [20, 150]: 12 at small angles, 9 elsewhere (0.0046%), the same
    // before and after the polish's holds of bound breakers by angles and edge removal at
    // holding tets (main at 84cb640); 196082
    // tets, 12 and 8 since the polish's relaxed holds and vertex insertions (196044 tets, 12
    // and 16 on main at 2efc1b9).
    // Before:
    // 194978 tets, 28 outside [20, 150]: 12 at small angles, 16 elsewhere (0.0082%), 4.9 s of
    // CPU; 45 elsewhere (0.023%) before the improvement pass changes.
    {"step/gmsh-periodic-u.step", Group::kStep},
    // 79054 tets, 116 outside [20, 150]: 114 at small angles, 2 elsewhere (0.0025%), since the
    // polish's holds of bound breakers by angles and edge removal at holding tets (79055
    // tets, 122 and 2 on main at 84cb640, since the
    // polish's relaxed holds and vertex insertions; 79048 tets, 121 and 3 on main at 2efc1b9).
    // Before:
    // 79267 tets, 138 outside [20, 150], all at small angles, 1.2 s of CPU; 1 elsewhere
    // (0.0013%) before small_angles.h rule (e); 9 of 77975 elsewhere (0.0115%) before the
    // importer's lifted points, 152 before rule (d) and the improvement pass changes.
    {"step/gmsh-t20-data.step", Group::kStep},
    {"step/gmsh-wrenchnut.stp", Group::kStep},
    {"step/occt-linkrods.step", Group::kStep},
    {"step/occt-screw.step", Group::kStep},
    // 38588 tets, 4 outside [20, 150], all at small angles, 0.4 s of meshing CPU, since the
    // importer blends extrusion face 3's edge offsets into it (offset_blend.h: no lip 0.01
    // above the cap at the trailing edge, 20.02 degrees); 99014 tets, 60 elsewhere (0.061%)
    // before (10386 at small angles, nearly all at that lip; 69 elsewhere before
    // small_angles.h rule (e), 66 of them flat tets between the lip and the cap, B-spline
    // face 8); 270368 tets, 338 elsewhere (0.125%) while extrusion faces 3 and 4 kept
    // BRepMesh's needles.
    {"step/gmsh-t106-blade.step", Group::kStep},
    // 389599 tets, 16 outside [20, 150]: 14 at small angles, 2 elsewhere (0.0005%), since the
    // polish's holds of bound breakers by angles and edge removal at holding tets (17, 15 and
    // 2 on main at 84cb640); 389831
    // tets, 17 and 2 since the polish's vertex deletions (389837 tets, 17 and 4 on main at
    // 2efc1b9). Before:
    // 392569 tets, 10 outside [20, 150]: 7 at small angles, 3 elsewhere (0.0008%), 9.4 s of
    // CPU, since the importer's lifted points took faces 1, 2 and 9 to 20 degrees; 7 of 391468
    // elsewhere (0.0018%) before them, 120 elsewhere (0.030%) before the importer's node moves
    // and pole rules.
    {"step/gmsh-wing-fuselage.step", Group::kStep},
    // Meshed on the CCDT (conforming facet recovery stops at its bound at the 0.051 gap under
    // the tabs; tet3d_corpus_test.cpp): 313580 tets, 9 outside [20, 150], all elsewhere and
    // all with four vertices on the boundary (0.0029%), since the improvement rounds
    // (improvement_rounds.h); 313573 tets, 15 outside, 1 at small angles and 14 elsewhere
    // (0.0048% of all outside), smallest angle 17.7 degrees, 15 CPU s before.
    {"step/trimesh-box-sides.step", Group::kStep},
    // 106711 tets, 16496 outside [20, 150], all at small angles, 17 s of CPU on a loaded machine
    // (bench_dihedral_classify, main at 155d165).
    {"surface/cgal-step.off", Group::kOthers},
    {"surface/occt-tr12j.stl", Group::kOthers,
     "1577079 tets, 5724 outside [20, 150]: 5720 at small angles, 4 elsewhere (3 tets with four boundary vertices, "
     "worst angles 16.2 to 19.7 degrees, at (160.8, -136.8, 5) and at edges of domain angle 181.32 and 270 degrees; "
     "1 interior tet, 15.4 to 158.0 degrees, radius-edge 8.76, at (-142.36, -159.08, 247.88) beside the needle of "
     "degenerate input triangles at (-142.5, -159, 247.5)); 5 elsewhere before the deferred splits at one tet alone "
     "(deferred_split.h); 67 s of CPU, 468 MB on a loaded machine (bench_dihedral_classify)"},
};

void PrintTo(const DihedralInput& input, std::ostream* os) { *os << input.path; }

// The corpus inputs not in kInputs: the surfaces without small angles (benchmarked) and
// the files the importer refuses (tet3d_corpus_test.cpp checks the refusals).
const char* const kElsewhere[] = {
    "surface/cgal-bear.off",          "surface/cgal-bunny00.off",    "surface/cgal-fandisk.off",
    "surface/cgal-sphere.off",        "surface/trimesh-busted.stl",  "surface/cgal-nonmanifold-facegraph.off",
    "surface/gmsh-aorta.stl",         "surface/occt-motor.stl",      "surface/occt-video-part.stl",
    "surface/pocc-bottle.stl",        "surface/trimesh-soup.stl",    "surface/trimesh-teapot.stl",
    "step/gmsh-cube-fillet.stp",
};

TEST(Tet3dDihedralCorpus, ListCoversTheCleanCorpus) {
  std::set<std::string> listed(std::begin(kElsewhere), std::end(kElsewhere));
  for (const DihedralInput& input : kInputs) listed.insert(input.path);
  for (const char* folder : {"surface", "poly3d", "step"}) {
    for (const auto& entry : std::filesystem::directory_iterator(test::corpus_dir() / folder)) {
      const std::string path = std::string(folder) + "/" + entry.path().filename().string();
      EXPECT_TRUE(listed.count(path)) << path << " is in the corpus but not in the dihedral corpus test";
    }
  }
}

std::filesystem::path input_path(const DihedralInput& input) { return test::corpus_input_path(input.path); }

/// Imports and meshes one input; returns the summary line, then one line per failure.
std::string mesh_and_check(const DihedralInput& input) {
  std::vector<std::string> failures;
  auto expect = [&](bool ok, const std::string& what) {
    if (!ok) failures.push_back(what);
  };
  auto finish = [&](const std::string& summary) {
    std::string text = summary + "\n";
    for (const std::string& f : failures) text += f + "\n";
    return text;
  };
  const auto path = input_path(input);
  auto plc = import_file(path, ImportOptions{});
  if (!plc) {
    expect(false, "import failed: " + plc.error().describe());
    return finish("import failed");
  }
  MeshOptions options;
  options.min_dihedral_deg = kLow;
  options.max_dihedral_deg = kHigh;
  // TetGen's meaning of -pq on example.poly: its region volume bounds need -a. (With them
  // and the window, or at radius-edge 1.414, refinement does not finish today: hundreds
  // of thousands of Steiner points within minutes.)
  options.region_max_volume = false;
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
  check.check_delaunay = false;
  const auto issues = check_mesh(mesh, *plc, result->boundary_face_facets, check);
  for (std::size_t k = 0; k < issues.size() && k < 5; ++k)
    expect(false, std::string("check_mesh: ") + to_string(issues[k].kind) + ": " + issues[k].message);

  // Recount on the output; of the tets outside the window away from small angles, the ones
  // with a vertex on the boundary and with all four there (flat tets across nearly
  // coplanar facets) are counted for the summary.
  std::vector<char> on_boundary(mesh.points.size(), 0);
  for (const auto& face : mesh.boundary_faces)
    for (const std::uint32_t v : face) on_boundary[v] = 1;
  std::size_t touching = 0, outside_small = 0, outside_elsewhere = 0, unmet = 0, unmet_small = 0;
  std::size_t elsewhere_at_boundary = 0, elsewhere_all_boundary = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& v = mesh.tets[t];
    const Vec3 &a = mesh.points[v[0]], &b = mesh.points[v[1]], &c = mesh.points[v[2]], &d = mesh.points[v[3]];
    const bool at_small = small[t] != 0;
    bool outside = false;
    for (const double angle : dihedral_angles_deg(a, b, c, d)) outside = outside || !(angle >= kLow && angle <= kHigh);
    const bool skinny = !(radius_edge_ratio(a, b, c, d) <= options.max_radius_edge);
    touching += at_small;
    if (outside) ++(at_small ? outside_small : outside_elsewhere);
    if (outside && !at_small) {
      const int boundary_vertices = on_boundary[v[0]] + on_boundary[v[1]] + on_boundary[v[2]] + on_boundary[v[3]];
      elsewhere_at_boundary += boundary_vertices > 0;
      elsewhere_all_boundary += boundary_vertices == 4;
    }
    if (outside || skinny) {
      ++unmet;
      unmet_small += at_small;
    }
  }
  const std::size_t tets = mesh.tets.size();
  const std::size_t outside = outside_small + outside_elsewhere;
  char line[400];
  std::snprintf(line, sizeof line,
                "%zu tets, touching small angles %zu (%.2f%%), outside [20,150]: %zu there, %zu elsewhere (%zu with a "
                "boundary vertex, %zu all four), %.4f%% of all, unmet %zu, %s",
                tets, touching, 100.0 * static_cast<double>(touching) / static_cast<double>(tets), outside_small,
                outside_elsewhere, elsewhere_at_boundary, elsewhere_all_boundary,
                100.0 * static_cast<double>(outside) / static_cast<double>(tets), unmet, to_string(result->status));

  expect(stats.tets_at_small_angles == touching,
         "tets_at_small_angles " + std::to_string(stats.tets_at_small_angles) + ", recount " + std::to_string(touching));
  expect(stats.outside_dihedral_at_small_angles == outside_small,
         "outside_dihedral_at_small_angles " + std::to_string(stats.outside_dihedral_at_small_angles) + ", recount " +
             std::to_string(outside_small));
  expect(stats.outside_dihedral_elsewhere == outside_elsewhere,
         "outside_dihedral_elsewhere " + std::to_string(stats.outside_dihedral_elsewhere) + ", recount " +
             std::to_string(outside_elsewhere));
  expect(stats.unmet_tets == unmet,
         "unmet_tets " + std::to_string(stats.unmet_tets) + ", recount " + std::to_string(unmet));
  expect(stats.unmet_tets_at_small_angles == unmet_small, "unmet_tets_at_small_angles " +
                                                              std::to_string(stats.unmet_tets_at_small_angles) +
                                                              ", recount " + std::to_string(unmet_small));
  expect((result->status == MeshStatus::Partial) == (unmet > 0), "status Partial must mean unmet tets");
  expect(!stats.budget_exhausted, "budget exhausted without a budget");

  if (input.group == Group::kNoSmallAngles) {
    expect(outside * 10000 <= tets,
           std::to_string(outside) + " of " + std::to_string(tets) + " tets outside [20, 150]: more than 0.01%");
  } else if (input.group == Group::kStep) {
    expect(outside_elsewhere * 10000 <= tets, std::to_string(outside_elsewhere) + " of " + std::to_string(tets) +
                                                  " tets outside [20, 150] away from small input angles: more "
                                                  "than 0.01%");
  } else {
    expect(outside_elsewhere == 0, std::to_string(outside_elsewhere) +
                                       " tets that touch no small input angle have a dihedral angle outside [20, 150]");
  }
  return finish(line);
}

// A run that has not answered after this long is taken as a hang (not a performance
// target: the slowest input here takes a fraction of it on a loaded 2-core machine).
constexpr int kHangSeconds = 400;

class Tet3dDihedralCorpus : public ::testing::TestWithParam<DihedralInput> {};

TEST_P(Tet3dDihedralCorpus, MeetsTheWindowAwayFromSmallAngles) {
  const DihedralInput& input = GetParam();
  ASSERT_TRUE(std::filesystem::exists(input_path(input))) << input.path;
  const test::ForkedRun run = test::run_forked([&] { return mesh_and_check(input); }, kHangSeconds);
  test::report_findings(input.path, run, kHangSeconds);
}

INSTANTIATE_TEST_SUITE_P(Corpus, Tet3dDihedralCorpus, ::testing::ValuesIn(test::inputs_without_known_failure(kInputs)),
                         test::corpus_test_name<DihedralInput>);

}  // namespace
}  // namespace delmesh
