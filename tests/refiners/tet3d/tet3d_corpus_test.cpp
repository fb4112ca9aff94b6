// Corpus regression for 3D refinement (issue 5 item 9): every input of the public corpus
// (corpus_dir(): the surfaces the MANIFEST marks closed, manifold and oriented, the ones
// the importer repairs, poly3d/*.smesh and step/*) is imported and meshed with the default
// MeshOptions, and the result is judged independently of the refiner's bookkeeping:
//   * check_mesh finds nothing: positive tets forming a complex, every boundary face in its
//     input facet with the facet's marker, every input facet covered and every input
//     segment a chain of edges, constrained Delaunay (unless the default improvement
//     changed the mesh: MeshResult::constrained_delaunay), the PLC's volume conserved;
//   * every facet marker and every region of the input is in the mesh, and nothing else;
//   * the status and the counters agree: Partial exactly when tets are left above the
//     bound or the Steiner budget ran out, the unmet count equals the tets a separate
//     quality report finds above the bound, the stage list and Steiner counts add up;
//   * where the input has no small angles (the surfaces item 9 lists), at most 0.1% of
//     the tets may exceed the bound.
// Surfaces with defects the importer does not repair are refused with an error naming
// the defect; the CAD file that is an open set of faces is refused as open.
// Inputs that take minutes today at the default bound carry a Steiner budget
// (MeshOptions::max_steiner_points, the documented last resort), listed below with the
// reason, so the suite stays within a few minutes on two cores; with a budget the result
// must still be valid and is Partial when the budget runs out. Each input runs in a child
// process: a hang (no result after kHangSeconds) or a crash is a failure of that input.
// Inputs on which the mesher is known to fail today are listed with the failure
// and left out of the run; fixing one means deleting its
// reason so the input runs again. Inputs beyond conforming boundary recovery (features
// nearly touching over a long stretch, refiners/tet3d/recovery_limit.h) must end with the
// recovery error that names the features, in bounded time.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <ostream>
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

struct CorpusInput {
  const char* path;  ///< relative to corpus_dir()
  /// Refused inputs: text the import error must contain; nullptr: meshed.
  const char* defect = nullptr;
  /// Steiner budget (negative: none) and why it is there.
  long long budget = -1;
  const char* budget_reason = "";
  /// No small input angles (issue 5 item 9): at most 0.1% of the tets above the bound.
  bool no_small_angles = false;
  /// A known defect of the mesher on this input (nullptr: none). Such inputs stay in the
  /// list (so the list covers the corpus) but are not run until the defect is fixed; each
  /// reason names what fails.
  const char* known_failure = nullptr;
  /// Inputs beyond conforming facet recovery (refiners/tet3d/recovery_limit.h): the run
  /// is redone on a CCDT (MeshStats::ccdt.after_conforming); every other input meshes
  /// with the conforming recovery.
  bool ccdt_rerun = false;
};

// Budgets: inputs whose full default-options run took over a minute of wall time (15-22 s
// of CPU on a loaded machine, still refining when stopped) in the survey of this test's
// introduction; 20000 Steiner points take a few seconds.
constexpr long long kSlowBudget = 20000;
constexpr const char* kSlow = "slow today: a full default run takes over a minute";

// Beyond conforming facet recovery, meshed on a CCDT (mesh_plc.h, FacetRecovery::Auto).
// trimesh-box-sides: the conforming recovery's bound (134656) is reached between facet 0
// (CAD face 1, the base plate's top) and facet 228 (CAD face 133, a side wall tab's
// bottom), 0.051 apart over 25 units: the model's 0.0508 clearance under six 25.4-unit
// tabs (docs/MESHING.md, "Boundary recovery that cannot finish"). On the CCDT the gap is exterior
// space and needs no vertex: 91897 vertices, 284874 tets, 4 above radius-edge 2 (1 at
// a small angle; 325 before a constrained split's insertion radius counted only vertices
// of domain tets, boundary_split.h), 10.7 s of meshing with the conforming attempt
// (`delmesh mesh --check`, default options, 13.3 s of CPU).
constexpr bool kCcdtRerun = true;

const CorpusInput kInputs[] = {
    // Surfaces marked closed, manifold and oriented in MANIFEST.md.
    {"surface/cgal-anchor.off", nullptr, kSlowBudget, kSlow},
    {"surface/cgal-armadillo.off", nullptr, kSlowBudget, kSlow},
    {"surface/cgal-bear.off", nullptr, kSlowBudget, kSlow, true},
    {"surface/cgal-bunny00.off", nullptr, kSlowBudget, kSlow, true},
    {"surface/cgal-couplingdown.off", nullptr, kSlowBudget, kSlow},
    {"surface/cgal-dino.off", nullptr, kSlowBudget, kSlow},
    {"surface/cgal-fandisk.off", nullptr, -1, "", true},
    {"surface/cgal-homer.off"},
    {"surface/cgal-knot2.off"},
    {"surface/cgal-sphere.off", nullptr, -1, "", true},
    // Stopped at the recovery bound (20416) between its needle's arms 7-6 and 7-9 (0.00043
    // degrees) until those split on a common grid (refiners/tet3d/plc_preparation.h), then
    // between facets 0-1-2 and 0-2-6 (15.8 degrees) until recovery's subfacet splits
    // respected the field floor: 96781 tets, 15864 above the bound, all at small angles
    // (3290 + 3540 recovery Steiner points; 3.8 s of CPU with --check).
    {"surface/cgal-step.off"},
    {"surface/cgal-u-arch.off", nullptr, kSlowBudget, kSlow},
    {"surface/gmsh-netgen-hinge.stl", nullptr, kSlowBudget, kSlow},
    {"surface/occt-sh2.stl", nullptr, kSlowBudget, kSlow},
    {"surface/occt-tr12j.stl"},
    {"surface/trimesh-busted.stl", nullptr, -1, "", true},
    {"surface/trimesh-tray-bottom.stl", nullptr, kSlowBudget, kSlow},
    // Surfaces the importer repairs (reoriented facets, a collapsed triangle dropped).
    {"surface/cgal-boeing.off", nullptr, kSlowBudget, kSlow},
    {"surface/cgal-schonhardt.off"},
    {"surface/occt-propeller.stl", nullptr, kSlowBudget, kSlow},
    // Surfaces refused, with the defect named.
    {"surface/cgal-nonmanifold-facegraph.off", "non-manifold"},
    {"surface/gmsh-aorta.stl", "open: boundary edges"},
    {"surface/occt-motor.stl", "non-manifold"},
    {"surface/occt-video-part.stl", "open: boundary edges"},
    {"surface/pocc-bottle.stl", "open: boundary edges"},
    {"surface/trimesh-soup.stl", "open: boundary edges"},
    {"surface/trimesh-teapot.stl", "open: boundary edges"},
    // TetGen PLCs.
    {"poly3d/td-slit-1.smesh"},
    {"poly3d/td-slit-10.smesh"},
    {"poly3d/td-slit-5.smesh"},
    {"poly3d/td-spike-10-4.smesh"},
    {"poly3d/td-spike-5-7.smesh"},
    {"poly3d/td-wedge-10.smesh"},
    {"poly3d/td-wedge-5.smesh"},
    // STEP models (tessellated by the importer).
    {"step/as-anc101.stp", nullptr, kSlowBudget, kSlow},
    {"step/as-capot-40mm.stp"},
    {"step/as-mechanism.stp"},
    {"step/as-tie-rod.step"},
    {"step/as-wavy-cube.stp"},
    {"step/gmsh-angled.step"},
    {"step/gmsh-as1-tu-203.stp"},
    {"step/gmsh-boundary-colors.stp"},
    {"step/gmsh-cube-fillet.stp", "open"},
    {"step/gmsh-fusee-rocket.stp"},
    {"step/gmsh-laufrad-impeller.stp", nullptr, kSlowBudget, kSlow},
    {"step/gmsh-mambo-s34.step", nullptr, kSlowBudget, kSlow},
    {"step/gmsh-part.step"},
    {"step/gmsh-periodic-u.step", nullptr, kSlowBudget, kSlow},
    {"step/gmsh-t106-blade.step"},
    {"step/gmsh-t20-data.step", nullptr, kSlowBudget, kSlow},
    // Meshes since surface refinement refines its fuselage faces beside their poles
    // (importers/step/surface_refinement.cpp: encroachment judged in 3D too); a full default
    // run gave 344477 tets, 803 above the bound, in 58 s of wall-clock time (27 s here);
    // after the importer's node moves (importers/step/surface_smoothing.h) 337791 tets, 196
    // above the bound, in 46 s of wall-clock time (8.9 s of CPU; delmesh mesh --stats); after
    // the importer's pole rules took its wing-tip faces to 20 degrees 338859 tets, 27 above
    // the bound, all at small input angles, in 11 s of wall-clock time (7.1 s of CPU); after
    // the importer's lifted points took faces 1, 2 and 9 to 20 degrees 340766 tets, 26 above
    // the bound, all at small input angles, in 8.8 s of wall-clock time (8.0 s of CPU with
    // --check).
    {"step/gmsh-wing-fuselage.step", nullptr, kSlowBudget, kSlow},
    {"step/gmsh-wrenchnut.stp", nullptr, kSlowBudget, kSlow},
    {"step/occt-linkrods.step", nullptr, kSlowBudget, kSlow},
    {"step/occt-screw.step", nullptr, kSlowBudget, kSlow},
    {"step/pocc-eight-cyl.stp"},
    {"step/pocc-io1-ug-214.stp"},
    {"step/pocc-multi-shape-root.stp"},
    {"step/trimesh-box-sides.step", nullptr, -1, "", false, nullptr, kCcdtRerun},
};

void PrintTo(const CorpusInput& input, std::ostream* os) { *os << input.path; }

TEST(Tet3dCorpus, ListCoversTheCorpus) {
  std::set<std::string> listed;
  for (const CorpusInput& input : kInputs) listed.insert(input.path);
  for (const char* folder : {"surface", "poly3d", "step"}) {
    for (const auto& entry : std::filesystem::directory_iterator(test::corpus_dir() / folder)) {
      const std::string path = std::string(folder) + "/" + entry.path().filename().string();
      EXPECT_TRUE(listed.count(path)) << path << " is in the corpus but not in the mesh corpus test";
    }
  }
  for (const std::string& path : listed) EXPECT_TRUE(std::filesystem::exists(test::corpus_dir() / path)) << path;
}

/// Collects failed expectations of a run in a child process (GoogleTest's macros do not
/// cross fork()).
class Findings {
 public:
  void expect(bool ok, const std::string& what) {
    if (!ok) failures.push_back(what);
  }
  std::string summary;
  std::vector<std::string> failures;
};

/// Imports and meshes one input and checks the result; nothing here decides by time.
Findings mesh_and_check(const CorpusInput& input) {
  Findings out;
  const auto path = test::corpus_dir() / input.path;
  auto plc = import_file(path, ImportOptions{});
  if (input.defect) {
    out.summary = "refused";
    out.expect(!plc.has_value(), "should be refused: " + std::string(input.defect));
    if (!plc) {
      out.expect(plc.error().message.find(input.defect) != std::string::npos,
                 "the error does not name the defect '" + std::string(input.defect) + "': " + plc.error().describe());
      out.expect(plc.error().describe().find(path.filename().string()) != std::string::npos,
                 "the error does not name the file: " + plc.error().describe());
    }
    return out;
  }
  if (!plc) {
    out.expect(false, "import failed: " + plc.error().describe());
    return out;
  }
  MeshOptions options;
  options.max_steiner_points = input.budget;
  const auto start = std::chrono::steady_clock::now();
  auto result = mesh_plc(*plc, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result) {
    out.expect(false, "mesh_plc failed: " + result.error().describe());
    return out;
  }
  const TetraMesh& mesh = result->mesh;
  const MeshStats& stats = result->stats;
  out.expect(stats.ccdt.after_conforming == input.ccdt_rerun,
             input.ccdt_rerun ? "the conforming facet recovery should stop and the run be redone on a CCDT"
                              : "redone on a CCDT: the conforming facet recovery stopped at its bound");
  const TetQualityReport quality = tet_quality_report(mesh, options.max_radius_edge);
  char line[256];
  std::snprintf(line, sizeof line, "%zu tets %zu points %.2f s, max radius-edge %.3f, unmet %zu (%zu at small angles), %s%s",
                mesh.tets.size(), mesh.points.size(), seconds, quality.max_radius_edge, stats.unmet_tets,
                stats.unmet_tets_at_small_angles, to_string(result->status), stats.budget_exhausted ? " (budget)" : "");
  out.summary = line;

  // Valid and conforming.
  if (mesh.tets.empty()) {
    out.expect(false, "no tets");
    return out;
  }
  CheckMeshOptions check;
  check.check_delaunay = result->constrained_delaunay;  // not after the default improvement
  const auto issues = check_mesh(mesh, *plc, result->boundary_face_facets, check);
  for (std::size_t k = 0; k < issues.size() && k < 10; ++k) {
    out.expect(false, std::string("check_mesh: ") + to_string(issues[k].kind) + ": " + issues[k].message);
  }

  // Markers and regions of the input, and only those.
  std::set<int> input_markers, mesh_markers;
  for (const Plc::Facet& facet : plc->facets) input_markers.insert(facet.marker);
  mesh_markers.insert(mesh.boundary_markers.begin(), mesh.boundary_markers.end());
  out.expect(mesh_markers == input_markers, "the boundary markers differ from the input's facet markers");
  const std::set<int> mesh_regions(mesh.tet_regions.begin(), mesh.tet_regions.end());
  if (!plc->regions.empty()) {
    std::set<int> input_regions;
    for (const Plc::Region& region : plc->regions) input_regions.insert(region.id);
    out.expect(mesh_regions == input_regions, "the tet regions differ from the input's regions");
  } else {
    out.expect(mesh_regions.size() == 1, "one region expected, got " + std::to_string(mesh_regions.size()));
  }

  // Status and counters.
  out.expect(stats.input_vertices == plc->points.size(), "input_vertices differs from the PLC");
  out.expect(stats.input_facets == plc->facets.size(), "input_facets differs from the PLC");
  out.expect(stats.unmet_tets_at_small_angles <= stats.unmet_tets, "more unmet tets at small angles than unmet tets");
  out.expect((result->status == MeshStatus::Partial) == (stats.unmet_tets > 0 || stats.budget_exhausted),
             "status Partial must mean unmet tets or an exhausted budget");
  out.expect(stats.unmet_tets == quality.above_radius_edge,
             "unmet_tets " + std::to_string(stats.unmet_tets) + " but " + std::to_string(quality.above_radius_edge) +
                 " tets above the bound");
  out.expect(input.budget >= 0 || !stats.budget_exhausted, "budget exhausted without a budget");
  // The automatic bound on the quality stage (refiners/tet3d/quality_bound.h) is a last
  // resort: no corpus input reaches it.
  out.expect(!stats.quality_bound_reached, "the automatic bound on quality Steiner points was reached");
  std::vector<std::string> stages;
  std::size_t steiner = 0;
  for (const MeshStageStats& stage : stats.stages) {
    stages.push_back(stage.name);
    steiner += stage.steiner_points;
  }
  const std::vector<std::string> expected_stages{"delaunay", "segments", "facets", "domain", "quality"};
  out.expect(stages.size() >= 5 && std::equal(expected_stages.begin(), expected_stages.end(), stages.begin()),
             "stages are not delaunay, segments, facets, domain, quality");
  out.expect(mesh.points.size() <= plc->points.size() + steiner, "more points than input points plus Steiner points");
  if (input.no_small_angles && !stats.budget_exhausted) {
    out.expect(stats.unmet_tets * 1000 <= mesh.tets.size(), "more than 0.1% of the tets unmet");
  }
  return out;
}

// A run that has not finished after this long is taken as a hang (the slowest input that
// works takes about a quarter of it on a loaded 2-core machine); it guards against never
// terminating and is not a performance target.
constexpr int kHangSeconds = 400;

class Tet3dCorpusMesh : public ::testing::TestWithParam<CorpusInput> {};

// Each input runs in a child process, so that a hang or crash fails this input alone, as
// a finding, instead of stalling or killing the suite.
TEST_P(Tet3dCorpusMesh, MeshesValidOrIsRefused) {
  const CorpusInput& input = GetParam();
  ASSERT_TRUE(std::filesystem::exists(test::corpus_dir() / input.path)) << input.path;
  const test::ForkedRun run = test::run_forked(
      [&] {
        const Findings findings = mesh_and_check(input);
        std::string text = findings.summary + "\n";
        for (const std::string& failure : findings.failures) text += failure + "\n";
        return text;
      },
      kHangSeconds);
  test::report_findings(input.path, run, kHangSeconds);
}

INSTANTIATE_TEST_SUITE_P(Corpus, Tet3dCorpusMesh, ::testing::ValuesIn(test::inputs_without_known_failure(kInputs)),
                         test::corpus_test_name<CorpusInput>);

}  // namespace
}  // namespace delmesh
